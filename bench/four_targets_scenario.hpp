#pragma once
// The benchmarks' virtual-rig scene: a 752x480 camera (90 degrees, 100 fps)
// moving 1.3-1.9 m above four of the paper's large targets (16 markers of 3 cm,
// two-level codes, synchronised), circling slowly on the floor. A scenario in
// the format of sim/SCENARIOS.md.
#include <string>

namespace tetrapulse::bench {

inline std::string target_yaml(int id, const char* codes[4], double x, double y, double yaw_deg) {
  const char* positions[4] = {"[0.0, -0.1651, 0.2366]", "[0.0, 0.1304, 0.1845]", "[0.0626, -0.0221, 0.0539]",
                              "[-0.0802, 0.0249, 0.0621]"};
  std::string t = "  - id: " + std::to_string(id) + "\n    marker_diameter_m: 0.03\n    radiance_e_per_ms: 1600\n"
                  "    markers:\n";
  for (int m = 0; m < 4; ++m) {
    t += std::string("      - position_m: ") + positions[m] + "\n        code: \"" + codes[m] + "\"\n";
  }
  t += "    motion: {kind: circle, center_m: [" + std::to_string(x) + ", " + std::to_string(y) +
       ", 0.0], radius_m: 0.1, period_s: 6, rpy_deg: [0, 0, " + std::to_string(yaw_deg) + "]}\n";
  return t;
}

inline const std::string& four_targets_scenario() {
  static const std::string text = [] {
    const char* codes[4][4] = {{"010011100101", "011001001001", "100111110010", "010010010110"},
                               {"100110101100", "101101010110", "100101100110", "011100101010"},
                               {"110110010010", "001011110101", "100101010011", "101011001110"},
                               {"011001100110", "010110100111", "101010010110", "100110111001"}};
    std::string s = R"(name: bench-four-targets
frames: {start_ns: 4000000, period_ns: 10000000, exposure_ns: 2000000, count: 100000}
camera:
  image_width: 752
  image_height: 480
  hfov_deg: 90
  distortion_model: plumb_bob
  distortion_coefficients: [-0.05, 0.01, 0.0, 0.0, 0.0]
  psf_sigma_px: 0.6
  motion:
    kind: smooth_random
    position_m: [0.0, 0.0, 1.6]
    rpy_deg: [180, 0, 0]
    amplitude_m: [0.1, 0.1, 0.3]
    rotation_amplitude_deg: [5, 5, 30]
    min_period_s: 2.5
timebase: {synchronized: true, epoch_ns: 0, bit_period_ns: 10000000}
modulation: {kind: two_level, low: 0.3}
targets:
)";
    s += target_yaml(1, codes[0], -0.35, -0.2, 0);
    s += target_yaml(2, codes[1], 0.35, -0.2, 90);
    s += target_yaml(3, codes[2], -0.35, 0.25, 180);
    s += target_yaml(4, codes[3], 0.35, 0.25, 270);
    return s;
  }();
  return text;
}

}  // namespace tetrapulse::bench
