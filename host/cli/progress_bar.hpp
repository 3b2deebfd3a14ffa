#pragma once
// A progress bar on standard error for long runs, drawn only when standard error
// is a terminal (never into logs or pipes).
#include <chrono>
#include <cstddef>
#include <optional>

namespace tetrapulse::cli {

class ProgressBar {
 public:
  // `total`: the number of steps when known (else a counter is shown).
  ProgressBar(std::optional<size_t> total, bool wanted);
  void advance();
  void finish();  // clears the line

 private:
  void draw();
  std::optional<size_t> total_;
  bool enabled_;
  size_t done_ = 0;
  std::chrono::steady_clock::time_point start_, last_draw_;
};

}  // namespace tetrapulse::cli
