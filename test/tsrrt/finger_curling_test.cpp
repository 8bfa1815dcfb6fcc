// Finger closing on geometry built here: a finger whose base link meets an obstacle curls its tip;
// a motor that moves two fingers stops for either.
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "robots/collision_world.hpp"
#include "robots/kinematics.hpp"
#include "robots/robot_model.hpp"
#include "test/robots/test_meshes.hpp"
#include "test/support/capsule_hand.hpp"
#include "tsrrt/finger_closing.hpp"

namespace claspplan::test {
namespace {

// A 6 mm cube at a link's shape (its first or last) at q.
TriMesh cube_at(const robots::RobotModel& model, const Eigen::VectorXd& q, int link, bool last) {
  robots::RobotData data(model);
  robots::forward_kinematics(model, q, data);
  const std::vector<int>& shapes = model.links[link].shapes;
  const Eigen::Vector3d at =
      robots::shape_pose(data, model.shapes[last ? shapes.back() : shapes.front()]).translation();
  TriMesh cube = bar_mesh(0.004, 0.006, 4);
  for (auto& v : cube.vertices) v += at;
  return cube;
}

TEST(FingerClosing, ABlockedBaseLinkStopsItsJointWhileTheTipCurlsOn) {
  const robots::RobotModel model = robots::load_robot("kr5_sdh");
  const int base_joint = model.joint_index("finger_12_joint");
  const int tip_joint = model.joint_index("finger_13_joint");
  const int base_link = model.link_index("finger_12_link");
  ASSERT_FALSE(model.links[base_link].shapes.empty());

  // A 6 mm cube where the middle of the base link would be after closing its joint by 0.6 rad.
  const Eigen::VectorXd q = model.home;
  Eigen::VectorXd q_bent = q;
  q_bent[base_joint] += model.joints[base_joint].closing * 0.6;
  const TriMesh cube = cube_at(model, q_bent, base_link, false);

  robots::RobotData data(model);
  robots::CollisionWorld world(model);
  world.set_object(cube.vertices, cube.triangles);
  const Eigen::VectorXd closed = tsrrt::close_fingers(model, world, q, {});

  const auto closed_by = [&](int j) { return model.joints[j].closing * (closed[j] - q[j]); };
  // The base joint stops short of the cube; the tip joint goes on well beyond it.
  EXPECT_GT(closed_by(base_joint), 0.05);
  EXPECT_LT(closed_by(base_joint), 0.6);
  EXPECT_GT(closed_by(tip_joint), closed_by(base_joint) + 0.2);
  // The closed pose keeps the clearance: no link of the hand touches the cube.
  robots::forward_kinematics(model, closed, data);
  EXPECT_FALSE(world.in_collision(data));
}

// The same finger stopped by unseen space instead of the object: the closing says where, so that a
// camera can be named to look there (run_search); stopping at the object says nothing.
TEST(FingerClosing, AFingerStoppedByUnseenSpaceSaysWhere) {
  const robots::RobotModel model = robots::load_robot("kr5_sdh");
  const int base_joint = model.joint_index("finger_12_joint");
  const int base_link = model.link_index("finger_12_link");
  Eigen::VectorXd q_bent = model.home;
  q_bent[base_joint] += model.joints[base_joint].closing * 0.6;
  const TriMesh cube = cube_at(model, q_bent, base_link, false);
  Eigen::Vector3d centre = Eigen::Vector3d::Zero();
  for (const auto& v : cube.vertices) centre += v / static_cast<double>(cube.vertices.size());

  robots::CollisionWorld unseen(model);
  unseen.add_voxels({centre}, 0.006);
  std::vector<robots::EnvironmentHit> stops;
  const Eigen::VectorXd closed = tsrrt::close_fingers(model, unseen, model.home, {}, &stops);
  const double closed_by =
      model.joints[base_joint].closing * (closed[base_joint] - model.home[base_joint]);
  EXPECT_LT(closed_by, 0.6) << "the voxel stops the base joint";
  ASSERT_FALSE(stops.empty());
  for (const auto& hit : stops) {
    const Eigen::Vector3d p = unseen.contact_point(hit);
    EXPECT_LT((p - centre).norm(), 0.01) << p.transpose();
  }

  robots::CollisionWorld object(model);
  object.set_object(cube.vertices, cube.triangles);
  stops.clear();
  tsrrt::close_fingers(model, object, model.home, {}, &stops);
  EXPECT_TRUE(stops.empty());
}

// The capsule hand with one motor pair: the thumb's joints mimic the finger's (as Romeo's fingers
// all follow LHand), and both fingers list the motors. A cube in the thumb's path must stop the
// motors when the finger steps them, not only when the thumb does.
TEST(FingerClosing, AMotorSharedThroughMimicJointsStopsForEveryLinkItMoves) {
  const std::string urdf = one_motor_hand_urdf();
  const std::string yaml = capsule_hand_yaml("one_motor",
                                             "    - {name: finger_1, open: 0.4, closing: -1}\n"
                                             "    - {name: finger_2, open: 0.0, closing: -1}\n",
                                             "[finger_1, finger_2]");
  const robots::RobotModel model =
      robots::load_robot_from_text(yaml, urdf, "one_motor.yaml", "one_motor.urdf");
  const int motor = model.joint_index("finger_1");
  const int thumb_distal = model.link_index("thumb_distal");

  // A 6 mm cube where the thumb's tip would be after both motors closed 0.3 rad.
  Eigen::VectorXd q_bent = model.home;
  for (int j = model.arm_dof; j < model.dof(); ++j) q_bent[j] += model.joints[j].closing * 0.3;
  const TriMesh cube = cube_at(model, q_bent, thumb_distal, true);
  robots::RobotData data(model);
  robots::CollisionWorld world(model);
  world.set_object(cube.vertices, cube.triangles);

  const Eigen::VectorXd closed = tsrrt::close_fingers(model, world, model.home, {});
  const double closed_by = model.joints[motor].closing * (closed[motor] - model.home[motor]);
  EXPECT_GT(closed_by, 0.05);
  EXPECT_LT(closed_by, 0.3);
  robots::forward_kinematics(model, closed, data);
  EXPECT_FALSE(world.in_collision(data));
}

}  // namespace
}  // namespace claspplan::test
