#pragma once
// f(0) .. f(n - 1) on up to `threads` threads: thread t takes i = t, t + threads, ... Each f(i)
// must write only its own outputs; with per-item random streams (math::mixSeeds) the results are
// then the same for any thread count.
#include <algorithm>
#include <cstddef>
#include <thread>
#include <vector>

namespace adaptive_perception::math {

template <typename F>
void parallelFor(std::size_t n, int threads, F&& f) {
  const int used = std::min<int>(threads, static_cast<int>(n));
  if (used <= 1) {
    for (std::size_t i = 0; i < n; ++i) f(i);
    return;
  }
  std::vector<std::thread> pool;
  for (int t = 0; t < used; ++t)
    pool.emplace_back([&, t] {
      for (std::size_t i = t; i < n; i += used) f(i);
    });
  for (auto& th : pool) th.join();
}

}  // namespace adaptive_perception::math
