// The clasp problem's motion checks: a pruning shortcut is checked by how far the robot's points
// travel, not only by the joint resolution of the search's steps.
#include "tsrrt/clasp_problem.hpp"

#include <cmath>

#include <gtest/gtest.h>

#include "robots/collision_world.hpp"
#include "robots/robot_model.hpp"
#include "servo/clasp_controller.hpp"
#include "test/support/wire_sweep.hpp"

namespace claspplan::test {
namespace {

constexpr double kDeg = 3.14159265358979 / 180.0;

TEST(ClaspProblem, AShortcutThatStepsOverAWireIsNotFree) {
  const robots::RobotModel m = robots::load_robot("kr5_icub");
  robots::CollisionWorld world(m);
  auto [q0, q1] = add_wire_across_sweep(world, m);
  // Any loop: the check does not depend on it.
  servo::Points loop;
  for (int i = 0; i < 12; ++i)
    loop.push_back(
        Eigen::Vector3d(0.6, 0.05 * std::cos(i * 30 * kDeg), 0.3 + 0.05 * std::sin(i * 30 * kDeg)));
  servo::ClaspController controller(m, loop, {{loop[0], Eigen::Vector3d::UnitZ()}});
  // The search's steps are checked every 0.2 rad: the sweep only at its ends.
  tsrrt::ClaspProblem problem(controller, world, 0.65, 0.0, 0.2);
  ASSERT_TRUE(world.in_collision(m.home));
  EXPECT_TRUE(problem.motion_free(q0, q1));
  EXPECT_FALSE(problem.shortcut_free(q0, q1));
  EXPECT_EQ(world.motion_travel(), 0.0);  // the search's checks are as before
  EXPECT_TRUE(problem.motion_free(q0, q1));
  // Beside the wire a shortcut is free.
  q1[0] = 10 * kDeg;
  EXPECT_TRUE(problem.shortcut_free(q0, q1));
}

}  // namespace
}  // namespace claspplan::test
