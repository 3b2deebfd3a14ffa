#pragma once
// The requests a bootloader answers while it waits for an update (SPEC.md §7.3; on the
// STM32F405 over CAN, beside USB DFU): GetInfo, GetStatus, UpdateBegin, UpdateChunk,
// UpdateVerify, UpdateAbort (through the core's UpdateReceiver, into the slot
// update_target_slot() chose) and Reboot. Any other request is refused with
// not_supported; a message that fails to decode gets an ErrorResponse as SPEC.md §3 says;
// Sync, FollowUp and responses are ignored.
//
// In its Info the bootloader reports fw_version 0 and active_slot 0xFF: no application runs.
#include <array>
#include <cstdint>

#include "tetrapulse/fw/boot/update_receiver.hpp"
#include "tetrapulse/fw/clock/local_clock.hpp"
#include "tetrapulse/fw/links/can_link.hpp"
#include "tetrapulse/fw/links/message_link.hpp"
#include "tetrapulse/protocol/message.hpp"
#include "tetrapulse/protocol/response_messages.hpp"

namespace tetrapulse::fw {

struct BootloaderIdentity {
  protocol::HwModel hw_model = protocol::HwModel::kStm32f405Reference;
  uint8_t hw_revision = 0;
  uint32_t bootloader_version = 0;  // pack_version()
  std::array<uint8_t, protocol::kSerialSize> serial{};
  uint32_t capabilities = 0;        // protocol::capability bits of the bootloader
  uint8_t node_id = 1;              // the configured CAN node id
};

class BootloaderCommandHandler final : public MessageSink {
 public:
  // `can` (may be null) supplies the CAN counters of StatusReport.
  BootloaderCommandHandler(UpdateReceiver& update, const BootloaderIdentity& identity, const LocalClock& clock,
                           const CanLink* can);

  // One received message; the answer (if any) goes to `out` (kMaxMessageSize bytes suffice).
  size_t handle(protocol::ByteView message, uint8_t* out, size_t capacity);

  // A Reboot was acknowledged: the board resets into `reboot_mode()` once the Ack has left.
  bool reboot_requested() const { return reboot_requested_; }
  protocol::RebootMode reboot_mode() const { return reboot_mode_; }

 private:
  void do_on_message(const ReceivedMessage& message) override;
  protocol::Result<protocol::Body> execute(const protocol::Message& request, uint16_t* detail);
  protocol::StatusReport status() const;
  uint64_t uptime_ms() const;

  UpdateReceiver& update_;
  BootloaderIdentity identity_;
  const LocalClock& clock_;
  const CanLink* can_;
  uint16_t rx_malformed_ = 0;
  protocol::Error last_error_ = protocol::Error::kNone;
  bool reboot_requested_ = false;
  protocol::RebootMode reboot_mode_ = protocol::RebootMode::kApplication;
};

}  // namespace tetrapulse::fw
