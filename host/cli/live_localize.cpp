// The live camera as a FrameSource (live_localize.hpp).
#include "live_localize.hpp"

#include <cstdio>

#include "tetrapulse/datasets/rig_dataset.hpp"

#include "tetrapulse/host/rig_clock.hpp"

namespace tetrapulse::cli {
namespace {

constexpr uint64_t kNamedBadFrames = 5;

class LiveFrameSource final : public FrameSource {
 public:
  LiveFrameSource(std::unique_ptr<LiveCapture> live, const std::atomic<bool>& stop, std::optional<RigDatasetWriter> record)
      : live_(std::move(live)), stop_(stop), record_(std::move(record)) {}
  ~LiveFrameSource() override {
    if (record_) {
      if (auto r = record_->finish(); !r) std::fprintf(stderr, "tetrapulse localize: %s\n", r.error().what().c_str());
    }
    const LiveStats s = live_->stats();
    std::fprintf(stderr,
                 "tetrapulse localize: %s; %llu buffers, %llu bad, %llu dropped by the queue, %llu exposures without a "
                 "frame, %llu frames without an exposure; stamps: %s\n",
                 latency_.summary().c_str(), static_cast<unsigned long long>(s.grabbed),
                 static_cast<unsigned long long>(s.bad_buffers), static_cast<unsigned long long>(s.queue_drops),
                 static_cast<unsigned long long>(s.match.dropped), static_cast<unsigned long long>(s.match.unmatched_frames),
                 stamp_source(s).c_str());
    if (const std::string t = live_->transport_summary(); !t.empty()) std::fprintf(stderr, "tetrapulse localize: %s\n", t.c_str());
    if (live_->error()) std::fprintf(stderr, "tetrapulse localize: %s\n", live_->error()->c_str());
  }

  DatasetResult<std::optional<Frame>> next() override {
    // The previous frame's poses are out: its latency from the end of its exposure.
    if (previous_end_ns_) latency_.add(host::monotonic_now_ns() - *previous_end_ns_);
    previous_end_ns_.reset();
    auto f = live_->next(stop_);
    // A bad buffer costs its frame only: named (the first few; on a lossy link the
    // summary counts the rest) and passed over, so the loop sees good frames only.
    while (f && f->frame.bad) {
      if (++bad_named_ <= kNamedBadFrames) {
        std::fprintf(stderr, "tetrapulse localize: skipped %s%s\n", f->frame.bad->c_str(),
                     bad_named_ == kNamedBadFrames ? " (further ones only counted)" : "");
      }
      f = live_->next(stop_);
    }
    if (!f) return std::optional<Frame>{};
    Frame out;
    out.frame = f->stamp.exposure.frame;
    out.timestamp_ns = f->stamp.exposure.timestamp_ns;
    out.exposure_ns = f->stamp.exposure.exposure_ns;
    out.name = live_->camera_name() + " frame " + std::to_string(f->frame.sequence);
    out.image = std::move(f->frame.image);
    if (record_) {
      if (auto r = record_->add_frame(out.frame, out.timestamp_ns, out.exposure_ns, out.image); !r) return tl::unexpected(r.error());
    }
    previous_end_ns_ = f->exposure_end_host_ns;
    monotonic_minus_rig_ns_ = f->exposure_end_host_ns - (out.timestamp_ns + out.exposure_ns);
    return std::optional<Frame>(std::move(out));
  }
  std::optional<size_t> count() const override { return std::nullopt; }
  LiveLoopState state() const { return LiveLoopState{live_->stats(), monotonic_minus_rig_ns_}; }

 private:
  std::unique_ptr<LiveCapture> live_;
  const std::atomic<bool>& stop_;
  std::optional<RigDatasetWriter> record_;
  LatencyStats latency_;
  std::optional<int64_t> previous_end_ns_;
  uint64_t bad_named_ = 0;
  int64_t monotonic_minus_rig_ns_ = 0;
};

}  // namespace

bool is_live_camera_spec(const std::string& spec) {
  return spec.rfind("aravis:", 0) == 0 || spec.rfind("v4l2:", 0) == 0;
}

tl::expected<std::unique_ptr<FrameSource>, std::string> live_frame_source(const LiveArgs& args, const CameraInfo& camera,
                                                                          const TargetsFile& targets,
                                                                          const std::atomic<bool>& stop) {
  auto live = LiveCapture::open(args, camera.width, camera.height,
                                [](const std::string& n) { std::fprintf(stderr, "tetrapulse localize: %s\n", n.c_str()); });
  if (!live) return tl::unexpected(live.error());
  std::optional<RigDatasetWriter> record;
  if (!args.record.empty()) {
    auto w = RigDatasetWriter::create(args.record, camera, targets);
    if (!w) return tl::unexpected(w.error().what());
    record = std::move(*w);
  }
  return std::unique_ptr<FrameSource>(new LiveFrameSource(std::move(*live), stop, std::move(record)));
}

std::optional<LiveLoopState> live_loop_state(const FrameSource& source) {
  const auto* live = dynamic_cast<const LiveFrameSource*>(&source);
  if (!live) return std::nullopt;
  return live->state();
}

}  // namespace tetrapulse::cli
