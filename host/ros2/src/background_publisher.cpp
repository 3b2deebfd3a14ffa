#include "tetrapulse/ros2/background_publisher.hpp"

#include <chrono>
#include <condition_variable>
#include <deque>
#include <mutex>
#include <optional>
#include <thread>
#include <variant>

namespace tetrapulse::ros2 {

namespace {

using Clock = std::chrono::steady_clock;
using Item = std::variant<std::vector<TargetPose>, LocalizerStatus>;

class BackgroundPublisher final : public PosePublisher {
 public:
  BackgroundPublisher(std::unique_ptr<PosePublisher> inner, size_t capacity, WhenQueueFull when_full)
      : inner_(std::move(inner)), capacity_(capacity == 0 ? 1 : capacity), when_full_(when_full),
        thread_([this] { run(); }) {}

  ~BackgroundPublisher() override {
    {
      std::lock_guard<std::mutex> lock(mutex_);
      stop_ = true;
    }
    changed_.notify_all();
    thread_.join();
  }

 private:
  Ros2Result<void> do_publish(const std::vector<TargetPose>& poses) override { return enqueue(Item(poses)); }
  Ros2Result<void> do_publish_status(const LocalizerStatus& status) override { return enqueue(Item(status)); }

  int do_wait_for_readers(int64_t timeout_ns, int64_t settle_ns) override {
    std::lock_guard<std::mutex> lock(inner_mutex_);
    return inner_->wait_for_readers(timeout_ns, settle_ns);
  }

  bool do_wait_for_acknowledgments(int64_t timeout_ns) override {
    const auto deadline = Clock::now() + std::chrono::nanoseconds(timeout_ns);
    {
      std::unique_lock<std::mutex> lock(mutex_);
      if (!changed_.wait_until(lock, deadline, [this] { return queue_.empty() && !busy_; })) return false;
    }
    const int64_t left = std::chrono::duration_cast<std::chrono::nanoseconds>(deadline - Clock::now()).count();
    std::lock_guard<std::mutex> lock(inner_mutex_);
    return inner_->wait_for_acknowledgments(left > 0 ? left : 0);
  }

  PublishCounters do_counters() const override {
    PublishCounters c;
    {
      std::lock_guard<std::mutex> lock(inner_mutex_);
      c = inner_->counters();
    }
    std::lock_guard<std::mutex> lock(mutex_);
    c.dropped += dropped_;
    return c;
  }

  Ros2Result<void> enqueue(Item item) {
    std::unique_lock<std::mutex> lock(mutex_);
    if (error_) return tl::unexpected(*error_);
    if (queue_.size() >= capacity_) {
      if (when_full_ == WhenQueueFull::kDropOldest) {
        queue_.pop_front();
        ++dropped_;
      } else {
        changed_.wait(lock, [this] { return queue_.size() < capacity_ || error_; });
        if (error_) return tl::unexpected(*error_);
      }
    }
    queue_.push_back(std::move(item));
    lock.unlock();
    changed_.notify_all();
    return {};
  }

  void run() {
    for (;;) {
      Item item;
      {
        std::unique_lock<std::mutex> lock(mutex_);
        changed_.wait(lock, [this] { return stop_ || !queue_.empty(); });
        if (queue_.empty()) return;  // stopping, and everything was written
        item = std::move(queue_.front());
        queue_.pop_front();
        busy_ = true;
      }
      changed_.notify_all();  // room in the queue
      Ros2Result<void> r;
      {
        std::lock_guard<std::mutex> lock(inner_mutex_);
        r = std::holds_alternative<LocalizerStatus>(item) ? inner_->publish_status(std::get<LocalizerStatus>(item))
                                                          : inner_->publish(std::get<std::vector<TargetPose>>(item));
      }
      {
        std::lock_guard<std::mutex> lock(mutex_);
        busy_ = false;
        if (!r && !error_) error_ = r.error();
      }
      changed_.notify_all();
    }
  }

  std::unique_ptr<PosePublisher> inner_;
  mutable std::mutex inner_mutex_;  // the wrapped publisher is called by one thread at a time
  const size_t capacity_;
  const WhenQueueFull when_full_;
  mutable std::mutex mutex_;        // everything below
  std::condition_variable changed_;
  std::deque<Item> queue_;
  bool busy_ = false;               // the thread is writing an item it took
  bool stop_ = false;
  std::optional<Ros2Error> error_;
  uint64_t dropped_ = 0;
  std::thread thread_;              // last: starts once the rest exists
};

}  // namespace

std::unique_ptr<PosePublisher> publish_in_background(std::unique_ptr<PosePublisher> publisher, size_t queue_frames,
                                                     WhenQueueFull when_full) {
  return std::make_unique<BackgroundPublisher>(std::move(publisher), queue_frames, when_full);
}

}  // namespace tetrapulse::ros2
