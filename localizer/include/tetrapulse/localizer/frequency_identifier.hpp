#pragma once
// Which frequency code (protocol/SPEC.md §8.5: a square wave "1..10..0") one
// blob track carries, from its intensity samples alone.
//
// Model. A marker playing code c on board time tau(t) = o + r (t - t_ref)
// (r = 1 +- 200e-6 and o unknown when the boards run free; r = 1 and o from the
// time base's epoch when synchronized) puts into an exposure [s, s + E)
//     I(s) = a + b g_c(s),   g_c(s) = (lit board time of c in [tau(s), tau(s + E))) / (r E),
// the lit fraction of the exposure; a and b > 0 absorb brightness, distance and
// two_level's dim 0 bit. Samples are taken where frames were (dropped frames are
// simply absent), so g_c at the true exposure times carries the aliasing at
// the frame rate and the exposure's integration exactly: no spectrum is formed,
// the prediction is compared with what was seen. For each code of the rig the
// least squares residual RSS_c over a, b, o (a grid of `phase_steps` per bit,
// then refined) and r (three rates when the window is long enough for 200 ppm
// to matter) is found. RSS_c / TSS (TSS: the samples' variance times n) is what
// the code leaves unexplained.
//
// Decision over the newest `max_samples` samples (at least `min_samples`):
//   best      c* = argmin RSS_c over every code of the rig, frequency and binary alike;
//   fit       1 - RSS_c* / TSS >= min_fit: one periodic component, at c*'s predicted
//             alias (with its harmonics), explains the track;
//   modulated b >= min_modulation * the brightest sample (not a constant lamp);
//   evidence  (RSS_rival - RSS_c*) / (2 sigma^2) >= min_evidence for the runner-up,
//             sigma^2 = max(RSS_c* / (n - 3), (noise_floor b)^2): the log-likelihood
//             ratio (nats) against every other code under Gaussian noise.
// All three hold: kFrequency (c* is a square wave) or kBinary (c* is a binary
// code); otherwise kUnknown, and more samples are awaited. Never a guess.
//
// Families. Frequency and binary codes compete in one comparison, so a track
// is given a frequency code only when that square wave explains it better than
// every binary code of the rig by min_evidence, and the reverse: a Localizer
// must assign a binary code (code_match) to a track only while this identifier
// does not say kFrequency, and a frequency code only on kFrequency.
//
// Times are integer nanoseconds of rig time; intensities in any linear unit.
#include <array>
#include <cstddef>
#include <cstdint>
#include <deque>
#include <utility>
#include <vector>

#include "tetrapulse/localizer/blob_tracker.hpp"
#include "tetrapulse/localizer/targets.hpp"

namespace tetrapulse {

struct FrequencyIdentifierOptions {
  size_t max_samples = 64;     // newest samples used (a track's history: kTrackHistory)
  size_t min_samples = 8;
  double min_fit = 0.7;        // fraction of the track's variance the best code explains
  double min_evidence = 12.0;  // nats against the runner-up
  double noise_floor = 0.05;   // sigma never below this fraction of the fitted swing b
  double min_modulation = 0.2; // fitted swing b against the brightest sample
  int phase_steps = 8;         // free-running phase grid: points per bit
  double clock_ppm = 200;      // free-running rate search: 1 +- this
  // push(TrackSample): a sample with no measurement whose blob was not found is
  // dark (intensity 0) when true, skipped when false. With on_off modulation a
  // dark 0 bit makes no blob, so the dark samples are half of the evidence.
  bool absent_is_dark = true;
};

// One exposure of a track.
struct FrequencySample {
  int64_t start_ns = 0;     // exposure start, rig time
  int64_t exposure_ns = 0;  // > 0
  double intensity = 0;     // integrated over the blob
};

// The codes of a rig, as the identifier compares them.
struct RigCode {
  Code code;
  bool frequency = false;                          // a square wave (protocol::is_square_wave, SPEC.md §8.5)
  std::vector<std::pair<size_t, size_t>> markers;  // (target index, marker index) that play it
};
// The distinct codes of `targets` (a code's rotations are the same code when
// the boards run free; they are kept apart when synchronized).
std::vector<RigCode> rig_codes(const TargetsFile& targets);
// For each target (targets.yaml order) and marker, the index in `codes` of the
// frequency code it plays; -1 for a binary code or none.
std::vector<std::array<int, 4>> frequency_code_of(const TargetsFile& targets, const std::vector<RigCode>& codes);

struct FrequencyDecision {
  enum class Kind : uint8_t { kUnknown, kFrequency, kBinary };
  Kind kind = Kind::kUnknown;
  int code = -1;            // index in codes() of the best code (also when unknown, -1 before any fit)
  double evidence = 0;      // nats of the best code against the runner-up (the confidence)
  double fit = 0;           // fraction of the variance the best code explains
  size_t samples = 0;       // samples used
  // The best code's board clock: bit index at rig time t is
  // floor((origin_ns + rate (t - reference_ns)) / bit_period) mod L (origin in board ns).
  int64_t reference_ns = 0;
  double origin_ns = 0;
  double rate = 1.0;

  bool decided() const { return kind != Kind::kUnknown; }
};

class FrequencyIdentifier {
 public:
  FrequencyIdentifier(const TargetsFile& targets, FrequencyIdentifierOptions options = {});

  // A sample, in time order (older ones are ignored). Dropped frames: push nothing.
  void push(const FrequencySample& sample);
  void push(const TrackSample& sample);
  // The decision over the samples pushed so far (computed on demand, then kept until the next push).
  const FrequencyDecision& decision();
  void reset();

  const std::vector<RigCode>& codes() const { return codes_; }
  // Residual fraction RSS_c / TSS of every code at its best phase and rate (after decision()).
  const std::vector<double>& unexplained() const { return unexplained_; }

 private:
  void decide();

  FrequencyIdentifierOptions options_;
  Timebase timebase_;
  std::vector<RigCode> codes_;
  std::deque<FrequencySample> samples_;
  bool stale_ = true;
  FrequencyDecision decision_;
  std::vector<double> unexplained_;
};

}  // namespace tetrapulse
