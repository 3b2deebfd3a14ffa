#include "tetrapulse/protocol/can_transfer_receiver.hpp"

#include "tetrapulse/protocol/crc.hpp"

namespace tetrapulse::protocol {
namespace {

constexpr size_t kBufferSize = kMaxMessageSize + kCanTransferCrcSize;

// now - then without signed overflow, whatever the caller's timestamps are.
int64_t elapsed(int64_t now, int64_t then) {
  return static_cast<int64_t>(static_cast<uint64_t>(now) - static_cast<uint64_t>(then));
}

bool same_bytes(const uint8_t* a, const uint8_t* b, size_t n) {
  for (size_t i = 0; i < n; ++i) {
    if (a[i] != b[i]) return false;
  }
  return true;
}

}  // namespace

Error can_fault_error(CanFault fault) {
  switch (fault) {
    case CanFault::kNone: return Error::kNone;
    case CanFault::kBadIdentifier: return Error::kBadValue;
    case CanFault::kTooLong:
    case CanFault::kBadLength: return Error::kBadLength;
    case CanFault::kBadCrc: return Error::kBadCrc;
    case CanFault::kNoFreeSession: return Error::kBusy;
    case CanFault::kTimedOut: return Error::kTimeout;
    case CanFault::kBadFrameSize:
    case CanFault::kMissingStart:
    case CanFault::kWrongToggle:
    case CanFault::kTransferIdChanged:
    case CanFault::kRestarted:
    case CanFault::kShortFrame:
    case CanFault::kTypeMismatch: return Error::kBadFraming;
  }
  return Error::kBadFraming;
}

const char* can_fault_name(CanFault fault) {
  switch (fault) {
    case CanFault::kNone: return "none";
    case CanFault::kBadIdentifier: return "bad_identifier";
    case CanFault::kBadFrameSize: return "bad_frame_size";
    case CanFault::kMissingStart: return "missing_start";
    case CanFault::kWrongToggle: return "wrong_toggle";
    case CanFault::kTransferIdChanged: return "transfer_id_changed";
    case CanFault::kRestarted: return "restarted";
    case CanFault::kShortFrame: return "short_frame";
    case CanFault::kTooLong: return "too_long";
    case CanFault::kBadLength: return "bad_length";
    case CanFault::kBadCrc: return "bad_crc";
    case CanFault::kTypeMismatch: return "type_mismatch";
    case CanFault::kNoFreeSession: return "no_free_session";
    case CanFault::kTimedOut: return "timed_out";
  }
  return "unknown_fault";
}

void CanTransferReceiver::count(CanFault fault) {
  const auto i = static_cast<size_t>(fault);
  if (fault != CanFault::kNone && i < kCanFaultCount) ++stats_.faults[i];
}

bool CanTransferReceiver::expired(const CanReceiveSession& s, int64_t now_ns) const {
  return elapsed(now_ns, s.last_ns) > timeout_ns_;
}

CanReceiveSession* CanTransferReceiver::find(uint8_t source, uint8_t type, uint8_t destination) {
  for (size_t i = 0; i < session_count_; ++i) {
    CanReceiveSession& s = sessions_[i];
    if (s.state != CanReceiveSession::State::kEmpty && s.source == source && s.type == type &&
        s.destination == destination) {
      return &s;
    }
  }
  return nullptr;
}

// An empty session, else the one idle longest among finished and timed-out ones.
CanReceiveSession* CanTransferReceiver::allocate(int64_t now_ns) {
  CanReceiveSession* victim = nullptr;
  for (size_t i = 0; i < session_count_; ++i) {
    CanReceiveSession& s = sessions_[i];
    if (s.state == CanReceiveSession::State::kEmpty) return &s;
    const bool reusable = s.state == CanReceiveSession::State::kDone || expired(s, now_ns);
    if (reusable && (victim == nullptr || elapsed(s.last_ns, victim->last_ns) < 0)) victim = &s;
  }
  if (victim != nullptr && victim->state == CanReceiveSession::State::kInProgress) {
    count(CanFault::kTimedOut);
  }
  return victim;
}

CanReceiveOutcome CanTransferReceiver::drop(CanReceiveSession* session, CanFault fault) {
  if (session != nullptr) session->state = CanReceiveSession::State::kEmpty;
  count(fault);
  CanReceiveOutcome out;
  out.verdict = CanFrameVerdict::kDropped;
  out.fault = fault;
  return out;
}

CanReceiveOutcome CanTransferReceiver::accept(const CanFrame& frame, int64_t timestamp_ns) {
  using State = CanReceiveSession::State;
  ++stats_.frames;
  if (frame.size == 0 || frame.size > kCanFrameDataSize) return drop(nullptr, CanFault::kBadFrameSize);
  const Result<CanId> id = unpack_can_id(frame.id);
  if (!id) return drop(nullptr, CanFault::kBadIdentifier);

  const CanTail tail = decode_can_tail(frame.data[frame.size - 1]);
  const uint8_t* payload = frame.data;
  const size_t payload_size = frame.size - 1u;

  CanFault displaced = CanFault::kNone;
  CanReceiveSession* s = find(id->source, id->type, id->destination);
  if (s != nullptr && expired(*s, timestamp_ns)) {
    if (s->state == State::kInProgress) displaced = CanFault::kTimedOut;
    s->state = State::kEmpty;
    s = nullptr;
  }

  // A CAN controller retransmits a frame that lost its acknowledgement late, so a
  // receiver can see it twice; an exact repeat of the previous frame is ignored.
  if (s != nullptr && frame.data[frame.size - 1] == s->last_tail &&
      payload_size == s->last_payload_size &&
      same_bytes(payload, s->buffer + s->size - s->last_payload_size, payload_size)) {
    ++stats_.duplicates;
    CanReceiveOutcome out;
    out.verdict = CanFrameVerdict::kDuplicate;
    return out;
  }

  if (tail.start) {
    if (s != nullptr && s->state == State::kInProgress) {
      displaced = tail.transfer_id != s->transfer_id ? CanFault::kTransferIdChanged : CanFault::kRestarted;
      s->state = State::kEmpty;
    }
    count(displaced);
    if (!tail.toggle) return drop(s, CanFault::kWrongToggle);
    if (!tail.end && payload_size != kCanFramePayloadSize) return drop(s, CanFault::kShortFrame);
    if (tail.end && payload_size < 3) return drop(s, CanFault::kBadLength);
    if (tail.end && payload[1] != id->type) return drop(s, CanFault::kTypeMismatch);

    if (s == nullptr) s = allocate(timestamp_ns);
    if (s == nullptr && !tail.end) return drop(nullptr, CanFault::kNoFreeSession);

    CanReceiveOutcome out;
    out.fault = displaced;
    uint8_t* store = s != nullptr ? s->buffer : single_frame_;
    for (size_t i = 0; i < payload_size; ++i) store[i] = payload[i];
    if (s != nullptr) {
      s->state = tail.end ? State::kDone : State::kInProgress;
      s->priority = id->priority;
      s->type = id->type;
      s->destination = id->destination;
      s->source = id->source;
      s->transfer_id = tail.transfer_id;
      s->next_toggle = false;
      s->last_tail = frame.data[frame.size - 1];
      s->last_payload_size = static_cast<uint8_t>(payload_size);
      s->size = static_cast<uint16_t>(payload_size);
      s->first_ns = timestamp_ns;
      s->last_ns = timestamp_ns;
    }
    if (!tail.end) {
      out.verdict = CanFrameVerdict::kPending;
      return out;
    }
    ++stats_.transfers;
    out.verdict = CanFrameVerdict::kComplete;
    out.transfer = CanReceivedTransfer{*id, tail.transfer_id, timestamp_ns, ByteView{store, payload_size}};
    return out;
  }

  // A continuation frame.
  if (s == nullptr || s->state != State::kInProgress) {
    count(displaced);
    return drop(nullptr, CanFault::kMissingStart);
  }
  if (tail.transfer_id != s->transfer_id) return drop(s, CanFault::kTransferIdChanged);
  if (tail.toggle != s->next_toggle) return drop(s, CanFault::kWrongToggle);
  if (!tail.end) {
    if (payload_size != kCanFramePayloadSize) return drop(s, CanFault::kShortFrame);
    // A last frame with at least one byte must still fit.
    if (s->size + payload_size + 1 > kBufferSize) return drop(s, CanFault::kTooLong);
  } else {
    if (payload_size == 0) return drop(s, CanFault::kBadFrameSize);
    if (s->size + payload_size > kBufferSize) return drop(s, CanFault::kTooLong);
  }

  for (size_t i = 0; i < payload_size; ++i) s->buffer[s->size + i] = payload[i];
  s->size = static_cast<uint16_t>(s->size + payload_size);
  s->next_toggle = !s->next_toggle;
  s->last_tail = frame.data[frame.size - 1];
  s->last_payload_size = static_cast<uint8_t>(payload_size);
  s->last_ns = timestamp_ns;
  if (!tail.end) return CanReceiveOutcome{};

  const size_t message_size = s->size - kCanTransferCrcSize;
  if (message_size <= kCanSingleFrameMaxMessage) return drop(s, CanFault::kBadLength);
  if (crc16_ccitt(s->buffer, s->size) != 0) return drop(s, CanFault::kBadCrc);
  if (s->buffer[1] != s->type) return drop(s, CanFault::kTypeMismatch);
  s->state = State::kDone;
  ++stats_.transfers;
  CanReceiveOutcome out;
  out.verdict = CanFrameVerdict::kComplete;
  out.transfer = CanReceivedTransfer{CanId{s->priority, s->type, s->destination, s->source},
                                     s->transfer_id, s->first_ns, ByteView{s->buffer, message_size}};
  return out;
}

size_t CanTransferReceiver::expire(int64_t now_ns) {
  size_t dropped = 0;
  for (size_t i = 0; i < session_count_; ++i) {
    CanReceiveSession& s = sessions_[i];
    if (s.state == CanReceiveSession::State::kEmpty || !expired(s, now_ns)) continue;
    if (s.state == CanReceiveSession::State::kInProgress) {
      count(CanFault::kTimedOut);
      ++dropped;
    }
    s.state = CanReceiveSession::State::kEmpty;
  }
  return dropped;
}

void CanTransferReceiver::reset() {
  for (size_t i = 0; i < session_count_; ++i) sessions_[i].state = CanReceiveSession::State::kEmpty;
}

}  // namespace tetrapulse::protocol
