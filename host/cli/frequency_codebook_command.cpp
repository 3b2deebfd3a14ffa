#include "frequency_codebook_command.hpp"

#include <cmath>

#include <fmt/format.h>

#include "codebook_constraints.hpp"
#include "exit_codes.hpp"
#include "tetrapulse/protocol/limits.hpp"

namespace tetrapulse::cli {
namespace {

using protocol::FrequencyCodebook;
using protocol::FrequencySpec;

constexpr double kQ32 = 4294967296.0;

// "1ms", "500us", "2000000ns", "0.002s"; a bare number is milliseconds.
std::optional<int64_t> parse_duration_ns(const std::string& text) {
  size_t used = 0;
  double value = 0;
  try {
    value = std::stod(text, &used);
  } catch (const std::exception&) {
    return std::nullopt;
  }
  const std::string unit = text.substr(used);
  double scale = 0;
  if (unit.empty() || unit == "ms") scale = 1e6;
  if (unit == "us") scale = 1e3;
  if (unit == "ns") scale = 1;
  if (unit == "s") scale = 1e9;
  if (scale == 0 || !std::isfinite(value) || value <= 0 || value * scale > 1e10) return std::nullopt;
  return static_cast<int64_t>(std::llround(value * scale));
}

}  // namespace

tl::expected<FrequencySpec, FrequencyCodebookError> frequency_spec(const FrequencyCodebookArgs& a,
                                                                   ModulationKind modulation) {
  auto usage = [](std::string m) { return tl::unexpected(FrequencyCodebookError{std::move(m), kExitUsage}); };
  if (!a.fps || a.exposure.empty()) return usage("--family frequency needs --fps and --exposure (the camera's)");
  FrequencySpec s;
  s.camera.frame_period_ns = static_cast<int64_t>(std::llround(1e9 / *a.fps));
  const std::optional<int64_t> exposure = parse_duration_ns(a.exposure);
  if (!exposure) return usage(fmt::format("--exposure: '{}' is not a duration such as 1ms, 500us or 2000000ns", a.exposure));
  s.camera.exposure_ns = *exposure;
  if (s.camera.exposure_ns > s.camera.frame_period_ns) {
    return usage(fmt::format("--exposure {}: longer than the frame period at --fps {} ({} ns)", a.exposure, *a.fps,
                             s.camera.frame_period_ns));
  }
  s.bit_period_ns = a.bit_period_ns.value_or(0);
  s.window_frames = a.window_frames;
  s.clock_ppm = a.clock_ppm;
  s.min_swing_percent = static_cast<uint8_t>(a.min_swing_percent);
  if (a.max_dark_frames == "none" || (a.max_dark_frames.empty() && modulation == ModulationKind::kTwoLevel)) {
    s.max_dark_frames = protocol::kNoDarkLimit;
  } else if (!a.max_dark_frames.empty()) {
    const bool digits = a.max_dark_frames.size() <= 2 &&
                        a.max_dark_frames.find_first_not_of("0123456789") == std::string::npos;
    if (!digits) return usage(fmt::format("--max-dark-frames: '{}' is not 'none' or 0..99", a.max_dark_frames));
    s.max_dark_frames = static_cast<uint8_t>(std::stoi(a.max_dark_frames));
  }
  s.count = 1;  // the caller's count is checked against the capacity, not here
  if (const char* why = protocol::check_frequency_spec(s); why != nullptr) {
    return usage(fmt::format("--family frequency: {}", why));
  }
  return s;
}

std::string describe_camera(const FrequencySpec& s, double fps) {
  return fmt::format("{:g} fps, {:g} ms exposure, apparent frequencies 1/{} cycle per frame apart under {} ppm{}",
                     fps, s.camera.exposure_ns * 1e-6, s.window_frames, s.clock_ppm,
                     s.max_dark_frames == protocol::kNoDarkLimit
                         ? std::string()
                         : fmt::format(", at most {} dark frames", int(s.max_dark_frames)));
}

void add_frequency_codebook_options(CLI::App* cmd, FrequencyCodebookArgs* a) {
  cmd->add_option("--family", a->family,
                  "binary: words of one length (search); frequency: square waves of different lengths kept apart "
                  "in apparent frequency at one camera (needs --fps, --exposure)")
      ->check(CLI::IsMember({"binary", "frequency"}))
      ->capture_default_str();
  add_frequency_camera_options(cmd, a);
}

void add_frequency_camera_options(CLI::App* cmd, FrequencyCodebookArgs* a) {
  cmd->add_option("--fps", a->fps, "frequency: the camera's frame rate (Hz)")->check(CLI::Range(0.1, 100000.0));
  cmd->add_option("--exposure", a->exposure, "frequency: the camera's exposure (1ms, 500us, 2000000ns; bare: ms)");
  cmd->add_option("--window-frames", a->window_frames,
                  "frequency: identification window; apparent frequencies are kept 1/W cycle per frame apart")
      ->check(CLI::Range(4, 4096))
      ->capture_default_str();
  cmd->add_option("--clock-ppm", a->clock_ppm, "frequency: board clock error bound (ppm)")
      ->check(CLI::Range(0, 10000))
      ->capture_default_str();
  cmd->add_option("--max-dark-frames", a->max_dark_frames,
                  "frequency: most frames in a row a marker may look dark (default 3 with on_off, none with two_level)");
  cmd->add_option("--min-swing", a->min_swing_percent,
                  "frequency: least swing of an exposure's lit fraction across phases (percent)")
      ->check(CLI::Range(1, 100))
      ->capture_default_str();
}

tl::expected<FrequencyChoice, FrequencyCodebookError> choose_frequency_codebook(const FrequencyCodebookArgs& a,
                                                                                ModulationKind modulation,
                                                                                size_t count, bool per_marker,
                                                                                size_t targets) {
  auto spec = frequency_spec(a, modulation);
  if (!spec) return tl::unexpected(spec.error());
  FrequencyCodebook book;
  FrequencySpec ask = *spec;
  ask.count = static_cast<uint16_t>(std::min<size_t>(count, protocol::kMaxFrequencyCodes));
  if (!protocol::choose_frequency_codes(ask, &book).ok()) {
    return tl::unexpected(FrequencyCodebookError{"--family frequency: the camera options are out of range", kExitUsage});
  }
  const std::string camera = describe_camera(*spec, *a.fps);
  if (book.count == 0 || count > protocol::kMaxFrequencyCodes) {
    const size_t fit = per_marker ? book.capacity / protocol::kMarkersPerTarget : book.capacity;
    std::string advice = fmt::format("use --targets {}", fit);
    if (fit == 0) advice = "use fewer targets";
    if (per_marker && book.capacity >= targets) advice += fmt::format(", or --per target ({} codes)", targets);
    advice += fmt::format(", a longer --window-frames (now {}: slower identification)", a.window_frames);
    if (modulation == ModulationKind::kOnOff) advice += ", or --modulation two_level (no dark runs)";
    return tl::unexpected(FrequencyCodebookError{
        fmt::format("{} targets need {} frequency codes; this camera separates at most {} ({}{}); {}", targets, count,
                    book.capacity, camera,
                    a.bit_period_ns ? fmt::format(", bit period {} ns", *a.bit_period_ns) : std::string(), advice),
        kExitCheckFailed});
  }
  FrequencyChoice choice;
  choice.bit_period_ns = book.bit_period_ns;
  for (uint32_t i = 0; i < book.count; ++i) {
    choice.codes.push_back(Code{book.codes[i].wave.length, book.codes[i].word});
  }
  choice.description = fmt::format(
      "frequency codes, bit period {} ns, {}; margin {:.4f} cycle per frame (identified within ~{:.0f} frames); "
      "the camera separates at most {}",
      book.bit_period_ns, camera, book.margin_q32 / kQ32, std::ceil(kQ32 / book.margin_q32), book.capacity);
  return choice;
}

std::vector<uint64_t> FrequencyChoice::words() const {
  std::vector<uint64_t> out;
  for (const Code& c : codes) out.push_back(c.bits);
  return out;
}

int run_frequency_capacity(const FrequencyCodebookArgs& a, ModulationKind modulation) {
  auto spec = frequency_spec(a, modulation);
  if (!spec) {
    codebook_error(spec.error().message);
    return spec.error().exit;
  }
  FrequencyCodebook book;
  if (!protocol::choose_frequency_codes(*spec, &book).ok()) {
    codebook_error("--family frequency: the camera options are out of range");
    return kExitUsage;
  }
  fmt::print("{}: {} separable frequency codes (bit period {} ns): {} targets with a code per marker, {} with a code "
             "per target\n",
             describe_camera(*spec, *a.fps), book.capacity, book.capacity_bit_period_ns,
             book.capacity / protocol::kMarkersPerTarget, book.capacity);
  return kExitOk;
}

}  // namespace tetrapulse::cli
