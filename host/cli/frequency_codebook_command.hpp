#pragma once
// `tetrapulse codebook --family frequency`: square-wave codes of different lengths
// whose apparent frequencies one camera keeps apart (protocol/SPEC.md §8.5).
// The rest of the command (geometry, ids, targets.yaml) is codebook_command.cpp's.
#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include <CLI/CLI.hpp>
#include <tl/expected.hpp>

#include "tetrapulse/localizer/targets.hpp"
#include "tetrapulse/codebook/codebook_frequency.hpp"

namespace tetrapulse::cli {

struct FrequencyCodebookArgs {
  std::string family = "binary";
  std::optional<double> fps;
  std::string exposure;               // "1ms", "500us", "0.002s", "2000000ns"; a bare number is ms
  uint16_t window_frames = protocol::FrequencySpec{}.window_frames;
  uint32_t clock_ppm = protocol::FrequencySpec{}.clock_ppm;
  std::string max_dark_frames;        // "K" or "none"; default 3 with on_off, none with two_level
  int min_swing_percent = protocol::FrequencySpec{}.min_swing_percent;
  std::optional<int64_t> bit_period_ns;  // given: use it; else chosen

  bool frequency() const { return family == "frequency"; }
};

// Registers --family and the frequency options on `codebook`.
void add_frequency_codebook_options(CLI::App* cmd, FrequencyCodebookArgs* a);
// The frequency options without --family (--fps, --exposure, --window-frames, ...).
void add_frequency_camera_options(CLI::App* cmd, FrequencyCodebookArgs* a);

// Codes chosen for one request, ready for targets.yaml.
struct FrequencyChoice {
  int64_t bit_period_ns = 0;
  std::vector<Code> codes;    // in the order targets (or markers) take them
  std::string description;    // one line: camera, window, codes, margin

  std::vector<uint64_t> words() const;
};

// The user's problem in one line, and the exit code it deserves.
struct FrequencyCodebookError {
  std::string message;
  int exit = 0;
};

// The spec the options describe (count 1; bit period --bit-period-ns or 0), or a usage error.
tl::expected<protocol::FrequencySpec, FrequencyCodebookError> frequency_spec(const FrequencyCodebookArgs& a,
                                                                             ModulationKind modulation);
// "100 fps, 1 ms exposure, apparent frequencies 1/24 cycle per frame apart under 200 ppm, ..."
std::string describe_camera(const protocol::FrequencySpec& s, double fps);

// `count` codes for this camera, or why not (a request above the capacity says the maximum).
// `per_marker`/`targets` only shape the error's advice.
tl::expected<FrequencyChoice, FrequencyCodebookError> choose_frequency_codebook(const FrequencyCodebookArgs& a,
                                                                                ModulationKind modulation,
                                                                                size_t count, bool per_marker,
                                                                                size_t targets);

// --capacity with --family frequency: prints how many codes the camera separates. Exit code.
int run_frequency_capacity(const FrequencyCodebookArgs& a, ModulationKind modulation);

}  // namespace tetrapulse::cli
