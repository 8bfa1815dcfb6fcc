// Where a motion is checked: the travel bound (no point of any robot's shapes travels farther).
#include "robots/motion_sampling.hpp"

#include <algorithm>
#include <random>
#include <string>

#include <gtest/gtest.h>

#include "robots/kinematics.hpp"

namespace claspplan::robots {
namespace {

// The corners of every shape's box, world frame, at the configuration data was computed for.
std::vector<Eigen::Vector3d> shape_corners(const RobotModel& m, const RobotData& d) {
  std::vector<Eigen::Vector3d> out;
  for (const CollisionShape& s : m.shapes) {
    const Eigen::Isometry3d pose = shape_pose(d, s);
    const Eigen::AlignedBox3d box = shape_bounds(s);
    for (int c = 0; c < 8; ++c)
      out.push_back(pose * box.corner(static_cast<Eigen::AlignedBox3d::CornerType>(c)));
  }
  return out;
}

TEST(MotionReach, NoShapeCornerTravelsFartherThanTheBound) {
  for (const std::string& name : builtin_robots()) {
    const RobotModel m = load_robot(name);
    const Eigen::VectorXd reach = motion_reach(m);
    ASSERT_EQ(reach.size(), m.dof());
    // The first axis carries the whole arm and hand: at least the KR5's 0.85 m reach.
    EXPECT_GT(reach[0], 0.85) << name;
    EXPECT_LT(reach[0], 2.0) << name;
    std::mt19937 rng(7);
    RobotData d(m);
    for (int trial = 0; trial < 20; ++trial) {
      Eigen::VectorXd q0(m.dof()), q1(m.dof());
      for (int j = 0; j < m.dof(); ++j) {
        std::uniform_real_distribution<double> u(m.joints[j].lower, m.joints[j].upper);
        q0[j] = u(rng), q1[j] = u(rng);
      }
      // Each corner's path length, summed over 400 steps (a lower estimate of the arc).
      forward_kinematics(m, q0, d);
      std::vector<Eigen::Vector3d> last = shape_corners(m, d);
      std::vector<double> travelled(last.size(), 0.0);
      for (int k = 1; k <= 400; ++k) {
        forward_kinematics(m, q0 + (k / 400.0) * (q1 - q0), d);
        const std::vector<Eigen::Vector3d> now = shape_corners(m, d);
        for (std::size_t i = 0; i < now.size(); ++i) travelled[i] += (now[i] - last[i]).norm();
        last = now;
      }
      const double bound = travel_bound(reach, q0, q1);
      for (double t : travelled) ASSERT_LE(t, bound) << name << " trial " << trial;
      // Not a uselessly loose bound: the farthest corner goes at least a tenth of it.
      EXPECT_GT(*std::max_element(travelled.begin(), travelled.end()), 0.1 * bound) << name;
    }
  }
}

TEST(MotionSampling, EverySampleOnceEndsFirstAndStopsAtTheFirstCollision) {
  std::vector<int> visited;
  EXPECT_TRUE(all_samples_free(9, [&](int k) { return visited.push_back(k), true; }));
  ASSERT_EQ(visited.size(), 10u);
  EXPECT_EQ(visited[0], 9);
  EXPECT_EQ(visited[1], 0);
  EXPECT_EQ(visited[2], 4);  // then the midpoints, coarse to fine
  std::vector<int> sorted = visited;
  std::sort(sorted.begin(), sorted.end());
  for (int k = 0; k <= 9; ++k) EXPECT_EQ(sorted[k], k);
  int calls = 0;
  EXPECT_FALSE(all_samples_free(9, [&](int k) { return ++calls, k != 4; }));
  EXPECT_EQ(calls, 3);
  const Eigen::VectorXd reach = Eigen::VectorXd::Constant(2, 1.0), q0 = Eigen::VectorXd::Zero(2);
  const Eigen::VectorXd q1 = Eigen::Vector2d(0.125, -0.0625);       // binary fractions: exact steps
  EXPECT_EQ(motion_steps(reach, 0.0, q0, q1, 0.015625), 8);         // 0.125 rad
  EXPECT_EQ(motion_steps(reach, 0.0078125, q0, q1, 0.015625), 24);  // 0.1875 m of travel
  EXPECT_EQ(motion_steps(reach, 0.0, q0, q0, 0.015625), 1);
  EXPECT_THROW(motion_steps(reach, 0.0, q0, q1, 0.0), std::invalid_argument);
  EXPECT_THROW(motion_steps(reach, 1e-9, q0, q1, 0.015625), std::invalid_argument);
}

}  // namespace
}  // namespace claspplan::robots
