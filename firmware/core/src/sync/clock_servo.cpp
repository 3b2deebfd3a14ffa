#include "tetrapulse/fw/sync/clock_servo.hpp"

#include <stdint.h>

#include "tetrapulse/fw/sync/fixed_point.hpp"

namespace tetrapulse::fw {
namespace {

constexpr int64_t kOne = int64_t{1} << kCorrectionShift;  // correction 1.0
constexpr int64_t kMaxErrorForRate = int64_t{1} << 22;   // ns; keeps e << 40 inside int64

int64_t abs64(int64_t v) { return v < 0 ? -v : v; }

// gain/256 * e / tau as a correction (2^-40 units).
int64_t rate_term(uint16_t gain_256, int64_t e, int64_t tau) {
  const int64_t clamped = clamp64(e, -kMaxErrorForRate, kMaxErrorForRate);
  return div_round(clamped * kOne / 256 * gain_256, tau);
}

int64_t ppm_to_correction(int64_t ppm) { return div_round(ppm * kOne, 1'000'000); }

}  // namespace

ServoTuning ServoTuning::gpio() { return ServoTuning{}; }

ServoTuning ServoTuning::can() {
  ServoTuning t;
  t.kp_256 = 32;
  t.ki_256 = 2;
  t.window = 16;
  t.lock_threshold_ns = 20'000;
  t.lock_count = 10;
  t.unlock_count = 10;  // 1 s at 10 Hz: a scheduling hiccup on the sender is not a lost lock
  t.hold_ahead_ns = 80'000;  // 4 lock thresholds: locked, the envelope is within one of zero
  t.gate_acquiring_ns = 2'000'000;
  t.gate_locked_ns = 300'000;
  t.gate_growth_ppb = 20'000;
  t.restep_after = 5;
  t.min_baseline_ns = 1'000'000'000;
  t.holdover_after_ns = 1'000'000'000;
  return t;
}

ClockServo::ClockServo(uint32_t tick_hz) : mapping_(tick_hz) {}

void ClockServo::restart(const ServoTuning& tuning) {
  tuning_ = tuning;
  if (tuning_.window == 0) tuning_.window = 1;
  if (tuning_.window > kMaxWindow) tuning_.window = kMaxWindow;
  phase_ = Phase::kIdle;
  ever_sampled_ = false;
  was_locked_ = false;
  good_in_row_ = 0;
  far_in_row_ = 0;
  bad_in_row_ = 0;
  held_in_row_ = 0;
  window_count_ = 0;
  window_next_ = 0;
  have_accepted_ = false;
}

void ClockServo::stop() {
  phase_ = Phase::kStopped;
  was_locked_ = false;
  have_accepted_ = false;
}

void ClockServo::step_to(Tick local, int64_t rig_ns) {
  mapping_.step(local, rig_ns);
  ++generation_;
  window_count_ = 0;
  window_next_ = 0;
}

void ClockServo::remember(Tick local, int64_t rig_ns) {
  window_[window_next_] = Sample{local, rig_ns};
  window_next_ = static_cast<uint8_t>((window_next_ + 1) % tuning_.window);
  if (window_count_ < tuning_.window) ++window_count_;
}

int64_t ClockServo::envelope(Tick local) const {
  // Residuals of the remembered samples against a line through (local, rig(local)) at the
  // integral rate only: the proportional part of the rate is a transient phase correction
  // and would skew samples further back.
  const int64_t here = mapping_.to_rig(local);
  int64_t best = INT64_MIN;
  for (uint8_t i = 0; i < window_count_; ++i) {
    const Sample& s = window_[i];
    const int64_t dticks = s.local >= local ? static_cast<int64_t>(s.local - local)
                                            : -static_cast<int64_t>(local - s.local);
    const int64_t predicted = here + mapping_.span_ns(dticks, integral_);
    const int64_t residual = s.rig - predicted;
    if (residual > best) best = residual;
  }
  return best;
}

int64_t ClockServo::filtered_error(Tick local, int64_t rig_ns) const {
  const int64_t own = rig_ns - mapping_.to_rig(local);
  const int64_t remembered = envelope(local);
  return remembered > own ? remembered : own;
}

bool ClockServo::hold_out(Tick local, int64_t error) {
  if (phase_ != Phase::kLocked || tuning_.hold_ahead_ns <= 0 || window_count_ == 0) return false;
  if (error - envelope(local) <= tuning_.hold_ahead_ns) {
    held_in_row_ = 0;
    return false;
  }
  if (++held_in_row_ < tuning_.unlock_count) {
    ++held_out_;
    return true;
  }
  // A run of them: the time base did move. Unlock and let the loop follow.
  held_in_row_ = 0;
  phase_ = Phase::kTracking;
  good_in_row_ = 0;
  return false;
}

int64_t ClockServo::gate(Tick local) const {
  const int64_t base = phase_ == Phase::kLocked ? tuning_.gate_locked_ns : tuning_.gate_acquiring_ns;
  if (!have_accepted_ || local <= last_accepted_.local) return base;
  const int64_t since_ns = mapping_.to_rig(local) - mapping_.to_rig(last_accepted_.local);
  return base + mul_shr_signed(since_ns, tuning_.gate_growth_ppb, 0) / 1'000'000'000;
}

SampleVerdict ClockServo::add_sample(Tick local, int64_t rig_ns) {
  switch (phase_) {
    case Phase::kStopped:
      ++rejected_;
      return SampleVerdict::kRejected;
    case Phase::kIdle:
      step_to(local, rig_ns);
      first_ = Sample{local, rig_ns};
      acquire_start_rig_ = rig_ns;
      have_late_ = false;
      last_accepted_ = first_;
      have_accepted_ = true;
      ever_sampled_ = true;
      last_error_ = 0;
      phase_ = Phase::kFirstSample;
      remember(local, rig_ns);
      ++accepted_;
      return SampleVerdict::kStepped;
    case Phase::kFirstSample:
    case Phase::kTracking:
    case Phase::kLocked:
      break;
  }

  const int64_t error = rig_ns - mapping_.to_rig(local);
  const int64_t tau = rig_ns - last_accepted_.rig;
  if (abs64(error) > gate(local) || tau <= 0) {
    ++rejected_;
    if (++bad_in_row_ >= tuning_.restep_after) {
      // Persistent disagreement: the time base moved (or our step was wrong). Start over
      // from this sample.
      const bool locked_before = was_locked_;
      restart(tuning_);
      was_locked_ = locked_before;
      --rejected_;
      return add_sample(local, rig_ns);
    }
    return SampleVerdict::kRejected;
  }
  bad_in_row_ = 0;
  if (hold_out(local, error)) {
    ++rejected_;
    return SampleVerdict::kRejected;
  }
  last_error_ = error;

  if (phase_ == Phase::kFirstSample) {
    // Latency only ever delays a sample, so the earliest arrivals (the largest errors) are
    // the truest: the first half of the baseline moves the starting point to the earliest
    // of its samples, the second half picks the earliest to take the rate to.
    ++accepted_;
    const int64_t baseline = rig_ns - acquire_start_rig_;
    if (baseline < tuning_.min_baseline_ns / 2) {
      if (error <= 0) {
        remember(local, rig_ns);
        return SampleVerdict::kAccepted;
      }
      step_to(local, rig_ns);
      first_ = Sample{local, rig_ns};
      last_accepted_ = first_;
      remember(local, rig_ns);
      return SampleVerdict::kStepped;
    }
    if (!have_late_ || error > late_.rig - mapping_.to_rig(late_.local)) {
      late_ = Sample{local, rig_ns};
      have_late_ = true;
    }
    if (baseline < tuning_.min_baseline_ns) {
      remember(local, rig_ns);
      return SampleVerdict::kAccepted;
    }
    // The rate from the first sample to the earliest late one (the mapping is exact at the
    // first), then the phase through that one: the PI loop starts with both errors small.
    const int64_t late_error = late_.rig - mapping_.to_rig(late_.local);
    const int64_t correction = mapping_.correction() + rate_term(256, late_error, late_.rig - first_.rig);
    integral_ = clamp64(correction, -ppm_to_correction(tuning_.max_correction_ppm),
                        ppm_to_correction(tuning_.max_correction_ppm));
    mapping_.set_rate(late_.local, integral_);
    step_to(late_.local, late_.rig);
    remember(local, rig_ns);
    last_accepted_ = Sample{local, rig_ns};
    phase_ = Phase::kTracking;
    good_in_row_ = 0;
    return SampleVerdict::kStepped;
  }

  remember(local, rig_ns);
  const int64_t e = filtered_error(local, rig_ns);
  const int64_t limit = ppm_to_correction(tuning_.max_correction_ppm);
  integral_ = clamp64(integral_ + rate_term(tuning_.ki_256, e, tau), -limit, limit);
  const int64_t correction = clamp64(integral_ + rate_term(tuning_.kp_256, e, tau), -limit, limit);
  mapping_.set_rate(local, correction);
  last_accepted_ = Sample{local, rig_ns};
  ++accepted_;

  if (abs64(e) < tuning_.lock_threshold_ns) {
    if (good_in_row_ < 255) ++good_in_row_;
  } else {
    good_in_row_ = 0;
  }
  if (abs64(e) > 4 * tuning_.lock_threshold_ns) {
    if (far_in_row_ < 255) ++far_in_row_;
  } else {
    far_in_row_ = 0;
  }
  if (phase_ == Phase::kTracking && good_in_row_ >= tuning_.lock_count) {
    phase_ = Phase::kLocked;
    was_locked_ = true;
  } else if (phase_ == Phase::kLocked && far_in_row_ >= tuning_.unlock_count) {
    phase_ = Phase::kTracking;
  }
  return SampleVerdict::kAccepted;
}

protocol::SyncState ClockServo::state(Tick now) const {
  using protocol::SyncState;
  switch (phase_) {
    case Phase::kStopped:
      return SyncState::kFreeRunning;
    case Phase::kIdle:
      if (was_locked_) return SyncState::kHoldover;
      return ever_sampled_ ? SyncState::kAcquiring : SyncState::kFreeRunning;
    case Phase::kFirstSample:
    case Phase::kTracking:
    case Phase::kLocked:
      break;
  }
  const bool silent = have_accepted_ && now > last_accepted_.local &&
                      mapping_.to_rig(now) - mapping_.to_rig(last_accepted_.local) > tuning_.holdover_after_ns;
  if (silent && was_locked_) return SyncState::kHoldover;
  return phase_ == Phase::kLocked ? SyncState::kLocked : SyncState::kAcquiring;
}

int32_t ClockServo::rate_ppb() const {
  // The frequency estimate (the integral), not the applied rate with its transient
  // phase correction.
  return correction_to_ppb(integral_);
}

int32_t ClockServo::offset_ns() const {
  return static_cast<int32_t>(clamp64(last_error_, INT32_MIN, INT32_MAX));
}

uint32_t ClockServo::holdover_ms(Tick now) const {
  if (state(now) != protocol::SyncState::kHoldover || !have_accepted_ || now <= last_accepted_.local) return 0;
  const int64_t ms = (mapping_.to_rig(now) - mapping_.to_rig(last_accepted_.local)) / 1'000'000;
  return static_cast<uint32_t>(clamp64(ms, 0, UINT32_MAX));
}

}  // namespace tetrapulse::fw
