// Pieces of clasp planning that need no robot: the loop's collision tube and the detour points.
#include "tsrrt/clasp_planning.hpp"

#include <cmath>

#include <gtest/gtest.h>

#include "test/support/curves.hpp"

namespace claspplan::test {
namespace {

TEST(LoopTube, FollowsTheLoopWithoutTwisting) {
  // A loop that turns in 3-D: one component of a torus link.
  const Curve loop = torus_link_component(2, 0, 90, 0.2, 0.05);
  std::vector<Eigen::Vector3d> vertices = {Eigen::Vector3d::Zero()};  // appended after these
  std::vector<Eigen::Vector3i> triangles;
  const double r = 0.003;
  tsrrt::loop_tube(loop, r, vertices, triangles);
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

TEST(ClaspApproaches, ComeFromOutsideTheHoleAndBothSidesOfTheLoop) {
  // A circle of radius 0.1 in a tilted plane, unevenly sampled (denser on one half).
  const Eigen::Vector3d centre(0.5, -0.1, 0.3);
  const Eigen::Vector3d u = Eigen::Vector3d(1, 0, 1).normalized(), v = Eigen::Vector3d::UnitY();
  servo::Points loop;
  for (int i = 0; i < 60; ++i) {
    const double a = i < 40 ? i * 3.14159265358979 / 40 : 3.14159265358979 * (1 + (i - 40) / 20.0);
    loop.push_back(centre + 0.1 * (std::cos(a) * u + std::sin(a) * v));
  }
  const double a = 0.7;
  const Eigen::Vector3d p = centre + 0.1 * (std::cos(a) * u + std::sin(a) * v);
  const Eigen::Vector3d t = -std::sin(a) * u + std::cos(a) * v;
  const Eigen::Vector3d out = (p - centre).normalized(), normal = t.cross(out);
  const auto points = tsrrt::clasp_approaches(loop, {p, 2.0 * t}, 0.1);
  ASSERT_EQ(points.size(), 5u);
  for (const auto& x : points) {
    EXPECT_NEAR((x - p).norm(), 0.1, 1e-9);
    EXPECT_NEAR((x - p).dot(t), 0.0, 1e-9);  // across the tangent: the hand's roll changes
    EXPECT_GE((x - p).dot(out), -1e-9);      // never from inside the hole
  }
  EXPECT_LT((points[0] - (p + 0.1 * out)).norm(), 1e-3);     // straight from outside
  EXPECT_LT((points[1] - (p + 0.1 * normal)).norm(), 1e-3);  // from both sides of the plane
  EXPECT_LT((points[2] - (p - 0.1 * normal)).norm(), 1e-3);
}

}  // namespace
}  // namespace claspplan::test
