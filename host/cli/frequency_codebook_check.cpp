#include "frequency_codebook_check.hpp"

#include <algorithm>
#include <cstdint>

#include <fmt/format.h>

#include "codebook_constraints.hpp"
#include "exit_codes.hpp"
#include "tetrapulse/codebook/codebook_word.hpp"
#include "tetrapulse/codebook/frequency_code.hpp"

namespace tetrapulse::cli {
namespace {

using protocol::FrequencyFault;
using protocol::FrequencyReport;
using protocol::FrequencySpec;

constexpr double kQ32 = 4294967296.0;
constexpr size_t kShown = 20;
constexpr uint32_t kDarkCap = 64;  // dark runs are reported up to this many frames

std::string named(const LabelledCode& c) { return fmt::format("{} '{}'", c.label, code_text(c.code)); }

// nu and drift (Q32) of a signal that repeats every `bits` bits.
struct Seen {
  uint32_t nu = 0;
  uint32_t drift = 0;
};
Seen seen(const FrequencySpec& s, uint32_t bits) {
  const int64_t period = static_cast<int64_t>(bits) * s.bit_period_ns;
  return Seen{protocol::apparent_frequency_q32(s.camera.frame_period_ns, period),
              protocol::frequency_drift_q32(s.camera.frame_period_ns, period, s.clock_ppm)};
}
std::string seen_text(const FrequencySpec& s, uint32_t bits) {
  const Seen x = seen(s, bits);
  return fmt::format("{:.4f} +- {:.4f} cycle per frame", x.nu / kQ32, x.drift / kQ32);
}

// How far apart two signals stay beyond their drifts (Q32; negative: overlapping).
int64_t margin(const FrequencySpec& s, uint32_t bits_a, uint32_t bits_b) {
  const Seen a = seen(s, bits_a);
  const Seen b = seen(s, bits_b);
  const int64_t gap = std::abs(static_cast<int64_t>(a.nu) - static_cast<int64_t>(b.nu));
  return gap - static_cast<int64_t>(a.drift) - static_cast<int64_t>(b.drift);
}

std::string fault_text(const FrequencySpec& s, const FrequencyReport& r, const LabelledCode& c,
                       const LabelledCode* other) {
  const std::string who = named(c);
  protocol::SquareWave wave;
  protocol::is_square_wave(c.code, &wave);
  switch (r.fault) {
    case FrequencyFault::kNearConstant:
      return fmt::format("{}: seen at {}, within 1/{} of 0: it looks constant (--window-frames, or another length)",
                         who, seen_text(s, c.code.length), s.window_frames);
    case FrequencyFault::kNearNyquist:
      return fmt::format(
          "{}: seen at {}, within 1/{} of 1/2 cycle per frame, where what a camera sees of it depends on the phase",
          who, seen_text(s, c.code.length), 2 * s.window_frames);
    case FrequencyFault::kTooDark:
      return fmt::format("{}: looks dark for {} frames in a row at some phase, more than {} (--max-dark-frames)", who,
                         protocol::wave_visibility(s.camera, s.bit_period_ns, wave, kDarkCap).dark_frames,
                         int(s.max_dark_frames));
    case FrequencyFault::kTooFaint:
      return fmt::format("{}: an exposure's lit fraction swings by only {}% across phases, less than {}% (--min-swing)",
                         who, protocol::wave_visibility(s.camera, s.bit_period_ns, wave, kDarkCap).swing_percent,
                         int(s.min_swing_percent));
    case FrequencyFault::kTooClose:
      if (other == nullptr) break;
      return fmt::format(
          "{} seen at {} and {} seen at {}: less than 1/{} cycle per frame apart beyond their drifts, too close to "
          "tell apart (--window-frames)",
          who, seen_text(s, c.code.length), named(*other), seen_text(s, other->code.length), s.window_frames);
    case FrequencyFault::kNone:
    case FrequencyFault::kBadSpec:
    case FrequencyFault::kNotSquareWave:
      break;
  }
  return fmt::format("{}: {}", who, protocol::frequency_fault_name(r.fault));
}

std::string beside_text(const FrequencySpec& s, const LabelledCode& binary, const LabelledCode& frequency) {
  const uint32_t p = protocol::least_period(binary.code.bits, binary.code.length);
  return fmt::format(
      "binary {} repeats every {} bits, so it is seen at {} like a square wave of {} bits, and frequency {} at {}: "
      "less than 1/{} cycle per frame apart beyond their drifts, a reader may take one for the other",
      named(binary), p, seen_text(s, p), p, named(frequency), seen_text(s, frequency.code.length), s.window_frames);
}

}  // namespace

int check_frequency_family(const std::string& path, const TargetsFile& file, const FrequencyCodebookArgs& camera,
                           const std::vector<LabelledCode>& frequency, const std::vector<LabelledCode>& binary,
                           const std::string& what) {
  if (!camera.fps || camera.exposure.empty()) {
    codebook_error(fmt::format(
        "{}: {} are square waves (frequency codes, e.g. {}): checking them needs the camera, give --fps and "
        "--exposure",
        path, what, named(frequency.front())));
    return kExitUsage;
  }
  auto spec = frequency_spec(camera, file.modulation.kind);
  if (!spec) {
    codebook_error(spec.error().message);
    return spec.error().exit;
  }
  FrequencySpec s = *spec;
  s.bit_period_ns = file.timebase.bit_period_ns;
  if (const char* why = protocol::check_frequency_spec(s); why != nullptr || s.bit_period_ns == 0) {
    codebook_error(fmt::format("{}: timebase bit_period_ns {}: {}", path, s.bit_period_ns,
                               why != nullptr ? why : "must not be 0"));
    return kExitCheckFailed;
  }

  size_t faults = 0;
  auto note = [&](const std::string& text) {
    if (faults++ < kShown) codebook_error(fmt::format("{}: {}", path, text));
  };
  // One code, then one pair at a time: every fault, not only the first.
  std::vector<bool> admissible(frequency.size());
  for (size_t i = 0; i < frequency.size(); ++i) {
    const uint64_t word = frequency[i].code.bits;
    const auto length = static_cast<uint8_t>(frequency[i].code.length);
    const FrequencyReport r = protocol::check_frequency_codes(s, &word, &length, 1);
    admissible[i] = r.ok();
    if (!r.ok()) note(fault_text(s, r, frequency[i], nullptr));
  }
  int64_t closest = INT64_MAX;
  for (size_t i = 0; i < frequency.size(); ++i) {
    for (size_t j = i + 1; j < frequency.size(); ++j) {
      if (!admissible[i] || !admissible[j]) continue;
      const uint64_t words[] = {frequency[i].code.bits, frequency[j].code.bits};
      const uint8_t lengths[] = {static_cast<uint8_t>(frequency[i].code.length),
                                 static_cast<uint8_t>(frequency[j].code.length)};
      const FrequencyReport r = protocol::check_frequency_codes(s, words, lengths, 2);
      if (!r.ok()) note(fault_text(s, r, frequency[i], &frequency[j]));
      closest = std::min(closest, margin(s, frequency[i].code.length, frequency[j].code.length));
    }
  }
  for (const LabelledCode& b : binary) {
    const auto b_length = static_cast<uint8_t>(b.code.length);
    for (const LabelledCode& f : frequency) {
      const auto f_length = static_cast<uint8_t>(f.code.length);
      const FrequencyReport r = protocol::check_binary_beside_frequency(s, &b.code.bits, &b_length, 1, &f.code.bits,
                                                                        &f_length, 1);
      if (!r.ok()) note(beside_text(s, b, f));
    }
  }
  const std::string setting = fmt::format("{}, bit period {} ns", describe_camera(s, *camera.fps), s.bit_period_ns);
  if (faults > 0) {
    if (faults > kShown) codebook_error(fmt::format("{}: ... and {} more", path, faults - kShown));
    codebook_error(fmt::format("{}: {} faults in {}{}: {}", path, faults, what,
                               binary.empty() ? "" : " and beside the binary codes", setting));
    return kExitCheckFailed;
  }
  std::string closest_text;
  if (closest != INT64_MAX) {
    closest_text = fmt::format("; closest pair {:.4f} cycle per frame apart beyond drifts (told apart within ~{:.0f} "
                               "frames)",
                               closest / kQ32, kQ32 / static_cast<double>(closest));
  }
  fmt::print("{}: {} pass: {}{}{}\n", path, what, setting, closest_text,
             binary.empty() ? std::string()
                            : fmt::format("; the {} binary codes stay apart from them in apparent frequency",
                                          binary.size()));
  return kExitOk;
}

}  // namespace tetrapulse::cli
