#pragma once
// The scale benchmarks' scenes: N of the paper's large targets (16 markers of
// 3 cm, two-level codes, synchronised) on a grid under a static camera looking
// straight down, each circling slowly on the floor. N <= 8: the 752x480 camera
// 1.6 m up; N >= 16: a 1280x960 camera (same 90 degree field) 3.0 m up, where a
// marker spans about as many pixels. Codes: 16 bits, four per target, drawn by
// the project's codebook search (recommended synchronised two-level spec), so
// that 64 targets (256 codes) fit; every N uses the same code length.
#include <cstdint>
#include <map>
#include <memory>
#include <string>
#include <vector>

#include <opencv2/core/mat.hpp>

#include "four_targets_sequence.hpp"
#include "tetrapulse/codebook/codebook.hpp"
#include "tetrapulse/codebook/codebook_workspace.hpp"

namespace tetrapulse::bench {

inline constexpr int kScaleFrames = 120;

// 260 codes of 16 bits as strings (character i = bit i of the word).
inline const std::vector<std::string>& scale_codes() {
  static const std::vector<std::string> codes = [] {
    protocol::CodebookSpec spec =
        protocol::recommended_spec(protocol::CodeTiming::kSynchronized, protocol::ZeroBit::kDim, 16);
    spec.count = 260;  // 4 per target for 64 targets, 4 for a target never shown
    auto workspace = std::make_unique<protocol::CodebookWorkspace>();
    std::vector<uint64_t> words(spec.count);
    auto n = protocol::generate(spec, words.data(), words.size(), *workspace);
    std::vector<std::string> out;
    for (size_t k = 0; n && k < *n; ++k) {
      std::string s(16, '0');
      for (int i = 0; i < 16; ++i) s[size_t(i)] = ((words[k] >> i) & 1u) ? '1' : '0';
      out.push_back(s);
    }
    return out;
  }();
  return codes;
}

inline std::string scale_scenario(int n) {
  const bool large = n >= 16;
  const int cols = n <= 1 ? 1 : n <= 4 ? 2 : n <= 16 ? 4 : 8;
  const int rows = (n + cols - 1) / cols;
  const double spacing = large ? 0.5 : 0.7;
  std::string s = "name: bench-scale-" + std::to_string(n) +
                  "\nframes: {start_ns: 4000000, period_ns: 10000000, exposure_ns: 2000000, count: 100000}\n"
                  "camera:\n  image_width: " +
                  std::string(large ? "1280" : "752") + "\n  image_height: " + std::string(large ? "960" : "480") +
                  "\n  hfov_deg: 90\n  distortion_model: plumb_bob\n"
                  "  distortion_coefficients: [-0.05, 0.01, 0.0, 0.0, 0.0]\n  psf_sigma_px: 0.6\n"
                  "  motion: {kind: static, position_m: [0.0, 0.0, " +
                  std::string(large ? "3.0" : "1.6") +
                  "], rpy_deg: [180, 0, 0]}\n"
                  "timebase: {synchronized: true, epoch_ns: 0, bit_period_ns: 10000000}\n"
                  "modulation: {kind: two_level, low: 0.3}\ntargets:\n";
  const std::vector<std::string>& codes = scale_codes();
  for (int k = 0; k < n; ++k) {
    const int c = k % cols, r = k / cols;
    const double x = (c - 0.5 * (cols - 1)) * spacing, y = (r - 0.5 * (rows - 1)) * spacing;
    const char* target_codes[4];
    for (int m = 0; m < 4; ++m) target_codes[m] = codes[size_t(4 * k + m)].c_str();
    std::string t = target_yaml(k + 1, target_codes, x, y, 90.0 * (k % 4));
    // A smaller circle than the four-target scene's: neighbours stay apart.
    const std::string from = "radius_m: 0.1", to = "radius_m: 0.05";
    t.replace(t.find(from), from.size(), to);
    s += t;
  }
  return s;
}

// Frames of the N-target scene, rendered once per N (the last N asked for is
// kept: 120 frames of 1280x960 are 150 MB).
inline const Sequence& scale_sequence(int n) {
  static int cached = -1;
  static std::unique_ptr<Sequence> s;
  if (cached != n) {
    s.reset();
    s = std::make_unique<Sequence>();
    s->scenario = *sim::parse_scenario(scale_scenario(n), "bench-scale");
    const sim::Scene scene = sim::build_scene(s->scenario, 1);
    sim::SensorModel sensor(s->scenario.camera.width, s->scenario.camera.height, s->scenario.sensor, 1);
    sim::FrameRenderer renderer(scene, s->scenario.render, sensor);
    s->exposure_ns = s->scenario.frames.exposure_ns;
    for (int k = 0; k < kScaleFrames; ++k) {
      const int64_t start = s->scenario.frames.start_ns + k * s->scenario.frames.period_ns;
      cv::Mat image;
      renderer.render(start, s->exposure_ns, sim::stream_seed(1, sim::kStreamSensorNoise, uint64_t(k)), &image);
      s->images.push_back(image);
      s->starts.push_back(start);
    }
    cached = n;
  }
  return *s;
}

}  // namespace tetrapulse::bench
