// The background queue around a publisher: order kept, a replay loses nothing, a
// live loop drops the oldest and says so, errors come back, the end drains.
#include "tetrapulse/ros2/background_publisher.hpp"

#include <gtest/gtest.h>

#include <condition_variable>
#include <mutex>

namespace tetrapulse::ros2 {
namespace {

// Records what it is asked to publish; holds its writer thread while `gate` is closed.
struct Recording {
  std::mutex mutex;
  std::condition_variable changed;
  bool open = true;
  int entered = 0;  // publish calls begun
  std::vector<int64_t> frames;  // mid_exposure_ns of each frame's first pose (-1: a status)
  bool fail_next = false;
};

class RecordingPublisher final : public PosePublisher {
 public:
  explicit RecordingPublisher(Recording* r) : r_(r) {}

 private:
  Ros2Result<void> record(int64_t what) {
    std::unique_lock<std::mutex> lock(r_->mutex);
    ++r_->entered;
    r_->changed.notify_all();
    r_->changed.wait(lock, [this] { return r_->open; });
    if (r_->fail_next) return ros2_error(Ros2Error::Kind::kDdsFailed, "writing /tf: test");
    r_->frames.push_back(what);
    return {};
  }
  Ros2Result<void> do_publish(const std::vector<TargetPose>& poses) override {
    return record(poses.empty() ? 0 : poses[0].mid_exposure_ns);
  }
  Ros2Result<void> do_publish_status(const LocalizerStatus&) override { return record(-1); }
  int do_wait_for_readers(int64_t, int64_t) override { return 7; }
  bool do_wait_for_acknowledgments(int64_t) override { return true; }
  PublishCounters do_counters() const override {
    std::lock_guard<std::mutex> lock(r_->mutex);
    PublishCounters c;
    c.frames = r_->frames.size();
    return c;
  }
  Recording* r_;
};

std::vector<TargetPose> frame(int64_t t) {
  TargetPose p;
  p.mid_exposure_ns = t;
  return {p};
}

void close_gate(Recording& r) {
  std::lock_guard<std::mutex> lock(r.mutex);
  r.open = false;
}
void open_gate(Recording& r) {
  std::lock_guard<std::mutex> lock(r.mutex);
  r.open = true;
  r.changed.notify_all();
}
// Waits until the writer thread is inside its n-th publish call.
void wait_entered(Recording& r, int n) {
  std::unique_lock<std::mutex> lock(r.mutex);
  r.changed.wait(lock, [&] { return r.entered >= n; });
}

TEST(BackgroundPublisher, KeepsOrderAndDrainsBeforeAcknowledging) {
  Recording r;
  auto p = publish_in_background(std::make_unique<RecordingPublisher>(&r), 4, WhenQueueFull::kWait);
  EXPECT_EQ(p->wait_for_readers(0, 0), 7);
  for (int64_t t = 1; t <= 50; ++t) {
    ASSERT_TRUE(p->publish(frame(t)));
    if (t % 10 == 0) {
      ASSERT_TRUE(p->publish_status(LocalizerStatus{}));
    }
  }
  EXPECT_TRUE(p->wait_for_acknowledgments(60'000'000'000));
  ASSERT_EQ(r.frames.size(), 55u);  // every one, although the queue holds 4
  std::vector<int64_t> expected;
  for (int64_t t = 1; t <= 50; ++t) {
    expected.push_back(t);
    if (t % 10 == 0) expected.push_back(-1);
  }
  EXPECT_EQ(r.frames, expected);
  EXPECT_EQ(p->counters().dropped, 0u);
}

TEST(BackgroundPublisher, LiveDropsTheOldestWhenTheWriterFallsBehind) {
  Recording r;
  close_gate(r);
  auto p = publish_in_background(std::make_unique<RecordingPublisher>(&r), 3, WhenQueueFull::kDropOldest);
  ASSERT_TRUE(p->publish(frame(1)));
  wait_entered(r, 1);  // frame 1 is being written, held at the gate
  for (int64_t t = 2; t <= 10; ++t) ASSERT_TRUE(p->publish(frame(t)));  // never blocks
  open_gate(r);
  EXPECT_TRUE(p->wait_for_acknowledgments(60'000'000'000));
  EXPECT_EQ(r.frames, (std::vector<int64_t>{1, 8, 9, 10}));  // the newest three waited
  EXPECT_EQ(p->counters().dropped, 6u);
  EXPECT_EQ(p->counters().frames, 4u);
}

TEST(BackgroundPublisher, AnErrorComesBackFromTheNextCall) {
  Recording r;
  r.fail_next = true;
  auto p = publish_in_background(std::make_unique<RecordingPublisher>(&r), 8, WhenQueueFull::kWait);
  ASSERT_TRUE(p->publish(frame(1)));
  EXPECT_TRUE(p->wait_for_acknowledgments(60'000'000'000));  // drained (the write failed)
  const auto next = p->publish(frame(2));
  ASSERT_FALSE(next);
  EXPECT_EQ(next.error().message, "writing /tf: test");
}

TEST(BackgroundPublisher, AcknowledgmentWaitIsBounded) {
  Recording r;
  close_gate(r);
  auto p = publish_in_background(std::make_unique<RecordingPublisher>(&r), 8, WhenQueueFull::kWait);
  ASSERT_TRUE(p->publish(frame(1)));
  wait_entered(r, 1);
  EXPECT_FALSE(p->wait_for_acknowledgments(20'000'000));  // held: gives up after 20 ms
  open_gate(r);
  EXPECT_TRUE(p->wait_for_acknowledgments(60'000'000'000));
}

}  // namespace
}  // namespace tetrapulse::ros2
