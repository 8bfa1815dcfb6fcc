// Room for the hand at a clasp target (tsrrt::clasp_room): the closed hand, placed as the
// controller leaves it, tested against the environment alone.
#include "tsrrt/hand_room.hpp"

#include <algorithm>
#include <cmath>

#include <gtest/gtest.h>

#include "perception/loops.hpp"
#include "robots/hand_size.hpp"

namespace claspplan::test {
namespace {

// A circle of radius `radius` in the vertical x-z plane, centred at height `height`.
servo::Points upright_loop(double radius, double height) {
  servo::Points loop;
  for (int i = 0; i < 48; ++i) {
    const double a = 2 * M_PI * i / 48;
    loop.emplace_back(0.6 + radius * std::cos(a), 0.0, height + radius * std::sin(a));
  }
  return loop;
}

std::vector<ClaspTarget> targets_on(const servo::Points& loop) {
  return perception::clasp_targets(loop, 12);
}

// The floor's top at z = 0.
robots::CollisionWorld floor_world(const robots::RobotModel& m) {
  robots::CollisionWorld world(m);
  Eigen::Isometry3d pose = Eigen::Isometry3d::Identity();
  pose.translation() = Eigen::Vector3d(0.5, 0, -0.025);
  world.add_box(pose, Eigen::Vector3d(2.0, 2.0, 0.05));
  return world;
}

int count(const std::vector<bool>& v) {
  return static_cast<int>(std::count(v.begin(), v.end(), true));
}

TEST(ClaspRoom, EveryTargetFitsHighAboveTheFloor) {
  for (const char* name : {"kr5_sdh", "kr5_dlr", "kr5_icub", "kr5_armar3"}) {
    const robots::RobotModel m = robots::load_robot(name);
    robots::CollisionWorld world = floor_world(m);
    const servo::Points loop = upright_loop(0.03, 0.5);
    const auto room =
        tsrrt::clasp_room(m, robots::hand_size(m).closed_q, world, loop, targets_on(loop));
    EXPECT_EQ(count(room), 12) << name;
  }
}

// A 6 cm ring standing on the floor: the DLR hand, 19 cm from palm to fingertip, has no room
// around its lower half, where the closed fingers reach into the floor from every approach, and
// room at its top.
TEST(ClaspRoom, TheFloorTakesTheRoomOfTheLowTargets) {
  const robots::RobotModel m = robots::load_robot("kr5_dlr");
  robots::CollisionWorld world = floor_world(m);
  const servo::Points loop = upright_loop(0.03, 0.035);
  const auto targets = targets_on(loop);
  const auto room = tsrrt::clasp_room(m, robots::hand_size(m).closed_q, world, loop, targets);
  ASSERT_EQ(room.size(), targets.size());
  bool low_has_room = false, top_has_room = false;
  for (std::size_t i = 0; i < targets.size(); ++i) {
    if (targets[i].point.z() < 0.02) low_has_room = low_has_room || room[i];
    if (targets[i].point.z() > 0.06) top_has_room = top_has_room || room[i];
  }
  EXPECT_FALSE(low_has_room);
  EXPECT_TRUE(top_has_room);
  EXPECT_LT(count(room), 12);

  // Inside a block of 1 m on each side nothing fits.
  robots::CollisionWorld block(m);
  Eigen::Isometry3d centre = Eigen::Isometry3d::Identity();
  centre.translation() = Eigen::Vector3d(0.6, 0, 0.5);
  block.add_box(centre, Eigen::Vector3d(1, 1, 1));
  const servo::Points inside = upright_loop(0.03, 0.5);
  EXPECT_EQ(
      count(tsrrt::clasp_room(m, robots::hand_size(m).closed_q, block, inside, targets_on(inside))),
      0);
}

TEST(ClaspRoom, FloatingHandIsPlacedByItsCentreAndAxes) {
  // The hand centred 1 m above the floor touches nothing; centred on the floor's top, it does,
  // whatever its orientation.
  const robots::RobotModel m = robots::load_robot("kr5_sdh");
  robots::CollisionWorld world = floor_world(m);
  tsrrt::FloatingHand hand(m, robots::hand_size(m).closed_q);
  const Eigen::Vector3d down(0, 0, -1), side(0, 1, 0), along(1, 0, 0);
  EXPECT_FALSE(hand.blocked(world, Eigen::Vector3d(0.5, 0, 1.0), down, side));
  EXPECT_TRUE(hand.blocked(world, Eigen::Vector3d(0.5, 0, 0.0), down, side));
  EXPECT_TRUE(hand.blocked(world, Eigen::Vector3d(0.5, 0, 0.0), along, side));
  EXPECT_THROW(tsrrt::FloatingHand(m, Eigen::VectorXd::Zero(1)), std::invalid_argument);
}

}  // namespace
}  // namespace claspplan::test
