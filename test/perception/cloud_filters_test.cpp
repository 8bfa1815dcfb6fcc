// Farthest-point sampling against its definition, computed by brute force: every pick is the
// point farthest from all earlier picks (ties: the larger index), on random clouds, on a grid
// (many equal distances) and with duplicate points; the seeded subsets and the duplicate filter
// against their plain definitions.
#include "perception/cloud_filters.hpp"

#include <algorithm>
#include <random>
#include <utility>

#include <gtest/gtest.h>

#include "core/random_draws.hpp"
#include "perception/first_occurrences.hpp"

namespace claspplan::perception {
namespace {

std::vector<int> brute_force_farthest(const PointCloud& cloud, int count, std::uint64_t seed) {
  const int m = static_cast<int>(cloud.size());
  std::mt19937_64 rng(seed);
  const int start = static_cast<int>(uniform_index(rng(), m));
  std::vector<double> nearest(m);
  for (int i = 0; i < m; ++i) nearest[i] = (cloud[i] - cloud[start]).squaredNorm();
  std::vector<int> picked{start};
  while (static_cast<int>(picked.size()) < count) {
    int best = 0;
    for (int i = 1; i < m; ++i)
      if (nearest[i] >= nearest[best]) best = i;
    if (nearest[best] <= 0.0) break;
    picked.push_back(best);
    for (int j = 0; j < m; ++j) {
      double d2 = 0.0;
      for (int a = 0; a < 3; ++a)
        d2 += (cloud[best][a] - cloud[j][a]) * (cloud[best][a] - cloud[j][a]);
      if (d2 < nearest[j]) nearest[j] = d2;
    }
  }
  return picked;
}

TEST(FarthestPointSampling, MatchesItsDefinition) {
  std::mt19937_64 rng(11);
  std::uniform_real_distribution<double> u(-0.2, 0.2);
  for (int trial = 0; trial < 12; ++trial) {
    PointCloud cloud;
    const int n = 200 + 150 * trial;
    for (int i = 0; i < n; ++i) {
      if (trial % 3 == 0) {
        // A 1 cm grid: many points at equal distances, so ties decide.
        cloud.emplace_back(0.01 * (i % 7), 0.01 * ((i / 7) % 9), 0.01 * (i / 63));
      } else {
        cloud.emplace_back(u(rng), u(rng), 0.3 * u(rng));
      }
    }
    if (trial % 3 == 1) {
      for (int i = 0; i < n / 10; ++i) cloud.push_back(cloud[(7 * i) % n]);  // duplicates
    }
    for (const int count : {1, 2, n / 10, n / 2, static_cast<int>(cloud.size()) - 1}) {
      SCOPED_TRACE("trial " + std::to_string(trial) + ", count " + std::to_string(count));
      EXPECT_EQ(farthest_point_indices(cloud, count, 5 + trial),
                brute_force_farthest(cloud, count, 5 + trial));
    }
  }
}

TEST(FarthestPointSampling, StopsAtDuplicatesAndTakesAllWhenAskedForMore) {
  const PointCloud cloud(5, Eigen::Vector3d(0.1, 0.2, 0.3));
  EXPECT_EQ(farthest_point_indices(cloud, 3, 1).size(), 1u);  // one distinct point
  const PointCloud two{{0, 0, 0}, {1, 0, 0}};
  EXPECT_EQ(farthest_point_indices(two, 5, 1), (std::vector<int>{0, 1}));
  EXPECT_TRUE(farthest_point_indices({}, 3, 1).empty());
}

// Two objects 10 cm apart, one with four times the other's points, and a few stray points: with
// labels, sampling stops when the larger object holds the count, the smaller keeps its share, and
// the strays count for nothing.
TEST(FarthestPointSampling, EachObjectGetsTheSpacingItWouldHaveAlone) {
  std::mt19937_64 rng(3);
  std::uniform_real_distribution<double> u(0.0, 1.0);
  PointCloud cloud;
  for (int i = 0; i < 4000; ++i) cloud.emplace_back(0.2 * u(rng), 0.2 * u(rng), 0.0);
  for (int i = 0; i < 1000; ++i) cloud.emplace_back(0.3 + 0.1 * u(rng), 0.1 * u(rng), 0.0);
  for (int i = 0; i < 5; ++i) cloud.emplace_back(1.0 + 0.1 * i, 1.0, 1.0);
  const std::vector<int> labels = object_labels(cloud, 0.02, 0.1);
  EXPECT_EQ(labels[0], 0);
  EXPECT_EQ(labels[4000], 1);
  EXPECT_EQ(labels[5000], -1);
  EXPECT_EQ(*std::max_element(labels.begin(), labels.end()), 1);

  const std::vector<int> picked = farthest_point_indices(cloud, 400, 1, labels, 800);
  std::vector<int> per_object(2, 0);
  for (int i : picked)
    if (labels[i] >= 0) ++per_object[labels[i]];
  EXPECT_EQ(per_object[0], 400);
  // The smaller object (a quarter of the area) gets about a quarter as many, not what is left
  // of 400 after the larger.
  EXPECT_GT(per_object[1], 60);
  EXPECT_LT(per_object[1], 160);
  EXPECT_EQ(static_cast<int>(picked.size()), per_object[0] + per_object[1] + 5);
  // Without labels it is the plain sampling.
  EXPECT_EQ(farthest_point_indices(cloud, 400, 1, {}, 400), farthest_point_indices(cloud, 400, 1));
  EXPECT_THROW(farthest_point_indices(cloud, 400, 1, {0, 1}, 800), std::invalid_argument);
}

// The sparse shuffle behind random_subset() against the plain partial Fisher-Yates on an array of
// every index, then sorted: the same points, in input order, for small and large clouds.
TEST(RandomSubset, SameAsAFullPartialShuffle) {
  for (const auto& [n, count] : std::vector<std::pair<int, int>>{
           {10, 3}, {10, 9}, {1000, 1}, {1000, 500}, {200000, 20000}, {200000, 199999}}) {
    PointCloud cloud(n);
    for (int i = 0; i < n; ++i) cloud[i] = Eigen::Vector3d(i, -i, 0.5 * i);
    for (std::uint64_t seed : {1u, 7u}) {
      std::vector<int> idx(n);
      for (int i = 0; i < n; ++i) idx[i] = i;
      std::mt19937_64 rng(seed);
      for (int i = 0; i < count; ++i) std::swap(idx[i], idx[i + uniform_index(rng(), n - i)]);
      idx.resize(count);
      std::sort(idx.begin(), idx.end());
      PointCloud expected;
      for (int i : idx) expected.push_back(cloud[i]);
      EXPECT_EQ(random_subset(cloud, count, seed), expected) << n << " " << count << " " << seed;
    }
  }
}

TEST(UniquePoints, KeepsFirstOccurrencesInOrderAndTakesMinusZeroForZero) {
  const PointCloud cloud{{1, 2, 3}, {0, 0, 0}, {1, 2, 3},        {-0.0, 0, -0.0},
                         {4, 5, 6}, {0, 0, 0}, {1, 2, 3.0000001}};
  const PointCloud expected{{1, 2, 3}, {0, 0, 0}, {4, 5, 6}, {1, 2, 3.0000001}};
  EXPECT_EQ(unique_points(cloud), expected);
  EXPECT_TRUE(unique_points({}).empty());
}

TEST(FirstOccurrences, OnePerDistinctKeyInInputOrder) {
  std::vector<int> keys;
  std::mt19937_64 rng(3);
  for (int i = 0; i < 5000; ++i) keys.push_back(static_cast<int>(rng() % 700));
  std::vector<int> expected;
  std::vector<char> seen(700, 0);
  for (int i = 0; i < 5000; ++i)
    if (!seen[keys[i]]) seen[keys[i]] = 1, expected.push_back(i);
  // A poor hash (many collisions) gives the same answer, only slower.
  for (int spread : {1, 0}) {
    const auto firsts = first_occurrences(
        keys.size(), [&](std::size_t i) { return spread ? keys[i] : keys[i] % 3; },
        [&](std::size_t i, std::size_t j) { return keys[i] == keys[j]; });
    EXPECT_EQ(firsts, expected);
  }
}

}  // namespace
}  // namespace claspplan::perception
