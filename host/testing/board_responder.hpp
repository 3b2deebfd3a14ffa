#pragma once
// A protocol responder that answers like a board (protocol/SPEC.md §2, §3, §7.3), for
// testing host code before the real board code (firmware/core with boards/sim or
// boards/linux) is there to answer. It keeps a running and a stored configuration,
// runs the update state machine with the checks of §7.3 and records what it was sent.
// It plays no codes and has no clock servo: it is a conversation partner, not a board.
#include <array>
#include <cstdint>
#include <optional>
#include <vector>

#include "tetrapulse/protocol/bytes.hpp"
#include "tetrapulse/protocol/hw_model.hpp"
#include "tetrapulse/protocol/message.hpp"

namespace tetrapulse::host::testing {

struct ResponderIdentity {
  protocol::HwModel hw_model = protocol::HwModel::kLinuxBoard;
  uint8_t hw_revision = 1;
  uint32_t fw_version = 0x01000000;  // 1.0.0
  std::array<uint8_t, protocol::kSerialSize> serial{0x54, 0x50, 0x00, 0x00, 0x00, 0x00,
                                                    0x00, 0x00, 0x00, 0x00, 0x00, 0x01};
  uint32_t capabilities = 0;
  std::array<uint32_t, 2> slot_base{0, 0};  // load_address an image needs in slot 0 / 1
  uint32_t slot_capacity = 1u << 20;        // bytes an update may write
  uint8_t active_slot = 0;
  uint8_t node_id = 1;  // CAN node id of the initial configuration
};

class BoardResponder {
 public:
  explicit BoardResponder(ResponderIdentity identity = {});

  // The encoded answer to one received message, following SPEC.md §3 for input that does not
  // decode; nothing for time sync, responses and inputs under 3 bytes. `now_ns` is the
  // responder's clock (uptime, Sync reception).
  std::optional<std::vector<uint8_t>> answer(protocol::ByteView received, int64_t now_ns);
  // The answer to one decoded message.
  std::optional<protocol::Message> handle(const protocol::Message& received, int64_t now_ns);

  const ResponderIdentity& identity() const { return identity_; }
  const protocol::Config& running_config() const { return running_; }
  const protocol::Config& stored_config() const { return stored_; }
  protocol::UpdateState update_state() const { return update_state_; }
  // The image of the last update that verified, as written.
  const std::vector<uint8_t>& installed_image() const { return installed_; }
  uint32_t reboots() const { return reboots_; }
  uint32_t chunks_written() const { return chunks_written_; }
  uint32_t chunk_repeats() const { return chunk_repeats_; }
  protocol::IdentifyPattern identify_pattern() const { return identify_; }
  // Sync samples: (sync_seq, reception on the responder's clock, FollowUp tx_time_ns).
  struct SyncSample {
    uint16_t sync_seq = 0;
    int64_t received_ns = 0;
    int64_t tx_time_ns = 0;
  };
  const std::vector<SyncSample>& sync_samples() const { return sync_samples_; }
  uint32_t malformed() const { return malformed_; }

  // Makes SetConfig fail with not_supported (a board that cannot play a configuration).
  void refuse_configs(bool refuse) { refuse_configs_ = refuse; }

 private:
  protocol::Message ack(const protocol::Message& request, uint32_t value = 0) const;
  protocol::Message refuse(const protocol::Message& request, protocol::Error error, uint16_t detail = 0) const;
  protocol::Message update_begin(const protocol::Message& m, const protocol::UpdateBegin& begin);
  protocol::Message update_chunk(const protocol::Message& m, const protocol::UpdateChunk& chunk);
  protocol::Message update_verify(const protocol::Message& m);
  protocol::Message reboot(const protocol::Message& m, int64_t now_ns);
  protocol::Info info(int64_t now_ns) const;
  protocol::StatusReport status(int64_t now_ns) const;

  ResponderIdentity identity_;
  protocol::Config running_;
  protocol::Config stored_;
  protocol::IdentifyPattern identify_ = protocol::IdentifyPattern::kStop;
  protocol::UpdateState update_state_ = protocol::UpdateState::kIdle;
  protocol::UpdateBegin update_;
  std::vector<uint8_t> image_;  // being received
  uint32_t next_offset_ = 0;
  uint32_t last_chunk_offset_ = 0;
  uint16_t last_chunk_length_ = 0;
  std::vector<uint8_t> installed_;
  uint32_t installed_version_ = 0;
  uint32_t reboots_ = 0;
  uint32_t chunks_written_ = 0;
  uint32_t chunk_repeats_ = 0;
  int64_t boot_ns_ = 0;
  bool booted_ = false;
  std::optional<std::pair<uint16_t, int64_t>> last_sync_;
  std::vector<SyncSample> sync_samples_;
  uint32_t malformed_ = 0;
  protocol::Error last_error_ = protocol::Error::kNone;
  bool refuse_configs_ = false;
};

}  // namespace tetrapulse::host::testing
