// The clasped loop's tube in the object's collision model (tsrrt/clasp_scene.hpp).
#include <cmath>

#include <gtest/gtest.h>

#include "test/support/curves.hpp"
#include "tsrrt/clasp_scene.hpp"

namespace claspplan::test {
namespace {

TEST(LoopTube, FollowsTheLoopWithoutTwisting) {
  // A loop that turns in 3-D: one component of a torus link.
  const Curve loop = torus_link_component(2, 0, 90, 0.2, 0.05);
  TriangleMesh tube;
  tube.vertices = {Eigen::Vector3d::Zero()};  // appended after these
  const double r = 0.003;
  tsrrt::loop_tube(loop, r, tube);
  const std::vector<Eigen::Vector3d>& vertices = tube.vertices;
  const std::vector<Eigen::Vector3i>& triangles = tube.triangles;
  const int sides = 6, n = static_cast<int>(loop.size());
  ASSERT_EQ(vertices.size(), 1u + n * sides);
  ASSERT_EQ(triangles.size(), static_cast<std::size_t>(2 * n * sides));
  double longest_segment = 0.0;
  for (int i = 0; i < n; ++i)
    longest_segment = std::max(longest_segment, (loop[(i + 1) % n] - loop[i]).norm());
  for (int i = 0; i < n; ++i) {
    for (int k = 0; k < sides; ++k) {
      // Every ring vertex is at the tube's radius from its loop point ...
      EXPECT_NEAR((vertices[1 + i * sides + k] - loop[i]).norm(), r, 1e-12);
      // ... and joined to the same-numbered vertex of the next ring without a twist (the closing
      // seam may turn by the loop's holonomy, but not the segments in between).
      if (i + 1 < n) {
        EXPECT_LT((vertices[1 + (i + 1) * sides + k] - vertices[1 + i * sides + k]).norm(),
                  longest_segment + 0.5 * r)
            << "ring " << i << " vertex " << k;
      }
    }
  }
  for (const auto& t : triangles) EXPECT_GE(t.minCoeff(), 1);  // only the new vertices
}

}  // namespace
}  // namespace claspplan::test
