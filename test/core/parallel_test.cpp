// parallel_chunks: every index handled exactly once whatever the thread count, and a failure in
// any chunk reaches the caller (the first in chunk order).
#include "core/parallel.hpp"

#include <atomic>
#include <stdexcept>
#include <string>

#include <gtest/gtest.h>

namespace claspplan::perception {
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

}  // namespace
}  // namespace claspplan::perception
