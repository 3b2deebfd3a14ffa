#include "progress_bar.hpp"

#include <cstdio>
#include <string>

#include <unistd.h>

namespace tetrapulse::cli {

ProgressBar::ProgressBar(std::optional<size_t> total, bool wanted)
    : total_(total), enabled_(wanted && ::isatty(STDERR_FILENO) == 1), start_(std::chrono::steady_clock::now()),
      last_draw_(start_) {}

void ProgressBar::advance() {
  ++done_;
  if (!enabled_) return;
  const auto now = std::chrono::steady_clock::now();
  if (now - last_draw_ < std::chrono::milliseconds(100) && (!total_ || done_ < *total_)) return;
  last_draw_ = now;
  draw();
}

void ProgressBar::draw() {
  const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start_).count();
  const double rate = seconds > 0 ? double(done_) / seconds : 0;
  if (total_ && *total_ > 0) {
    constexpr int kWidth = 30;
    const int filled = int(double(kWidth) * double(done_) / double(*total_));
    std::string bar(size_t(kWidth), ' ');
    for (int i = 0; i < filled && i < kWidth; ++i) bar[size_t(i)] = '=';
    std::fprintf(stderr, "\r[%s] %zu/%zu frames, %.0f frames/s ", bar.c_str(), done_, *total_, rate);
  } else {
    std::fprintf(stderr, "\r%zu frames, %.0f frames/s ", done_, rate);
  }
  std::fflush(stderr);
}

void ProgressBar::finish() {
  if (!enabled_ || done_ == 0) return;
  std::fprintf(stderr, "\r\033[K");
  std::fflush(stderr);
}

}  // namespace tetrapulse::cli
