#pragma once
// Disciplines the local counter to rig time from samples (local tick L_k, rig time R_k):
// GPIO sync edges (R_k from the edge rule, Config §2.5) or CAN Sync/FollowUp pairs
// (R_k = tx_time_ns of the Sync received at L_k).
//
// A PI loop in integer fixed point. With e_k = R_k - rig(L_k) (ns) and tau_k the rig
// time since the previous accepted sample:
//   integral_k = integral_{k-1} + Ki e_k / tau_k       (rate, fraction of 1)
//   correction = integral_k + Kp e_k / tau_k            (applied until the next sample)
// so the phase error obeys e_{k+1} = (1 - Kp - Ki) e_k - g_{k-1} with poles inside the
// unit circle for the gains of ServoTuning. The mapping stays continuous (LED edges never
// jump) except for the coarse step that acquisition starts with.
//
// Acquisition: the first sample steps rig(L) to R, and so does any sample ahead of the
// mapping in the first half of min_baseline (latency only delays: the earliest arrival is
// the truest); at min_baseline the rate is set from that sample to the earliest arrival of
// the second half and the mapping steps through it; then the PI loop runs. Locked once
// lock_count consecutive filtered errors are below lock_threshold_ns; unlocked again only
// after unlock_count consecutive ones above 4 lock_threshold_ns, so a short burst of
// late or early samples that the loop absorbs does not flap the state. A sample whose error
// exceeds the gate is an outlier and is refused (a missed or doubled edge, a stale
// FollowUp); restep_after consecutive outliers mean the time base really moved and start
// acquisition again. No accepted sample for holdover_after: holdover, on the last rate.
//
// Noisy samples (CAN reception latency, one-sided: a frame is never received early)
// pass a minimum-latency filter: the error fed to the loop is the largest of the last
// `window` residuals against the current mapping. A late arrival therefore costs nothing,
// but one sample ahead of that envelope (its FollowUp stamped late, a clock conversion
// off by a preempted read) would lead the filter for `window` samples and swing the rate
// by hundreds of ppm. So, while locked, a sample more than hold_ahead_ns above the envelope
// of the remembered residuals is held out: counted as rejected, not remembered, no loop
// update. unlock_count held in a row are a real step: the servo unlocks and follows them.
#include <cstdint>

#include "tetrapulse/fw/clock/tick.hpp"
#include "tetrapulse/fw/sync/clock_mapping.hpp"
#include "tetrapulse/protocol/response_messages.hpp"

namespace tetrapulse::fw {

struct ServoTuning {
  uint16_t kp_256 = 128;                // Kp = kp_256 / 256
  uint16_t ki_256 = 26;                 // Ki = ki_256 / 256
  uint8_t window = 1;                   // minimum-latency filter length (1 = off), <= kMaxWindow
  int64_t lock_threshold_ns = 300;      // |filtered error| below this ...
  uint8_t lock_count = 8;               // ... for this many consecutive samples: locked
  uint8_t unlock_count = 3;             // consecutive samples above 4 lock_threshold_ns: unlocked
  int32_t hold_ahead_ns = 0;            // while locked, hold out a sample this far above the envelope (0 = off)
  int64_t gate_acquiring_ns = 50'000;   // outlier gate before lock
  int64_t gate_locked_ns = 1'000;       // outlier gate once locked
  uint32_t gate_growth_ppb = 10'000;    // the gate widens by this rate while no sample is accepted
  uint8_t restep_after = 5;             // consecutive outliers that restart acquisition
  int64_t min_baseline_ns = 5'000'000;  // second acquisition sample at least this long after the first
  int64_t holdover_after_ns = 500'000'000;  // no accepted sample for this long: holdover
  int64_t max_correction_ppm = 500;     // the rate correction is clamped to this

  static ServoTuning gpio();  // exact edges (input capture)
  static ServoTuning can();   // Sync/FollowUp with reception latency of tens of microseconds
};

enum class SampleVerdict : uint8_t {
  kStepped,   // acquisition step (the mapping jumped)
  kAccepted,  // used by the PI loop
  kRejected,  // outlier, refused
};

class ClockServo {
 public:
  static constexpr uint8_t kMaxWindow = 16;

  explicit ClockServo(uint32_t tick_hz);

  // Starts over with `tuning` (sync source changed): acquiring on the next sample; the
  // mapping and its rate are kept, so the LEDs keep their timing until then.
  void restart(const ServoTuning& tuning);
  // No sync source: free-running on the last mapping.
  void stop();

  SampleVerdict add_sample(Tick local, int64_t rig_ns);

  const ClockMapping& mapping() const { return mapping_; }
  int64_t to_rig(Tick t) const { return mapping_.to_rig(t); }
  Tick to_local(int64_t rig_ns) const { return mapping_.to_local(rig_ns); }
  // Increments on every step; a code player reschedules when it changes.
  uint32_t generation() const { return generation_; }
  // True once the first sample has set the time (rig time is meaningful).
  bool acquired() const { return phase_ != Phase::kIdle && phase_ != Phase::kStopped; }

  protocol::SyncState state(Tick now) const;
  int32_t offset_ns() const;  // last measured error, saturated
  int32_t rate_ppb() const;  // the frequency estimate: the counter's rate error, ppb
  uint32_t holdover_ms(Tick now) const;
  uint32_t accepted() const { return accepted_; }
  uint32_t rejected() const { return rejected_; }  // outliers and held-out samples
  uint32_t held_out() const { return held_out_; }

 private:
  enum class Phase : uint8_t { kStopped, kIdle, kFirstSample, kTracking, kLocked };
  struct Sample {
    Tick local = 0;
    int64_t rig = 0;
  };

  void step_to(Tick local, int64_t rig_ns);
  // The largest residual of the remembered samples at `local` (INT64_MIN when none): the
  // earliest arrival's; filtered_error is that or the new sample's own, if larger.
  int64_t envelope(Tick local) const;
  int64_t filtered_error(Tick local, int64_t rig_ns) const;
  bool hold_out(Tick local, int64_t error);
  int64_t gate(Tick local) const;
  void remember(Tick local, int64_t rig_ns);

  ServoTuning tuning_;
  ClockMapping mapping_;
  Phase phase_ = Phase::kStopped;
  uint32_t generation_ = 0;
  Sample first_;           // the earliest arrival of acquisition's first half
  Sample late_;            // ... and of its second half
  int64_t acquire_start_rig_ = 0;
  bool have_late_ = false;
  Sample last_accepted_;
  bool have_accepted_ = false;
  bool ever_sampled_ = false;  // a sample arrived since restart()
  bool was_locked_ = false;    // locked since restart(): silence is holdover, not acquisition
  int64_t integral_ = 0;     // 2^-40 units
  int64_t last_error_ = 0;   // ns
  uint8_t good_in_row_ = 0;
  uint8_t far_in_row_ = 0;  // accepted samples above the unlock threshold, while locked
  uint8_t bad_in_row_ = 0;
  uint8_t held_in_row_ = 0;  // samples held out in a row, while locked
  Sample window_[kMaxWindow];
  uint8_t window_count_ = 0;
  uint8_t window_next_ = 0;
  uint32_t accepted_ = 0;
  uint32_t rejected_ = 0;
  uint32_t held_out_ = 0;
};

}  // namespace tetrapulse::fw
