// The parallel-for helpers: every index handled exactly once whatever the thread count, per-worker
// state never shared, and a failure anywhere reaches the caller (the first in chunk or worker
// order).
#include "core/parallel.hpp"

#include <atomic>
#include <stdexcept>
#include <string>
#include <thread>
#include <vector>

#include <gtest/gtest.h>

namespace claspplan {
namespace {

TEST(ParallelChunks, CoversEveryIndexOnce) {
  for (int threads : {0, 1, 2, 7})
    for (std::size_t n : {std::size_t(0), std::size_t(1), std::size_t(5), std::size_t(1000)}) {
      std::vector<std::atomic<int>> hits(n);
      parallel_chunks(n, threads, [&](std::size_t begin, std::size_t end) {
        for (std::size_t i = begin; i < end; ++i) ++hits[i];
      });
      for (std::size_t i = 0; i < n; ++i)
        EXPECT_EQ(hits[i].load(), 1)
            << "index " << i << " of " << n << ", " << threads << " threads";
    }
}

TEST(ParallelChunks, RethrowsTheFirstChunksFailure) {
  try {
    parallel_chunks(100, 4, [](std::size_t begin, std::size_t) {
      if (begin > 0) throw std::runtime_error("chunk at " + std::to_string(begin));
    });
    FAIL() << "no exception reached the caller";
  } catch (const std::runtime_error& e) {
    EXPECT_STREQ(e.what(), "chunk at 25");
  }
}

TEST(ParallelFor, CoversEveryIndexOnceAndKeepsEachWorkerOnOneThread) {
  for (int threads : {0, 1, 2, 7})
    for (std::size_t n : {std::size_t(0), std::size_t(1), std::size_t(5), std::size_t(1000)}) {
      std::vector<std::atomic<int>> hits(n);
      const int workers = thread_count(threads, n);
      std::vector<std::thread::id> owner(workers);
      std::vector<char> clash(workers, 0);
      parallel_for(n, threads, [&](std::size_t i, int w) {
        ASSERT_GE(w, 0);
        ASSERT_LT(w, workers);
        if (owner[w] == std::thread::id()) owner[w] = std::this_thread::get_id();
        clash[w] |= owner[w] != std::this_thread::get_id();
        ++hits[i];
      });
      for (std::size_t i = 0; i < n; ++i) EXPECT_EQ(hits[i].load(), 1) << i << " of " << n;
      for (int w = 0; w < workers; ++w) EXPECT_FALSE(clash[w]) << "worker " << w;
    }
}

TEST(ParallelFor, RethrowsAFailureAfterEveryWorkerEnded) {
  std::atomic<int> done{0};
  EXPECT_THROW(parallel_for(200, 4,
                            [&](std::size_t i, int) {
                              if (i == 17) throw std::runtime_error("index 17");
                              ++done;
                            }),
               std::runtime_error);
  EXPECT_GE(done.load(), 1);
}

TEST(ParallelInvoke, RunsBothAndRethrows) {
  for (int threads : {0, 1}) {
    int a = 0, b = 0;
    parallel_invoke([&] { a = 1; }, [&] { b = 2; }, threads);
    EXPECT_EQ(a + b, 3) << threads;
    EXPECT_THROW(parallel_invoke([] {}, [] { throw std::runtime_error("b"); }, threads),
                 std::runtime_error);
  }
}

TEST(ThreadCount, AtLeastOneAtMostTheItems) {
  EXPECT_EQ(thread_count(4, 2), 2);
  EXPECT_EQ(thread_count(1, 100), 1);
  EXPECT_EQ(thread_count(3, 0), 1);
  EXPECT_GE(thread_count(0, 1000), 1);
}

}  // namespace
}  // namespace claspplan
