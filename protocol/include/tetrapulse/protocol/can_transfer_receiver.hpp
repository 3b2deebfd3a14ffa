#pragma once
// Reassembles CAN transfers into messages (SPEC.md §4.4).
//
// Frames are taken one at a time with their receive timestamps (integer ns of any
// monotonic clock the caller chooses; for time sync, the local clock at the end of the
// frame's reception, SPEC.md §2.4). A completed message carries the first frame's timestamp.
// Sessions are keyed by (source, type, destination); the caller owns their storage.
// The receiver looks at every frame it is given: filter by destination first
// (can_node_filters) so that other nodes' traffic does not take sessions.
#include <cstddef>
#include <cstdint>

#include "tetrapulse/protocol/bytes.hpp"
#include "tetrapulse/protocol/can_frame.hpp"
#include "tetrapulse/protocol/can_id.hpp"
#include "tetrapulse/protocol/limits.hpp"
#include "tetrapulse/protocol/result.hpp"

namespace tetrapulse::protocol {

// Why a frame, or an unfinished transfer, was discarded.
enum class CanFault : uint8_t {
  kNone = 0,
  kBadIdentifier,      // not a tetrapulse identifier (over 29 bits, reserved bit set, source 255)
  kBadFrameSize,       // no tail byte, over 8 bytes, or a last frame with nothing but its tail
  kMissingStart,       // a continuation frame with no transfer in progress
  kWrongToggle,        // toggle not the expected one (a lost, repeated or reordered frame)
  kTransferIdChanged,  // a frame of another transfer-id before the current transfer ended
  kRestarted,          // a start frame with the current transfer-id before the transfer ended
  kShortFrame,         // a frame other than the last carries fewer than 8 bytes
  kTooLong,            // more than kMaxMessageSize message bytes
  kBadLength,          // message under 3 bytes, or a multi-frame transfer of a message that fits one frame
  kBadCrc,             // transfer CRC mismatch
  kTypeMismatch,       // message type byte differs from the identifier's type field
  kNoFreeSession,      // every session holds a transfer in progress
  kTimedOut,           // a transfer in progress saw no frame for longer than the timeout
};
constexpr size_t kCanFaultCount = 14;

// The protocol Error a fault corresponds to (for ErrorResponse and logs).
Error can_fault_error(CanFault fault);
const char* can_fault_name(CanFault fault);

enum class CanFrameVerdict : uint8_t {
  kPending,    // frame taken; its transfer continues
  kComplete,   // frame completed a transfer: see CanReceiveOutcome::transfer
  kDuplicate,  // an exact repeat of the session's previous frame; ignored
  kDropped,    // frame discarded: see CanReceiveOutcome::fault
};

struct CanReceivedTransfer {
  CanId id;                  // of the first frame
  uint8_t transfer_id = 0;
  int64_t timestamp_ns = 0;  // end of the first frame's reception
  ByteView message;          // valid until the receiver is called again
};

struct CanReceiveOutcome {
  CanFrameVerdict verdict = CanFrameVerdict::kPending;
  // kDropped: why this frame was discarded. kPending/kComplete: kNone, or the fault of
  // an unfinished transfer of the same session that this frame displaced
  // (kTimedOut, kTransferIdChanged, kRestarted).
  CanFault fault = CanFault::kNone;
  CanReceivedTransfer transfer;  // when verdict == kComplete
};

struct CanReceiverStats {
  uint32_t frames = 0;
  uint32_t transfers = 0;
  uint32_t duplicates = 0;
  uint32_t faults[kCanFaultCount] = {};  // indexed by CanFault
};

// Storage for one reassembly session; owned by the caller, used only by the receiver.
class CanReceiveSession {
 private:
  friend class CanTransferReceiver;
  enum class State : uint8_t { kEmpty, kInProgress, kDone };
  State state = State::kEmpty;
  uint8_t priority = 0;
  uint8_t type = 0;
  uint8_t destination = 0;
  uint8_t source = 0;
  uint8_t transfer_id = 0;
  bool next_toggle = true;
  uint8_t last_tail = 0;          // tail byte of the previous frame (duplicate detection)
  uint8_t last_payload_size = 0;  // its payload is the last bytes of `buffer`
  uint16_t size = 0;              // bytes in `buffer`: message, then the CRC once complete
  int64_t first_ns = 0;
  int64_t last_ns = 0;
  uint8_t buffer[kMaxMessageSize + kCanTransferCrcSize] = {};
};

class CanTransferReceiver {
 public:
  static constexpr int64_t kDefaultTimeoutNs = 1'000'000'000;

  // `timeout_ns` (> 0): an unfinished transfer is dropped once no frame of it has
  // arrived for longer than this; also how long a finished transfer's last frame is
  // remembered to recognise repeats.
  CanTransferReceiver(CanReceiveSession* sessions, size_t session_count,
                      int64_t timeout_ns = kDefaultTimeoutNs)
      : sessions_(sessions), session_count_(session_count), timeout_ns_(timeout_ns) {}

  CanReceiveOutcome accept(const CanFrame& frame, int64_t timestamp_ns);

  // Drops unfinished transfers idle for longer than the timeout at `now_ns`; returns
  // how many. Optional: accept() applies the same rule to the sessions it touches.
  size_t expire(int64_t now_ns);

  // Forgets every session.
  void reset();

  const CanReceiverStats& stats() const { return stats_; }

 private:
  CanReceiveSession* find(uint8_t source, uint8_t type, uint8_t destination);
  CanReceiveSession* allocate(int64_t now_ns);
  bool expired(const CanReceiveSession& s, int64_t now_ns) const;
  CanReceiveOutcome drop(CanReceiveSession* session, CanFault fault);
  void count(CanFault fault);

  CanReceiveSession* sessions_;
  size_t session_count_;
  int64_t timeout_ns_;
  CanReceiverStats stats_;
  uint8_t single_frame_[kCanFramePayloadSize] = {};  // a single-frame message when no session is free
};

}  // namespace tetrapulse::protocol
