// Splits a loop over rows across the machine's cores: the reference filters are embarrassingly
// parallel by row and this is the cheap way to use the cores.
#pragma once

#include <algorithm>
#include <thread>
#include <vector>

namespace penumbra::detail {

template <typename RowFunction>
void parallelForRows(int rows, RowFunction&& body) {
  const int workers =
      std::clamp(int(std::thread::hardware_concurrency()), 1, std::max(1, rows / 16));
  if (workers <= 1) {
    for (int y = 0; y < rows; ++y) body(y);
    return;
  }
  std::vector<std::thread> threads;
  for (int w = 0; w < workers; ++w) {
    threads.emplace_back([&, w] {
      for (int y = w; y < rows; y += workers) body(y);
    });
  }
  for (std::thread& t : threads) t.join();
}

}  // namespace penumbra::detail
