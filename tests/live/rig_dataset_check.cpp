// Checks a folder against the rig dataset contract (docs/rig-dataset.md), as a
// recorder's output must pass it: camera.yaml, targets.yaml and frames.csv read
// without a skipped line, frame numbers and exposure starts strictly increasing,
// every image present and camera-sized. `rig_dataset_check DIR [MIN_FRAMES]`;
// prints the first problem and exits 1, else prints the frame count.
#include <cstdio>
#include <cstdlib>

#include "tetrapulse/datasets/rig_dataset.hpp"

int main(int argc, char** argv) {
  if (argc < 2) {
    std::fprintf(stderr, "usage: rig_dataset_check DIR [MIN_FRAMES]\n");
    return 2;
  }
  const long min_frames = argc > 2 ? std::strtol(argv[2], nullptr, 10) : 1;
  auto d = tetrapulse::RigDataset::open(argv[1]);
  if (!d) {
    std::fprintf(stderr, "rig_dataset_check: %s\n", d.error().what().c_str());
    return 1;
  }
  if (!d->skipped_lines().empty()) {
    std::fprintf(stderr, "rig_dataset_check: %s\n", d->skipped_lines().front().what().c_str());
    return 1;
  }
  const auto& frames = d->frames();
  if (static_cast<long>(frames.size()) < min_frames) {
    std::fprintf(stderr, "rig_dataset_check: %s: %zu frames, %ld expected\n", argv[1], frames.size(), min_frames);
    return 1;
  }
  for (size_t i = 0; i < frames.size(); ++i) {
    if (i > 0 && (frames[i].frame <= frames[i - 1].frame || frames[i].timestamp_ns <= frames[i - 1].timestamp_ns)) {
      std::fprintf(stderr, "rig_dataset_check: %s: frame %lld does not follow frame %lld in number and time\n", argv[1],
                   static_cast<long long>(frames[i].frame), static_cast<long long>(frames[i - 1].frame));
      return 1;
    }
    if (frames[i].exposure_ns <= 0) {
      std::fprintf(stderr, "rig_dataset_check: %s: frame %lld has no exposure\n", argv[1], static_cast<long long>(frames[i].frame));
      return 1;
    }
    if (auto image = d->load_image(i); !image) {
      std::fprintf(stderr, "rig_dataset_check: %s\n", image.error().what().c_str());
      return 1;
    }
  }
  std::printf("%s: %zu frames pass the rig dataset contract\n", argv[1], frames.size());
  return 0;
}
