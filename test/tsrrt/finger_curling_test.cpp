// Finger closing on geometry built here: a finger whose base link meets an obstacle curls its tip.
#include <gtest/gtest.h>

#include "robots/collision_world.hpp"
#include "robots/kinematics.hpp"
#include "robots/robot_model.hpp"
#include "test/robots/test_meshes.hpp"
#include "tsrrt/finger_closing.hpp"

namespace claspplan::test {
namespace {

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
  robots::RobotData data(model);
  robots::forward_kinematics(model, q_bent, data);
  const Eigen::Vector3d at =
      robots::shape_pose(data, model.shapes[model.links[base_link].shapes.front()]).translation();
  TriMesh cube = bar_mesh(0.004, 0.006, 4);
  for (auto& v : cube.vertices) v += at;

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

}  // namespace
}  // namespace claspplan::test
