#include "tetrapulse/fw/app/firmware.hpp"

#include "tetrapulse/fw/boot/boot_state.hpp"
#include "tetrapulse/fw/storage/config_store.hpp"

namespace tetrapulse::fw {

Firmware::Firmware(const FirmwareParts& parts) : board_(parts), handler_(board_) {}

void Firmware::start() {
  const Tick now = board_.clock().now();
  started_at_ = now;
  if (!board_.store().open()) bump(board_.diagnostics().flash_errors);
  StoredConfig stored = load_config(board_.store());
  if (!board_.supports(stored.config)) stored.config = protocol::default_config();
  board_.apply_config(stored.config, now);
  // An image on trial (pending) confirms itself later, once healthy; any other start has
  // nothing to confirm.
  const protocol::Result<BootState> boot = load_boot_state(board_.store());
  confirmed_ = !boot || boot->pending_slot != board_.parts().board.active_slot;
  poll();
}

void Firmware::on_sync_edge(Tick captured) { board_.sync().on_edge(captured); }

void Firmware::confirm_if_healthy(Tick now) {
  if (confirmed_ || !board_.answered_request) return;
  const uint64_t ms = (now - started_at_) / (board_.clock().tick_hz() / 1000u);
  if (ms < kConfirmAfterMs) return;
  const protocol::Result<BootState> boot = load_boot_state(board_.store());
  if (!boot) {
    confirmed_ = true;
    return;
  }
  bool changed = false;
  const BootState next = confirm_slot(*boot, board_.parts().board.active_slot, &changed);
  if (!changed || save_boot_state(board_.store(), next)) {
    confirmed_ = true;
  } else {
    bump(board_.diagnostics().flash_errors);  // tried again on a later poll
  }
}

void Firmware::poll() {
  const Tick now = board_.clock().now();
  const ClockServo& servo = board_.sync().servo();
  board_.player().service(now, servo.mapping(), servo.generation());
  confirm_if_healthy(now);
  board_.system().kick_watchdog();
}

CommandReply Firmware::handle(protocol::ByteView message, Tick rx_tick, LinkKind link, uint8_t* out,
                              size_t capacity) {
  return handler_.handle(message, rx_tick, link, out, capacity);
}

void Firmware::do_on_message(const ReceivedMessage& message) {
  uint8_t out[protocol::kMaxMessageSize];
  const LinkKind kind = message.link != nullptr ? message.link->kind() : LinkKind::kUart;
  const CommandReply reply = handler_.handle(message.bytes, message.rx_tick, kind, out, sizeof(out));
  if (reply.size > 0 && message.link != nullptr) {
    message.link->send(message.reply, protocol::ByteView{out, reply.size});
  }
  if (reply.reboot) board_.system().reboot(reply.reboot_mode);
}

}  // namespace tetrapulse::fw
