#pragma once
// A smooth, seeded texture for the dark scene behind the targets: value noise
// (random values on a square lattice of spacing scale_px, blended with a C1
// smoothstep) in two octaves (scale_px and scale_px / 2 at half amplitude),
// scaled to span [-1, 1]. Fixed to the image (not to the world).
#include <cstdint>

#include <opencv2/core.hpp>

namespace tetrapulse::sim {

// CV_32F, width x height, values in [-1, 1].
cv::Mat smooth_texture(int width, int height, double scale_px, uint64_t seed);

}  // namespace tetrapulse::sim
