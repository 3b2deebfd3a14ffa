// libFuzzer: a stream of CAN frames (fuzz_input.hpp) into a CanTransferReceiver.
// Every delivered message must be well formed and survive a send/receive round trip.
#include <cstdlib>

#include "fuzz_input.hpp"
#include "tetrapulse/protocol/can_transfer_receiver.hpp"
#include "tetrapulse/protocol/can_transfer_sender.hpp"

using namespace tetrapulse::protocol;

namespace {

void check(const CanReceivedTransfer& t) {
  const ByteView m = t.message;
  if (m.size < 3 || m.size > kMaxMessageSize || m[1] != t.id.type || t.transfer_id > 31) std::abort();
  // Segmenting it again and reassembling gives the same bytes.
  const CanTransferHeader header{t.id.priority, t.id.destination, t.id.source, t.transfer_id};
  CanReceiveSession session;
  CanTransferReceiver again(&session, 1);
  const size_t count = can_frame_count(m.size);
  for (size_t i = 0; i < count; ++i) {
    const Result<CanFrame> f = make_can_transfer_frame(header, m, i);
    if (!f) std::abort();
    const CanReceiveOutcome out = again.accept(*f, 0);
    if ((out.verdict == CanFrameVerdict::kComplete) != (i + 1 == count)) std::abort();
    if (i + 1 == count) {
      if (out.transfer.message.size != m.size) std::abort();
      for (size_t k = 0; k < m.size; ++k) {
        if (out.transfer.message[k] != m[k]) std::abort();
      }
    }
  }
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  CanReceiveSession sessions[3];
  CanTransferReceiver rx(sessions, 3, 100'000'000);
  size_t pos = 0;
  int64_t t = 0;
  CanFrame frame;
  int64_t dt = 0;
  while (fuzz::next_can_frame(data, size, &pos, &frame, &dt)) {
    t += dt;
    const CanReceiveOutcome out = rx.accept(frame, t);
    if (out.verdict == CanFrameVerdict::kDropped && out.fault == CanFault::kNone) std::abort();
    if (out.verdict == CanFrameVerdict::kComplete) check(out.transfer);
    if (dt == 15 * fuzz::kCanFuzzTimeStepNs) rx.expire(t);  // a long pause: sweep the sessions
  }
  return 0;
}
