// An underactuated hand: the capsule hand whose thumb joints mimic the finger's (one motor pair,
// as Romeo's fingers all follow LHand), loaded with the thumb's mimic joints as adaptive joints.
// They follow their motor in every planned motion and stop on their own when the fingers close.
#include <string>

#include <gtest/gtest.h>

#include "core/input_error.hpp"
#include "robots/collision_world.hpp"
#include "robots/kinematics.hpp"
#include "robots/robot_model.hpp"
#include "servo/clasp_controller.hpp"
#include "test/robots/test_meshes.hpp"
#include "test/support/capsule_hand.hpp"
#include "tsrrt/finger_closing.hpp"

namespace claspplan::test {
namespace {

constexpr const char* kMotors =
    "    - {name: finger_1, open: 0.4, closing: -1}\n"
    "    - {name: finger_2, open: 0.0, closing: -1}\n";

robots::RobotModel coupled_hand() {
  return robots::load_robot_from_text(capsule_hand_yaml("coupled", kMotors, "[finger_1, finger_2]"),
                                      one_motor_hand_urdf(), "coupled.yaml", "coupled.urdf");
}

robots::RobotModel adaptive_hand(const std::string& thumb_entries =
                                     "    - {name: thumb_1, closing: 1}\n"
                                     "    - {name: thumb_2, closing: 1}\n") {
  return robots::load_robot_from_text(
      capsule_hand_yaml("adaptive", kMotors + thumb_entries, "[thumb_1, thumb_2]"),
      one_motor_hand_urdf(), "adaptive.yaml", "adaptive.urdf");
}

TEST(AdaptiveHand, ItsJointsFollowTheirMotorAndShareItsJacobianColumn) {
  const robots::RobotModel coupled = coupled_hand();
  const robots::RobotModel m = adaptive_hand();
  ASSERT_EQ(m.dof(), coupled.dof() + 2);
  const int motor = m.joint_index("finger_1"), thumb = m.joint_index("thumb_1");
  EXPECT_EQ(m.joints[thumb].follows, motor);
  EXPECT_EQ(m.joints[thumb].follow_multiplier, -1.0);
  EXPECT_EQ(m.home[thumb], -0.4);  // opens with its motor
  EXPECT_EQ(coupled.joints[motor].follows, -1);

  // At a coupled configuration the two models place every link alike, and the motor's column of
  // the thumb tip's Jacobian holds the thumb's motion; the adaptive joints' columns are empty.
  Eigen::VectorXd q = m.home;
  q[motor] = 0.1;
  q[m.joint_index("finger_2")] = -0.5;
  q = m.couple(q);
  EXPECT_DOUBLE_EQ(q[thumb], -0.1);
  EXPECT_DOUBLE_EQ(q[m.joint_index("thumb_2")], 0.5);
  robots::RobotData data(m), data_c(coupled);
  robots::forward_kinematics(m, q, data);
  robots::forward_kinematics(coupled, q.head(coupled.dof()), data_c);
  const int tip = m.link_index("thumb_tip");
  EXPECT_TRUE(data.link_poses[tip].isApprox(data_c.link_poses[tip], 1e-12));
  const auto J = robots::point_jacobian(m, data, tip, Eigen::Vector3d::Zero());
  const auto J_c = robots::point_jacobian(coupled, data_c, tip, Eigen::Vector3d::Zero());
  EXPECT_TRUE(J.leftCols(coupled.dof()).isApprox(J_c, 1e-12));
  EXPECT_GT(J.col(motor).norm(), 0.01);
  EXPECT_EQ(J.col(thumb).norm(), 0.0);
}

TEST(AdaptiveHand, AControllerStepKeepsThemOnTheirMotor) {
  const robots::RobotModel m = adaptive_hand();
  robots::RobotData data(m);
  robots::forward_kinematics(m, m.home, data);
  // A ring whose lowest point is 3 cm above the palm, to be linked by closing the hand.
  const Eigen::Vector3d palm = data.link_poses[m.link_index("palm")].translation();
  const Ring ring = ring_with_bottom_at(palm + Eigen::Vector3d(0, 0, 0.03));
  servo::ClaspController c(m, ring.loop, {{palm + Eigen::Vector3d(0, 0, 0.03), {0, 1, 0}}});
  Eigen::VectorXd q = m.home;
  for (int k = 0; k < 20; ++k) q = c.step(q, c.project(q).position, m.vlink_goal);
  const int motor = m.joint_index("finger_1");
  EXPECT_GT(std::abs(q[motor] - m.home[motor]), 0.01);  // the controller closed the hand
  EXPECT_TRUE(q.isApprox(m.couple(q), 1e-12));
}

// A cube in the thumb's path: the thumb stops there, and the finger, on the same motor, closes on.
// Coupled, the motor stops for the thumb (finger_curling_test.cpp).
TEST(AdaptiveHand, EachFingerStopsOnItsOwnAtContact) {
  const robots::RobotModel m = adaptive_hand();
  const int motor = m.joint_index("finger_1"), thumb = m.joint_index("thumb_1");
  Eigen::VectorXd q_bent = m.home;
  for (int j = m.arm_dof; j < m.dof(); ++j) q_bent[j] += m.joints[j].closing * 0.3;
  robots::RobotData data(m);
  robots::forward_kinematics(m, q_bent, data);
  const std::vector<int>& shapes = m.links[m.link_index("thumb_distal")].shapes;
  const Eigen::Vector3d at = robots::shape_pose(data, m.shapes[shapes.back()]).translation();
  TriMesh cube = bar_mesh(0.004, 0.006, 4);
  for (auto& v : cube.vertices) v += at;
  robots::CollisionWorld world(m);
  world.set_object(cube.vertices, cube.triangles);

  const Eigen::VectorXd closed = tsrrt::close_fingers(m, world, m.home, {});
  const auto closed_by = [&](int j) { return m.joints[j].closing * (closed[j] - m.home[j]); };
  EXPECT_LT(closed_by(thumb), 0.3);
  EXPECT_GT(closed_by(motor), 0.3 + 0.1);
  robots::forward_kinematics(m, closed, data);
  EXPECT_FALSE(world.in_collision(data));
}

TEST(AdaptiveHand, DescriptionsItCannotMeanAreRefused) {
  const auto reason = [](const std::string& entries) {
    try {
      adaptive_hand(entries);
    } catch (const InputError& e) {
      return std::string(e.what());
    }
    return std::string();
  };
  EXPECT_NE(reason("    - {name: thumb_1, open: -0.4, closing: 1}\n").find("opens with its leader"),
            std::string::npos);
  // finger_2 held: thumb_2 would follow a joint that is not in q.
  const std::string held = capsule_hand_yaml(
      "held", "    - {name: finger_1, open: 0.4, closing: -1}\n    - {name: thumb_2, closing: 1}\n",
      "[thumb_2]");
  std::string yaml = held;
  yaml.replace(yaml.find("joints: [finger_1, finger_2]"), 28, "joints: [finger_1]");
  yaml.insert(yaml.find("  fingers:"), "  held: {finger_2: 0.0}\n");
  try {
    robots::load_robot_from_text(yaml, one_motor_hand_urdf(), "held.yaml", "held.urdf");
    ADD_FAILURE() << "loaded";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("must follow a hand joint in q"), std::string::npos)
        << e.what();
  }
}

}  // namespace
}  // namespace claspplan::test
