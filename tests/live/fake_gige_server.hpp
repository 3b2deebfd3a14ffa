#pragma once
// A GigE Vision camera on one IPv4 address for the live tests, written here because
// Aravis' own ArvGvFakeCamera (0.8) ignores PACKETRESEND_CMD: with it, a lost GVSP
// packet always costs its frame. This one keeps Aravis' ArvFakeCamera as the
// register map and image source (GenICam XML, features, fill pattern) and does the
// transport itself: GVCP (read/write register and memory, packet resend) on UDP port
// 3956, GVSP frames (leader, payload packets, trailer) to the stream address the
// host wrote, every packet -- resent ones too -- lost with a given probability, and
// the last frames kept so that resend requests for them are answered. The GVCP
// capability register announces packet resend (unless disabled), as real cameras do.
//
// Opens sockets: run only inside tests/netns/isolated. Nothing is broadcast and
// discovery is not answered (the host opens the camera by address).
#include <arv.h>

#include <atomic>
#include <cstdint>
#include <optional>
#include <string>

namespace tetrapulse::live_test {

struct FakeGigeOptions {
  std::string address = "127.0.0.1";
  double lost_ratio = 0;        // probability that any one GVSP packet is not sent
  bool resend = true;           // answer PACKETRESEND_CMD (and announce it)
  int retained_frames = 32;     // frames kept for resend requests
  uint32_t seed = 1;            // of the loss pattern (a run is reproducible)
};

struct FakeGigeCounters {
  uint64_t frames_sent = 0;
  uint64_t packets_sent = 0;        // first transmissions put on the wire
  uint64_t packets_lost = 0;        // first transmissions dropped
  uint64_t resend_requests = 0;     // PACKETRESEND_CMD received
  uint64_t packets_requested = 0;   // packets those named
  uint64_t packets_resent = 0;      // resent and put on the wire
  uint64_t resent_lost = 0;         // resent but dropped again
  uint64_t packets_unavailable = 0; // requested from a frame no longer kept
};

// Serves `camera` until `stop` is set or `seconds` have passed. Error: why it could
// not listen (names the address).
std::optional<std::string> serve_fake_gige(ArvFakeCamera* camera, const FakeGigeOptions& options, int seconds,
                                           const std::atomic<bool>& stop, FakeGigeCounters* counters);

}  // namespace tetrapulse::live_test
