#include "tetrapulse/sim_board/sim_board.hpp"

#include <cmath>

#include "tetrapulse/fw/boot/boot_slot.hpp"
#include "tetrapulse/fw/boot/boot_state.hpp"
#include "tetrapulse/fw/storage/config_store.hpp"
#include "tetrapulse/fw/storage/record_store.hpp"
#include "tetrapulse/protocol/version.hpp"
#include "tetrapulse/sim_board/sim_image.hpp"

namespace tetrapulse::sim_board {

using protocol::ByteView;

std::vector<fw::FlashRegion> sim_flash_sectors() {
  return {{0x0000, 0x1000}, {0x1000, 0x1000}, {0x2000, 0x2000}, {0x4000, 0x2000}, {0x6000, 0x2000}, {0x8000, 0x2000}};
}

fw::FlashLayout sim_flash_layout() {
  fw::FlashLayout layout;
  layout.record_sectors = {fw::FlashRegion{0x0000, 0x1000}, fw::FlashRegion{0x1000, 0x1000}};
  layout.slots[0] = fw::SlotLayout{fw::FlashRegion{0x2000, 0x4000}, 0};
  layout.slots[1] = fw::SlotLayout{fw::FlashRegion{0x6000, 0x4000}, 0};
  layout.vector_alignment = protocol::kMinVectorAlignment;
  return layout;
}

namespace {

class SimLocalClock final : public fw::LocalClock {
 public:
  explicit SimLocalClock(const SimBoard& board) : board_(board) {}

 private:
  fw::Tick do_now() const override { return board_.tick(); }
  uint32_t do_tick_hz() const override { return board_.clock().tick_hz(); }
  const SimBoard& board_;
};

class SimSystem final : public fw::SystemControl {
 public:
  explicit SimSystem(const SimBoardOptions& o) : options_(o) {}
  std::optional<protocol::RebootMode> requested;

 private:
  void do_reboot(protocol::RebootMode mode) override { requested = mode; }
  std::array<uint8_t, protocol::kSerialSize> do_unique_id() const override { return options_.serial; }
  protocol::HwModel do_hw_model() const override { return protocol::HwModel::kSimulatedBoard; }
  uint8_t do_hw_revision() const override { return options_.hw_revision; }
  uint32_t do_bootloader_version() const override { return protocol::pack_version(1, 0, 0); }
  void do_kick_watchdog() override {}
  uint16_t do_watchdog_resets() const override { return 0; }
  const SimBoardOptions& options_;
};

class SimSyncInput final : public fw::SyncInput {
 public:
  bool enabled = false;
  protocol::GpioEdge edge = protocol::GpioEdge::kRising;

 private:
  void do_configure(bool on, protocol::GpioEdge e) override {
    enabled = on;
    edge = e;
  }
};

class SimCanBus final : public fw::CanBus {
 public:
  std::vector<protocol::CanFrame> sent;
  protocol::CanNodeFilters filters{};
  uint16_t errors = 0;
  bool bus_off = false;

 private:
  protocol::Status do_send(const protocol::CanFrame& frame) override {
    // Bus-off: the controller takes no frames off the board until it has recovered.
    if (bus_off) return protocol::Error::kBusy;
    sent.push_back(frame);
    return {};
  }
  void do_set_filters(const protocol::CanNodeFilters& f) override { filters = f; }
  uint16_t do_error_count() const override { return errors; }
  bool do_bus_off() const override { return bus_off; }
};

class SimSerial final : public fw::SerialPort {
 public:
  std::vector<uint8_t> sent;

 private:
  protocol::Status do_write(ByteView bytes) override {
    sent.insert(sent.end(), bytes.begin(), bytes.end());
    return {};
  }
};

class SimUsb final : public fw::UsbPipe {
 public:
  std::vector<std::vector<uint8_t>> sent;

