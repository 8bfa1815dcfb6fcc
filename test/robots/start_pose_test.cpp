// Finding a start above a point for any robot (issue 35): the tcp at its target, v_fwd down, no
// self-collision, nothing below the floor; the same answer for the same options.
#include "robots/start_pose.hpp"

#include <gtest/gtest.h>

#include "robots/collision_world.hpp"
#include "robots/kinematics.hpp"

namespace claspplan::robots {
namespace {

TEST(StartPose, EveryBuiltInRobotGetsAFreeStartAboveAPoint) {
  const Eigen::Vector3d point(0.55, 0.1, 0.05);
  for (const std::string& name : builtin_robots()) {
    const RobotModel m = load_robot(name);
    StartPoseOptions o;
    o.height = 0.3;
    const auto start = find_start_above(m, point, o);
    ASSERT_TRUE(start) << name;
    RobotData data(m);
    forward_kinematics(m, start->q, data);
    EXPECT_LE((point_position(data, m.tcp) - point - Eigen::Vector3d(0, 0, 0.3)).norm(),
              o.position_tolerance)
        << name;
    EXPECT_GE(-vector_direction(data, m.v_fwd).z(), std::cos(o.angle_tolerance)) << name;
    EXPECT_TRUE(m.within_limits(start->q)) << name;
    EXPECT_EQ(start->q.tail(m.hand_dof), m.home.tail(m.hand_dof)) << name << ": the hand open";
    CollisionWorld world(m);
    EXPECT_FALSE(world.in_collision(start->q)) << name;
    const auto again = find_start_above(m, point, o);
    ASSERT_TRUE(again);
    EXPECT_EQ(again->q, start->q) << name;
  }
}

// Out of reach (3 m away from a 0.85 m arm), and a target that puts the hand into the floor.
TEST(StartPose, NoStartWhenOutOfReachOrInTheFloor) {
  const RobotModel m = load_robot("kr5_sdh");
  StartPoseOptions o;
  o.restarts = 20;
  EXPECT_FALSE(find_start_above(m, Eigen::Vector3d(3.0, 0.0, 0.0), o));
  o.height = -0.1;  // the tcp 5 cm below the floor
  EXPECT_FALSE(find_start_above(m, Eigen::Vector3d(0.55, 0.0, 0.05), o));
}

}  // namespace
}  // namespace claspplan::robots
