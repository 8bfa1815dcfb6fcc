// The one way work is spread over the machine's cores. Every helper gives each index (or task) the
// same work whatever the number of threads, so results never depend on it; the first exception
// (in chunk, worker or argument order) is rethrown once every thread has ended.
#pragma once

#include <algorithm>
#include <atomic>
#include <cstddef>
#include <exception>
#include <thread>
#include <vector>

namespace claspplan {

/// The threads for n items: `threads` (0: all cores), at least 1, at most n (when n > 0).
inline int thread_count(int threads, std::size_t n) {
  const int cores = static_cast<int>(std::max(1u, std::thread::hardware_concurrency()));
  const int wanted = threads > 0 ? threads : cores;
  return static_cast<int>(std::max<std::size_t>(1, std::min<std::size_t>(wanted, n)));
}

namespace parallel_detail {

// Runs work(t) for t in [0, count): t = 0 on the calling thread, the others on their own.
template <class Work>
void run_workers(int count, const Work& work) {
  std::vector<std::exception_ptr> failed(count);
  const auto guarded = [&](int t) {
    try {
      work(t);
    } catch (...) {
      failed[t] = std::current_exception();
    }
  };
  std::vector<std::thread> pool;
  for (int t = 1; t < count; ++t) pool.emplace_back(guarded, t);
  guarded(0);
  for (auto& t : pool) t.join();
  for (const auto& f : failed)
    if (f) std::rethrow_exception(f);
}

}  // namespace parallel_detail

/// Calls body(begin, end) on disjoint contiguous chunks covering [0, n): one chunk per thread,
/// thread_count(threads, n) of them, the first chunk on the calling thread.
template <class Body>
void parallel_chunks(std::size_t n, int threads, Body&& body) {
  const int chunks = thread_count(threads, n);
  parallel_detail::run_workers(chunks, [&](int c) { body(n * c / chunks, n * (c + 1) / chunks); });
}

/// Calls body(i, worker) for every i in [0, n), the indices taken one at a time, in any order, by
/// thread_count(threads, n) workers (worker 0 is the calling thread). A worker index is used by one
/// thread only, so per-worker state (a search's scratch space, a collision world) needs no lock:
/// for items of uneven cost, where fixed chunks would leave cores idle.
template <class Body>
void parallel_for(std::size_t n, int threads, Body&& body) {
  std::atomic<std::size_t> next{0};
  parallel_detail::run_workers(thread_count(threads, n), [&](int worker) {
    for (std::size_t i; (i = next++) < n;) body(i, worker);
  });
}

/// Runs a() and b() side by side: b on a second thread unless `threads` is 1 or the machine has
/// one core (then one after the other).
template <class A, class B>
void parallel_invoke(A&& a, B&& b, int threads = 0) {
  if (thread_count(threads, 2) == 1) {
    a();
    b();
    return;
  }
  parallel_detail::run_workers(2, [&](int t) { t == 0 ? a() : b(); });
}

}  // namespace claspplan