 private:
  protocol::Status do_send_bulk(ByteView transfer) override {
    sent.emplace_back(transfer.begin(), transfer.end());
    return {};
  }
};

}  // namespace

class SimBoard::Hardware {
 public:
  explicit Hardware(const SimBoard& board) : clock(board), system(board.options()) {}
  SimLocalClock clock;
  SimSystem system;
  SimSyncInput sync_input;
  SimCanBus can;
  SimSerial serial;
  SimUsb usb;
};

SimBoard::SimBoard(const SimBoardOptions& options)
    : options_(options),
      now_(options.power_on_ns),
      last_poll_(options.power_on_ns),
      clock_(options.tick_hz, options.clock_ppm) {
  clock_.restart(now_);
  hw_ = std::make_unique<Hardware>(*this);
  flash_ = std::make_unique<SimFlash>(sim_flash_sectors());
  leds_ = std::make_unique<SimLedDriver>(hw_->clock, options.lead_ticks, options.led_queue_depth,
                                         options.led_full_scale_ma);
  leds_->set_rig_now(static_cast<long double>(now_));
  // The factory: an image in slot 0, confirmed, and a configuration with the node id.
  SimImageSpec image;
  image.fw_version = options.fw_version;
  flash_->load(sim_flash_layout().slots[0].region.address, make_sim_image(image));
  fw::RecordStore store(*flash_, sim_flash_layout().record_sectors);
  store.open();
  fw::BootState state;
  state.confirmed_slot = 0;
  fw::save_boot_state(store, state);
  protocol::Config config = protocol::default_config();
  config.node_id = options.node_id;
  fw::save_config(store, config);
  boot(false);
}

SimBoard::~SimBoard() = default;

fw::Tick SimBoard::tick() const { return clock_.tick_at(now_); }

void SimBoard::set_now(int64_t rig_ns) {
  if (rig_ns > now_) now_ = rig_ns;
  leds_->set_rig_now(static_cast<long double>(now_));
}

void SimBoard::boot(bool stay_in_bootloader) {
  firmware_.reset();
  bootloader_.reset();
  can_link_.reset();
  uart_link_.reset();
  usb_link_.reset();
  clock_.restart(now_);
  leds_->reset(static_cast<long double>(now_), 0);
  hw_->sync_input.enabled = false;
  ++boots_;

  const fw::FlashLayout layout = sim_flash_layout();
  const fw::BoardModel model{protocol::HwModel::kSimulatedBoard, options_.hw_revision};
  const fw::BootChoice choice = fw::choose_boot_slot(*flash_, layout, model, stay_in_bootloader);
  active_slot_ = choice.boot ? choice.slot : fw::kNoSlot;
  running_version_ = choice.boot ? choice.header.fw_version : 0;
  if (!choice.boot) {
    bootloader_ = std::make_unique<SimBootloader>(*flash_, layout, model, hw_->can, hw_->clock,
                                                  sim_bootloader_identity(model, options_.node_id));
    last_poll_ = now_;
    return;
  }

  can_link_.emplace(hw_->can, options_.tick_hz, options_.node_id);
  uart_link_.emplace(hw_->serial);
  usb_link_.emplace(hw_->usb);
  fw::FirmwareParts parts;
  parts.clock = &hw_->clock;
  parts.leds = leds_.get();
  parts.flash = flash_.get();
  parts.system = &hw_->system;
  parts.sync_input = options_.gpio_sync_input ? &hw_->sync_input : nullptr;
  parts.can = options_.can ? &*can_link_ : nullptr;
  parts.layout = layout;
  parts.board.fw_version = choice.header.fw_version;
  parts.board.active_slot = choice.slot;
  parts.board.min_bit_period_ns = protocol::kMinBitPeriodNs;
  parts.board.capabilities = protocol::capability::kUsb | protocol::capability::kUart |
                             protocol::capability::kCurrentLimit | protocol::capability::kCanUpdate;
  if (options_.can) parts.board.capabilities |= protocol::capability::kCan;
  if (options_.gpio_sync_input) parts.board.capabilities |= protocol::capability::kGpioSyncInput;
  if (options_.two_level) parts.board.capabilities |= protocol::capability::kTwoLevel;
  firmware_.emplace(parts);
  firmware_->board().set_message_links(&*uart_link_, &*usb_link_);
  firmware_->start();
  last_poll_ = now_;
}

void SimBoard::after_event() {
  if (bootloader_) {
    const fw::Tick ms = tick() / (clock_.tick_hz() / 1000);
    if (const auto mode = bootloader_->poll(static_cast<uint32_t>(ms))) boot(*mode == protocol::RebootMode::kBootloader);
    return;
  }
  if (hw_->system.requested) {
    const protocol::RebootMode mode = *hw_->system.requested;
    hw_->system.requested.reset();
    boot(mode == protocol::RebootMode::kBootloader);
    return;
  }
  if (firmware_) firmware_->poll();
}

void SimBoard::advance_to(int64_t rig_ns) {
  while (true) {
    const auto due = leds_->next_due();
    long double led_at = 0;
    bool led = false;
    if (due) {
      led_at = clock_.rig_at_tick(due->second);
      led = true;
    }
    const int64_t poll_at = last_poll_ + options_.poll_interval_ns;
    const int64_t led_ns = led ? static_cast<int64_t>(std::ceil(led_at)) : INT64_MAX;
    const int64_t next = led_ns < poll_at ? led_ns : poll_at;
    if (next > rig_ns) break;
    set_now(next);
    if (led && led_ns <= poll_at) {
      leds_->apply_next(due->first, led_at);
    } else {
      last_poll_ = next;
    }
    after_event();
  }
  set_now(rig_ns);
}

void SimBoard::sync_edge(int64_t rig_ns) {
  advance_to(rig_ns);
  if (!firmware_ || !hw_->sync_input.enabled) return;
  firmware_->on_sync_edge(tick());
  after_event();
}

void SimBoard::can_frame(const protocol::CanFrame& frame, int64_t rig_ns) {
  advance_to(rig_ns);
  if (!options_.can || (!firmware_ && !bootloader_)) return;
  const protocol::CanNodeFilters& f = hw_->can.filters;
  if (!protocol::can_filter_matches(f.addressed, frame.id) && !protocol::can_filter_matches(f.broadcast, frame.id)) {
    return;
  }
  if (bootloader_) {
    bootloader_->can_link().on_frame(frame, tick(), bootloader_->commands());
  } else {
    can_link_->on_frame(frame, tick(), *firmware_);
  }
  after_event();
}

void SimBoard::usb_bulk(ByteView transfer, int64_t rig_ns) {
  advance_to(rig_ns);
  if (!firmware_) return;
  usb_link_->on_bulk_transfer(transfer, tick(), *firmware_);
  after_event();
}

void SimBoard::usb_control(ByteView message, int64_t rig_ns) {
  advance_to(rig_ns);
  if (!firmware_) return;
  usb_link_->on_control_message(message, tick(), *firmware_);
  after_event();
}

void SimBoard::uart_bytes(ByteView bytes, int64_t rig_ns) {
  advance_to(rig_ns);
  if (!firmware_) return;
  uart_link_->on_bytes(bytes, tick(), *firmware_);
  after_event();
}

std::vector<uint8_t> SimBoard::usb_message_in() {
  if (!usb_link_) return {};
  uint8_t buf[protocol::kMaxMessageSize];
  const protocol::Result<size_t> n = usb_link_->take_control_response(buf, sizeof(buf));
  if (!n) return {};
  return std::vector<uint8_t>(buf, buf + *n);
}

std::vector<protocol::CanFrame> SimBoard::take_can_frames() {
  std::vector<protocol::CanFrame> out;
  out.swap(hw_->can.sent);
  return out;
}

std::vector<std::vector<uint8_t>> SimBoard::take_usb_bulk() {
  std::vector<std::vector<uint8_t>> out;
  out.swap(hw_->usb.sent);
  return out;
}

std::vector<uint8_t> SimBoard::take_uart_bytes() {
  std::vector<uint8_t> out;
  out.swap(hw_->serial.sent);
  return out;
}

void SimBoard::set_clock_ppm(double ppm) { clock_.set_drift(now_, ppm); }

void SimBoard::can_controller_error(bool bus_off) {
  if (hw_->can.errors != UINT16_MAX) ++hw_->can.errors;
  hw_->can.bus_off = bus_off;
}

void SimBoard::power_cycle() {
  flash_->restore_power();
  reset();
}

void SimBoard::reset() {
  hw_->system.requested.reset();
  boot(false);
}

protocol::StatusReport SimBoard::status() const {
  if (!firmware_) return protocol::StatusReport{};
  return firmware_->board().status(tick());
}

}  // namespace tetrapulse::sim_board
