// A GigE Vision camera on 127.0.0.1 that shows the virtual rig: Aravis' ArvFakeCamera
// (register map, GenICam features) whose fill-pattern callback serves a simulated rig
// dataset's images (`tetrapulse sim ... --out DIR`) in frames.csv order, each buffer
// stamped with its frame's exposure start (the simulated camera's clock is rig time).
// Frames travel as GVSP packets through fake_gige_server (packet resend answered),
// with `lost_per_thousand` of all packets dropped.
//   fake_rig_camera DATASET LOST_PER_THOUSAND SECONDS [--no-resend]
// Run only inside tests/netns/isolated; serves for SECONDS (or until SIGTERM/SIGINT),
// then prints what it sent: "fake_rig_camera: sent F frames, ...".
#include <arv.h>

#include <algorithm>
#include <atomic>
#include <csignal>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <vector>

#include "fake_gige_server.hpp"
#include "tetrapulse/datasets/rig_dataset.hpp"

namespace {

std::atomic<bool> g_stop{false};
void on_signal(int) { g_stop = true; }

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
  const bool no_resend = argc == 5 && std::strcmp(argv[4], "--no-resend") == 0;
  if (argc != 4 && !no_resend) {
    std::fprintf(stderr, "usage: fake_rig_camera DATASET LOST_PER_THOUSAND SECONDS [--no-resend]\n");
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
      std::fprintf(stderr, "fake_rig_camera: %s: frame %zu: not an 8-bit grey image\n", argv[1], i);
      return 1;
    }
    served.images.push_back(image->clone());
    served.stamps.push_back(d->frames()[i].timestamp_ns);
  }
  if (served.images.empty()) {
    std::fprintf(stderr, "fake_rig_camera: %s: no frames\n", argv[1]);
    return 1;
  }
  ArvFakeCamera* fake = arv_fake_camera_new("TP-RIG-1");
  served.fake = fake;
  arv_fake_camera_set_fill_pattern(fake, fill, &served);
  std::signal(SIGTERM, on_signal);
  std::signal(SIGINT, on_signal);
  tetrapulse::live_test::FakeGigeOptions options;
  options.lost_ratio = std::atof(argv[2]) / 1000.0;
  options.resend = !no_resend;
  tetrapulse::live_test::FakeGigeCounters c;
  std::printf("fake_rig_camera: serving %zu frames on %s, %.1f %% of packets lost, resend %s\n", served.images.size(),
              options.address.c_str(), options.lost_ratio * 100, options.resend ? "answered" : "ignored");
  std::fflush(stdout);
  const auto failed = tetrapulse::live_test::serve_fake_gige(fake, options, std::atoi(argv[3]), g_stop, &c);
  g_object_unref(fake);
  if (failed) {
    std::fprintf(stderr, "fake_rig_camera: %s\n", failed->c_str());
    return 1;
  }
  std::printf("fake_rig_camera: sent %llu frames, %llu packets (%llu lost), %llu resend requests for %llu packets: "
              "%llu resent (%llu lost again), %llu unavailable\n",
              static_cast<unsigned long long>(c.frames_sent), static_cast<unsigned long long>(c.packets_sent + c.packets_lost),
              static_cast<unsigned long long>(c.packets_lost), static_cast<unsigned long long>(c.resend_requests),
              static_cast<unsigned long long>(c.packets_requested), static_cast<unsigned long long>(c.packets_resent),
              static_cast<unsigned long long>(c.resent_lost), static_cast<unsigned long long>(c.packets_unavailable));
  return 0;
}
