// Loops split over the machine's cores in fixed contiguous chunks: each index is handled exactly
// as it would be on one thread, so results never depend on the number of threads.
#pragma once

#include <algorithm>
#include <cstddef>
#include <exception>
#include <thread>
#include <vector>

namespace claspplan {

/// Calls body(begin, end) on disjoint chunks covering [0, n): one chunk per thread, `threads`
/// threads at most (0: all cores), the first chunk on the calling thread. The first exception
/// thrown (in chunk order) is rethrown once every chunk has ended.
template <class Body>
void parallel_chunks(std::size_t n, int threads, Body&& body) {
  const std::size_t cores = std::max(1u, std::thread::hardware_concurrency());
  const std::size_t chunks =
      std::max<std::size_t>(1, std::min(n, threads > 0 ? std::size_t(threads) : cores));
  std::vector<std::exception_ptr> failed(chunks);
  const auto run = [&](std::size_t c) {
    try {
      body(n * c / chunks, n * (c + 1) / chunks);
    } catch (...) {
      failed[c] = std::current_exception();
    }
  };
  std::vector<std::thread> pool;
  for (std::size_t c = 1; c < chunks; ++c) pool.emplace_back(run, c);
  run(0);
  for (auto& t : pool) t.join();
  for (const auto& f : failed)
    if (f) std::rethrow_exception(f);
}

}  // namespace claspplan
