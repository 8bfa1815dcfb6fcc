// The exact sphere and capsule queries (robots/triangle_tree.hpp) against sampling and brute
// force, and a collision world using them against FCL's answers.
#include "robots/triangle_tree.hpp"

#include <algorithm>
#include <cmath>
#include <random>

#include <gtest/gtest.h>

#include "robots/collision_world.hpp"
#include "test/robots/test_meshes.hpp"

namespace claspplan::robots {
namespace {

using Eigen::Vector3d;

Vector3d random_point(std::mt19937_64& rng, double scale) {
  std::uniform_real_distribution<double> u(-scale, scale);
  return {u(rng), u(rng), u(rng)};
}

// The distance of two point sets sampled densely on the segment and the triangle.
double sampled_distance(const Vector3d& p0, const Vector3d& p1, const Vector3d& a,
                        const Vector3d& b, const Vector3d& c, int n) {
  double best = std::numeric_limits<double>::infinity();
  for (int i = 0; i <= n; ++i) {
    const Vector3d p = p0 + (p1 - p0) * (static_cast<double>(i) / n);
    for (int j = 0; j <= n; ++j)
      for (int k = 0; j + k <= n; ++k) {
        const Vector3d q =
            a + (b - a) * (static_cast<double>(j) / n) + (c - a) * (static_cast<double>(k) / n);
        best = std::min(best, (p - q).norm());
      }
  }
  return best;
}

// Both answers occur, each in more than a tenth of the trials.
void expect_mixed(int positives, int trials) {
  EXPECT_GT(positives, trials / 10);
  EXPECT_LT(positives, trials - trials / 10);
}

TEST(TriangleTree, SegmentTriangleDistanceMatchesSampling) {
  std::mt19937_64 rng(3);
  int crossing = 0;
  for (int trial = 0; trial < 300; ++trial) {
    const Vector3d a = random_point(rng, 1), b = random_point(rng, 1), c = random_point(rng, 1);
    const Vector3d p0 = random_point(rng, 1.5), p1 = random_point(rng, 1.5);
    const double d = std::sqrt(segment_triangle_distance_sq(p0, p1, a, b, c));
    const double sampled = sampled_distance(p0, p1, a, b, c, 60);
    // Samples can only be farther; 60 steps over a few units leave them within 0.1.
    EXPECT_LE(d, sampled + 1e-12) << trial;
    EXPECT_GE(d, sampled - 0.1) << trial;
    crossing += d == 0.0;
  }
  EXPECT_GT(crossing, 5);  // crossings occur and give 0
}

TEST(TriangleTree, CapsuleQueryEqualsBruteForce) {
  const test::TriMesh ring = test::torus_mesh(0.10, 0.015, 60, 30);
  const TriangleTree tree(ring.vertices, ring.triangles);
  std::mt19937_64 rng(5);
  int touching = 0;
  const int trials = 1000;
  for (int trial = 0; trial < trials; ++trial) {
    const Vector3d p0 = random_point(rng, 0.13);
    const Vector3d p1 = trial % 4 == 0 ? p0 : Vector3d(p0 + random_point(rng, 0.05));
    const double radius = 0.002 + 0.02 * std::uniform_real_distribution<double>(0, 1)(rng);
    bool expected = false;
    for (const auto& t : ring.triangles) {
      expected |= segment_triangle_distance_sq(p0, p1, ring.vertices[t[0]], ring.vertices[t[1]],
                                               ring.vertices[t[2]]) <= radius * radius;
    }
    EXPECT_EQ(tree.touches_capsule(p0, p1, radius), expected) << trial;
    touching += expected;
  }
  expect_mixed(touching, trials);
}

// The iCub's fingers (capsules) around a ring: the exact shapes give FCL's verdict everywhere.
TEST(TriangleTree, ExactRoundShapesGiveFclVerdicts) {
  const RobotModel model = load_robot("kr5_icub");
  const test::TriMesh ring = test::torus_mesh(0.10, 0.015, 150, 100);
  Eigen::Isometry3d pose = Eigen::Isometry3d::Identity();
  pose.linear() = Eigen::AngleAxisd(M_PI / 2, Eigen::Vector3d::UnitY()).toRotationMatrix();
  pose.translation() = Vector3d(0.68, 0.0, 0.83 + 0.10);
  CollisionWorld fcl_world(model), exact_world(model);
  exact_world.set_exact_round_shapes(true);
  for (CollisionWorld* w : {&fcl_world, &exact_world}) {
    w->set_self_collision(false);
    w->set_object(ring.vertices, ring.triangles);
  }
  std::mt19937_64 rng(11);
  std::uniform_real_distribution<double> jitter(-0.05, 0.05), close(0.0, 0.6), shift(-0.03, 0.03);
  int hits = 0;
  for (int k = 0; k < 400; ++k) {
    Eigen::VectorXd q = model.home;
    for (int i = 0; i < model.arm_dof; ++i) q[i] += jitter(rng);
    for (int i = model.arm_dof; i < model.dof(); ++i) q[i] += close(rng);
    Eigen::Isometry3d moved = pose;
    moved.translation() += Vector3d(shift(rng), shift(rng), shift(rng));
    fcl_world.set_object_pose(moved);
    exact_world.set_object_pose(moved);
    const bool fcl_hit = fcl_world.in_collision(model.clamp(q));
    EXPECT_EQ(exact_world.in_collision(model.clamp(q)), fcl_hit) << k;
    hits += fcl_hit;
  }
  expect_mixed(hits, 400);
}

TEST(TriangleTree, ExactShapesMustBeChosenBeforeTheObject) {
  const RobotModel model = load_robot("kr5_icub");
  const test::TriMesh ring = test::torus_mesh(0.10, 0.015, 20, 10);
  CollisionWorld world(model);
  world.set_object(ring.vertices, ring.triangles);
  EXPECT_THROW(world.set_exact_round_shapes(true), std::logic_error);
}

}  // namespace
}  // namespace claspplan::robots
