// Where the hand approaches a clasp target from (outside the hole, both sides of the loop), and
// the open hand's approach to contact: straight along its approach direction, the tool's
// orientation kept, ending within one step of the first contact.
#include "tsrrt/approach.hpp"

#include <cmath>

#include <Eigen/Geometry>
#include <gtest/gtest.h>

#include "core/mesh.hpp"
#include "robots/collision_world.hpp"
#include "robots/kinematics.hpp"
#include "robots/robot_model.hpp"

namespace claspplan::test {
namespace {

struct Pose {
  Eigen::Vector3d tcp;
  Eigen::Matrix3d tool;
};

Pose pose_at(const robots::RobotModel& m, const Eigen::VectorXd& q) {
  robots::RobotData data(m);
  robots::forward_kinematics(m, q, data);
  return {robots::point_position(data, m.tcp), data.link_poses[m.tool_link].linear()};
}

// The open hand at q: the approach direction and how far along it the fingers reach.
struct HandAhead {
  Eigen::Vector3d direction;
  double reach = 0.0;
};
HandAhead hand_ahead(const robots::RobotModel& m, const Eigen::VectorXd& q) {
  robots::RobotData data(m);
  robots::forward_kinematics(m, q, data);
  HandAhead out{robots::vector_direction(data, m.v_fwd)};
  const Eigen::Vector3d tcp = robots::point_position(data, m.tcp);
  robots::FingerCurvesData curves;
  robots::finger_curves(m, q, data, curves, false);
  for (const auto& curve : curves.points)
    for (const auto& p : curve) out.reach = std::max(out.reach, (p - tcp).dot(out.direction));
  return out;
}

// A 30 x 30 cm plate, 4 mm thick, square to `direction`, its near face at `near`.
Eigen::Isometry3d plate_pose(const Eigen::Vector3d& near, const Eigen::Vector3d& direction) {
  Eigen::Isometry3d pose = Eigen::Isometry3d::Identity();
  pose.linear() =
      Eigen::Quaterniond::FromTwoVectors(Eigen::Vector3d::UnitZ(), direction).toRotationMatrix();
  pose.translation() = near + 0.002 * direction;
  return pose;
}

TEST(ApproachToContact, GoesStraightAlongTheApproachAndStopsWithinAStepOfContact) {
  const robots::RobotModel m = robots::load_robot("kr5_sdh");
  const Eigen::VectorXd q = m.home;
  const Pose start = pose_at(m, q);
  // A plate 3 cm beyond the hand's farthest finger-curve point along the approach.
  const auto [direction, reach] = hand_ahead(m, q);
  const Eigen::Vector3d near = start.tcp + (reach + 0.03) * direction;
  const Eigen::Vector3d size(0.3, 0.3, 0.004);

  tsrrt::ApproachOptions o;
  o.step = 0.004;
  o.distance = 0.05;
  robots::CollisionWorld free_space(m);
  const auto unblocked = tsrrt::approach_until_contact(m, free_space, q, o);
  ASSERT_EQ(unblocked.size(), 12u);  // 12 steps of 4 mm within 5 cm
  EXPECT_NEAR((pose_at(m, unblocked.back()).tcp - start.tcp).norm(), 0.048, 1e-3);

  robots::CollisionWorld world(m);
  world.add_box(plate_pose(near, direction), size);
  const auto poses = tsrrt::approach_until_contact(m, world, q, o);
  ASSERT_FALSE(poses.empty());
  ASSERT_LT(poses.size(), unblocked.size());
  for (const auto& p : poses) {
    EXPECT_FALSE(world.in_collision(p));
    const Pose at = pose_at(m, p);
    const Eigen::Vector3d moved = at.tcp - start.tcp;
    EXPECT_LT(moved.cross(direction).norm(), 1e-3) << "off the approach line";
    EXPECT_GT(moved.dot(direction), 0.0);
    EXPECT_LT(Eigen::AngleAxisd(at.tool * start.tool.transpose()).angle(), 1e-3);
  }
  // One more step would touch: the same as the plate one step nearer.
  robots::CollisionWorld nearer(m);
  nearer.add_box(plate_pose(near - o.step * direction, direction), size);
  EXPECT_TRUE(nearer.in_collision(poses.back()));
}

TEST(ApproachToContact, KeepsTheClearanceFromTheObject) {
  const robots::RobotModel m = robots::load_robot("kr5_sdh");
  const Eigen::VectorXd q = m.home;
  const Pose start = pose_at(m, q);
  const auto [direction, reach] = hand_ahead(m, q);
  robots::RobotData data(m);
  const auto near_object = [&](robots::CollisionWorld& world, const Eigen::VectorXd& p, double c) {
    robots::forward_kinematics(m, p, data);
    for (std::size_t l = 0; l < m.links.size(); ++l)
      if (m.links[l].hand && world.link_near_object(data, static_cast<int>(l), c)) return true;
    return false;
  };
  // The plate as the object, at eight offsets within one step: with a 3 mm clearance the advance
  // never ends nearer than that, and where the last free step ends nearer, it stops a step early.
  tsrrt::ApproachOptions touching, clear;
  touching.clearance = 0.0;
  clear.clearance = 0.003;
  int earlier = 0;
  for (int k = 0; k < 8; ++k) {
    const Eigen::Vector3d near = start.tcp + (reach + 0.02 + 0.0005 * k) * direction;
    const TriangleMesh plate =
        transformed(box_mesh({0.3, 0.3, 0.004}), plate_pose(near, direction));
    robots::CollisionWorld world(m);
    world.set_object(plate.vertices, plate.triangles);
    const auto deep = tsrrt::approach_until_contact(m, world, q, touching);
    const auto kept = tsrrt::approach_until_contact(m, world, q, clear);
    ASSERT_FALSE(kept.empty());
    for (const auto& p : kept) EXPECT_FALSE(near_object(world, p, clear.clearance));
    earlier += kept.size() < deep.size();
  }
  EXPECT_GT(earlier, 0);
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
