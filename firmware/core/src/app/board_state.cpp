#include "tetrapulse/fw/app/board_state.hpp"

namespace tetrapulse::fw {

using protocol::capability::kCan;
using protocol::capability::kGpioSyncInput;
using protocol::capability::kTwoLevel;

BoardState::BoardState(const FirmwareParts& parts)
    : parts_(parts),
      store_(*parts.flash, parts.layout.record_sectors),
      player_(*parts.leds, led_log_),
      sync_(parts.clock->tick_hz()),
      update_(*parts.flash, parts.layout, store_, model(), parts.board.active_slot) {}

BoardModel BoardState::model() const { return BoardModel{parts_.system->hw_model(), parts_.system->hw_revision()}; }

protocol::Status BoardState::supports(const protocol::Config& config) const {
  const uint32_t caps = parts_.board.capabilities;
  if (config.bit_period_ns < parts_.board.min_bit_period_ns) return protocol::Error::kNotSupported;
  if (config.modulation == protocol::Modulation::kTwoLevel && (caps & kTwoLevel) == 0) {
    return protocol::Error::kNotSupported;
  }
  if (config.sync_source == protocol::SyncSource::kGpio &&
      ((caps & kGpioSyncInput) == 0 || parts_.sync_input == nullptr)) {
    return protocol::Error::kNotSupported;
  }
  if (config.sync_source == protocol::SyncSource::kCan && ((caps & kCan) == 0 || parts_.can == nullptr)) {
    return protocol::Error::kNotSupported;
  }
  return {};
}

uint16_t BoardState::duty_ceiling() const {
  return fw::duty_ceiling(config_.current_limit_ma, parts_.leds->full_scale_ma());
}

void BoardState::apply_config(const protocol::Config& config, Tick now) {
  config_ = config;
  player_.play(program_from_config(config, duty_ceiling()));
  sync_.configure(config, now);
  if (parts_.can != nullptr) parts_.can->set_node(config.node_id);
  if (parts_.sync_input != nullptr) {
    parts_.sync_input->configure(config.sync_source == protocol::SyncSource::kGpio, config.gpio_edge);
  }
}

uint64_t BoardState::uptime_ms(Tick now) const { return now / (parts_.clock->tick_hz() / 1000u); }

protocol::StatusReport BoardState::status(Tick now) const {
  protocol::StatusReport s;
  sync_.report(now, s);
  const uint32_t malformed = uint32_t{diagnostics_.rx_malformed} + (uart_ != nullptr ? uart_->transport_errors() : 0u) +
                             (usb_ != nullptr ? usb_->transport_errors() : 0u);
  s.rx_malformed = static_cast<uint16_t>(malformed > UINT16_MAX ? UINT16_MAX : malformed);
  if (parts_.can != nullptr) {
    const uint32_t errors = uint32_t{parts_.can->bus_errors()} + parts_.can->transport_errors();
    s.can_errors = static_cast<uint16_t>(errors > UINT16_MAX ? UINT16_MAX : errors);
    s.can_bus_off = parts_.can->bus_off() ? 1 : 0;
  }
  const uint32_t flash = uint32_t{diagnostics_.flash_errors} + update_.flash_errors();
  s.flash_errors = static_cast<uint16_t>(flash > UINT16_MAX ? UINT16_MAX : flash);
  s.watchdog_resets = parts_.system->watchdog_resets();
  s.last_error = diagnostics_.last_error;
  s.update_state = update_.state();
  s.uptime_ms = uptime_ms(now);
  return s;
}

}  // namespace tetrapulse::fw
