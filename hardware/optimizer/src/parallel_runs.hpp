#pragma once
// Runs f(0) .. f(count - 1) on `threads` std::threads and returns the results in
// index order. Each f(i) must depend on i alone (not on which thread runs it or
// when), so the results are the same for any thread count.
#include <algorithm>
#include <atomic>
#include <thread>
#include <vector>

namespace tetrapulse::hardware {

template <typename Result, typename Fn>
std::vector<Result> run_in_parallel(int count, int threads, const Fn& f) {
  std::vector<Result> results(static_cast<size_t>(std::max(count, 0)));
  std::atomic<int> next{0};
  auto worker = [&] {
    for (int i = next++; i < count; i = next++) results[static_cast<size_t>(i)] = f(i);
  };
  const int extra = std::min(std::max(threads, 1), std::max(count, 1)) - 1;
  std::vector<std::thread> pool;
  pool.reserve(static_cast<size_t>(extra));
  for (int t = 0; t < extra; ++t) pool.emplace_back(worker);
  worker();
  for (std::thread& t : pool) t.join();
  return results;
}

}  // namespace tetrapulse::hardware
