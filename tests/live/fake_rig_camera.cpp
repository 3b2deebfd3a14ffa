// A GigE Vision camera on 127.0.0.1 that shows the virtual rig: Aravis' in-process
// ArvGvFakeCamera whose fill-pattern callback serves a simulated rig dataset's images
// (`tetrapulse sim ... --out DIR`) in frames.csv order, each buffer stamped with its
// frame's exposure start (the simulated camera's clock is rig time). Frames travel as
// GVSP packets, with `lost_per_thousand` of them dropped by the fake camera.
//   fake_rig_camera DATASET LOST_PER_THOUSAND SECONDS
// Run only inside tests/netns/isolated; serves for SECONDS, then exits.
#include <arv.h>

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <thread>
#include <vector>

#include "tetrapulse/datasets/rig_dataset.hpp"

namespace {

struct Served {
  std::vector<cv::Mat> images;
  std::vector<int64_t> stamps;
  size_t next = 0;
  ArvFakeCamera* fake = nullptr;
};

void fill(ArvBuffer* buffer, void* data, guint32, guint32, ArvPixelFormat) {
  auto* s = static_cast<Served*>(data);
  const size_t k = s->next++;
  // The buffer's received size is set after the fill; its room is the payload.
  size_t unused = 0;
  auto* pixels = static_cast<uint8_t*>(const_cast<void*>(arv_buffer_get_data(buffer, &unused)));
  const size_t size = arv_fake_camera_get_payload(s->fake);
  if (!pixels) return;
  // Past the dataset's end: dark frames, stamps going on, so nothing is seen twice.
  const size_t last = s->images.size() - 1;
  const cv::Mat& image = s->images[std::min(k, last)];
  if (size >= image.total()) {
    if (k <= last) std::memcpy(pixels, image.data, image.total());
    else std::memset(pixels, 0, image.total());
  }
  const int64_t period = last > 0 ? (s->stamps[last] - s->stamps[0]) / static_cast<int64_t>(last) : 10'000'000;
  const int64_t stamp = k <= last ? s->stamps[k] : s->stamps[last] + static_cast<int64_t>(k - last) * period;
  arv_buffer_set_timestamp(buffer, static_cast<guint64>(stamp));
}

}  // namespace

int main(int argc, char** argv) {
  if (argc != 4) {
    std::fprintf(stderr, "usage: fake_rig_camera DATASET LOST_PER_THOUSAND SECONDS\n");
    return 2;
  }
  auto d = tetrapulse::RigDataset::open(argv[1]);
  if (!d) {
    std::fprintf(stderr, "fake_rig_camera: %s\n", d.error().what().c_str());
    return 1;
  }
  Served served;
  for (size_t i = 0; i < d->frames().size(); ++i) {
    auto image = d->load_image(i);
    if (!image || image->type() != CV_8UC1) {
      std::fprintf(stderr, "fake_rig_camera: frame %zu: not an 8-bit grey image\n", i);
      return 1;
    }
    served.images.push_back(image->clone());
    served.stamps.push_back(d->frames()[i].timestamp_ns);
  }
  // The lost-packet ratio (a fraction) is given when the camera is made, as the
  // arv-fake-gv-camera tool's -r does.
  auto* camera = ARV_GV_FAKE_CAMERA(g_object_new(ARV_TYPE_GV_FAKE_CAMERA, "interface-name", "127.0.0.1", "serial-number",
                                                 "TP-RIG-1", "gvsp-lost-ratio", std::atof(argv[2]) / 1000.0, nullptr));
  if (!camera || !arv_gv_fake_camera_is_running(camera)) {
    std::fprintf(stderr, "fake_rig_camera: cannot listen on 127.0.0.1\n");
    return 1;
  }
  ArvFakeCamera* fake = arv_gv_fake_camera_get_fake_camera(camera);
  served.fake = fake;
  arv_fake_camera_set_fill_pattern(fake, fill, &served);
  std::printf("fake_rig_camera: serving %zu frames on 127.0.0.1\n", served.images.size());
  std::fflush(stdout);
  std::this_thread::sleep_for(std::chrono::seconds(std::atoi(argv[3])));
  g_object_unref(camera);
  return 0;
}
