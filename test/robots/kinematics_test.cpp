// Forward kinematics against the KR5 R850 facts, finger curves at the pre-shapes, and every
// Jacobian against central differences.
#include "robots/kinematics.hpp"

#include <cmath>
#include <random>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "robots/robot_model.hpp"

namespace claspplan::robots {
namespace {

constexpr double kDeg = M_PI / 180.0;

Eigen::VectorXd arm_q(const RobotModel& m, std::vector<double> degrees) {
  Eigen::VectorXd q = m.home;
  for (int i = 0; i < 6; ++i) q[i] = degrees[i] * kDeg;
  return q;
}

TEST(Kinematics, Kr5ForwardKinematicsMatchesTheFacts) {
  const RobotModel m = load_robot("kr5_sdh");
  RobotData d(m);
  struct Case {
    std::vector<double> q;
    Eigen::Vector3d position, z_axis;
  };
  const std::vector<Case> cases = {
      {{0, 0, 0, 0, 0, 0}, {0.925, 0, 0.425}, {1, 0, 0}},
      {{0, -90, 90, 0, 0, 0}, {0.560, 0, 0.790}, {1, 0, 0}},
      {{0, -90, 90, 0, 90, 0}, {0.480, 0, 0.710}, {0, 0, -1}},
      {{30, -60, 100, 20, 40, 10}, {0.5467, -0.3360, 0.3833}, {0.062, -0.290, -0.955}},
  };
  for (const Case& c : cases) {
    forward_kinematics(m, arm_q(m, c.q), d);
    const Eigen::Isometry3d& tool0 = d.link_poses[m.tool_link];
    EXPECT_LT((tool0.translation() - c.position).norm(), 1e-3)
        << "q " << c.q[0] << "," << c.q[1] << "," << c.q[2] << ": "
        << tool0.translation().transpose();
    EXPECT_LT((tool0.linear().col(2) - c.z_axis).norm(), 2e-3) << tool0.linear().col(2).transpose();
    EXPECT_NEAR(tool0.linear().determinant(), 1.0, 1e-12);
  }
  // q = 0 is KUKA's mechanical zero: every link frame world-aligned.
  forward_kinematics(m, Eigen::VectorXd::Zero(m.dof()), d);
  for (int l = 0; l <= m.link_index("link_6"); ++l)
    EXPECT_TRUE(d.link_poses[l].linear().isIdentity(1e-12)) << m.links[l].name;
}

TEST(Kinematics, RejectsAWrongSizedQ) {
  const RobotModel m = load_robot("kr5_sdh");
  RobotData d(m);
  EXPECT_THROW(forward_kinematics(m, Eigen::VectorXd::Zero(6), d), std::invalid_argument);
}

// Mount of each hand on tool0 (robot facts §2) and HOME's tool0 pose, written out independently:
// at HOME tool0 sits at (0.560, 0, 0.790) with x = -world z, y = world y, z = world x.
Eigen::Vector3d home_world(const Eigen::Vector3d& hand_mm, const std::string& hand) {
  const Eigen::Vector3d p = hand_mm / 1000.0;
  Eigen::Vector3d t;
  if (hand == "dlr") {
    t = {p.x(), -p.z(), p.y()};  // rpy (π/2, 0, 0)
  } else if (hand == "icub") {
    t = {-p.z(), p.y(), p.x()};  // rpy (0, −π/2, 0)
  } else {
    t = p;  // SDH, ARMAR-III: identity
  }
  return {0.560 + t.z(), t.y(), 0.790 - t.x()};
}

void expect_curves(const std::string& robot, const std::string& hand,
                   const std::vector<std::vector<Eigen::Vector3d>>& expected_mm,
                   double tolerance = 5e-4) {
  const RobotModel m = load_robot(robot);
  RobotData d(m);
  FingerCurvesData curves;
  finger_curves(m, m.home, d, curves, false);
  ASSERT_EQ(curves.points.size(), expected_mm.size()) << robot;
  for (size_t c = 0; c < expected_mm.size(); ++c) {
    ASSERT_EQ(curves.points[c].size(), expected_mm[c].size()) << robot << " curve " << c;
    for (size_t i = 0; i < expected_mm[c].size(); ++i) {
      const Eigen::Vector3d want = home_world(expected_mm[c][i], hand);
      EXPECT_LT((curves.points[c][i] - want).norm(), tolerance)
          << robot << " curve " << c << " point " << i << ": got "
          << curves.points[c][i].transpose() << " want " << want.transpose();
    }
  }
}

TEST(Kinematics, SdhFingerCurvesAtTheOpenPreshape) {
  // Robot facts §7 (Simox hand-base frame, connector included, mm).
  std::vector<Eigen::Vector3d> c1 = {{91.8, 33, 223.0}, {91.8, 33, 154.5},  {19.1, 33, 107.8},
                                     {19.1, 33, 91.3},  {0, 0, 91.3},       {-38.1, 0, 91.3},
                                     {-38.1, 0, 107.8}, {-110.9, 0, 154.5}, {-110.9, 0, 223.0}};
  std::vector<Eigen::Vector3d> c2 = c1;
  for (int i = 0; i < 4; ++i) c2[i].y() = -33;
  expect_curves("kr5_sdh", "sdh", {c1, c2});

  // All joints 0: every tip 0.2628 above the hand base.
  const RobotModel m = load_robot("kr5_sdh");
  RobotData d(m);
  Eigen::VectorXd q = m.home;
  q.tail(m.hand_dof).setZero();
  forward_kinematics(m, q, d);
  const Eigen::Isometry3d hand = d.link_poses[m.tool_link].inverse();
  for (const char* tip : {"finger_13_tip", "finger_23_tip", "thumb_3_tip"})
    EXPECT_NEAR((hand * d.link_poses[m.link_index(tip)].translation()).z(), 0.2628, 1e-6);
}

TEST(Kinematics, DlrFingerCurvesAtTheOpenPreshape) {
  const Eigen::Vector3d palm(-31, 80, 0);
  const std::vector<Eigen::Vector3d> thumb = {
      {-44.5, 26.5, 19.85}, {-144.9, 26.5, 19.85}, {-184.9, 26.5, 19.85}, {-231.5, 26.5, 19.85}};
  auto curve = [&](std::vector<Eigen::Vector3d> finger_base_to_tip) {
    std::vector<Eigen::Vector3d> c(finger_base_to_tip.rbegin(), finger_base_to_tip.rend());
    c.push_back(palm);
    c.insert(c.end(), thumb.begin(), thumb.end());
    return c;
  };
  expect_curves(
      "kr5_dlr", "dlr",
      {curve({{-1.9, 134.5, 39.1}, {-1.9, 234.3, 49.6}, {-1.9, 274.1, 53.7}, {-1.9, 320.4, 58.6}}),
       curve({{0, 134.5, 0}, {0, 234.85, 0}, {0, 274.85, 0}, {0, 321.45, 0}}),
       curve({{-2.17, 134.5, -39.1},
              {-2.17, 234.3, -49.6},
              {-2.17, 274.1, -53.7},
              {-2.17, 320.4, -58.6}})});
}

TEST(Kinematics, IcubFingerCurvesAtTheGraspPreshape) {
  const Eigen::Vector3d palm(50, 0, 19);
  const std::vector<Eigen::Vector3d> thumb = {{39.0, -12.0, 14.5},
                                              {41.0, -11.9, 36.1},
                                              {46.2, -17.0, 61.0},
                                              {50.6, -21.3, 82.2},
                                              {58.6, -22.4, 99.0}};
  auto curve = [&](std::vector<Eigen::Vector3d> tip_to_j1) {
    tip_to_j1.push_back(palm);
    tip_to_j1.insert(tip_to_j1.end(), thumb.begin(), thumb.end());
    return tip_to_j1;
  };
  expect_curves("kr5_icub", "icub",
                {curve({{144.9, -29.8, 10.1},
                        {126.9, -29.0, 5.2},
                        {105.0, -27.4, 5.2},
                        {79.1, -25.5, 5.2},
                        {64.3, -26.2, 5.3}}),
                 curve({{149.9, -7.6, 9.4},
                        {131.9, -7.6, 4.4},
                        {106.1, -7.6, 4.4},
                        {80.3, -7.6, 4.4},
                        {65.0, -9.8, 4.4}}),
                 curve({{144.2, 15.5, 10.1},
                        {126.3, 14.1, 5.2},
                        {104.4, 11.7, 5.2},
                        {78.7, 9.0, 5.2},
                        {64.1, 5.7, 5.0}}),
                 curve({{135.6, 30.2, 10.8},
                        {117.7, 28.7, 5.9},
                        {98.8, 26.7, 5.9},
                        {77.0, 24.4, 5.9},
                        {62.1, 24.5, 6.0}})},
                // The facts give one decimal; the thumb's composed rotation rounds a little more.
                6e-4);
}

TEST(Kinematics, Armar3FingerCurvesAtThePowerPreshape) {
  const Eigen::Vector3d palm(-13, 23, 85);
  const std::vector<Eigen::Vector3d> thumb = {
      {-48.9, 0, 65.25}, {-89.1, 0, 65.25}, {-147.9, 0, 65.25}};
  auto curve = [&](double y, double tip, double j1, double j0) {
    std::vector<Eigen::Vector3d> c = {{-8.7, y, tip}, {-8.7, y, j1}, {-8.7, y, j0}, palm};
    c.insert(c.end(), thumb.begin(), thumb.end());
    return c;
  };
  expect_curves("kr5_armar3", "armar3",
                {curve(-13.5, 204.5, 145.7, 105.5), curve(13.5, 204.6, 145.8, 105.7),
                 curve(37.5, 197.1, 145.8, 105.7), curve(59.5, 189.6, 145.8, 105.7)});
}

// Closing every hand joint in its closing direction brings each fingertip toward the thumb tip.
TEST(Kinematics, ClosingDirectionsShortenTheVirtualCord) {
  for (const std::string& name : builtin_robots()) {
    const RobotModel m = load_robot(name);
    RobotData d(m);
    FingerCurvesData open, closed;
    finger_curves(m, m.home, d, open, false);
    Eigen::VectorXd q = m.home;
    for (int j = m.arm_dof; j < m.dof(); ++j) q[j] += 0.3 * m.joints[j].closing;
    finger_curves(m, m.clamp(q), d, closed, false);
    for (size_t c = 0; c < m.curves.size(); ++c) {
      const double before = (open.points[c].front() - open.points[c].back()).norm();
      const double after = (closed.points[c].front() - closed.points[c].back()).norm();
      EXPECT_LT(after, before - 0.01) << name << " " << m.curves[c].name;
    }
  }
}

// v_fwd is the approach direction (tool0 +z), v_swd the closing plane's normal (tool0 +y).
TEST(Kinematics, OrientationVectorsAndTcp) {
  for (const std::string& name : builtin_robots()) {
    const RobotModel m = load_robot(name);
    RobotData d(m);
    forward_kinematics(m, m.home, d);
    EXPECT_LT((vector_direction(d, m.v_fwd) - Eigen::Vector3d(1, 0, 0)).norm(), 1e-9) << name;
    EXPECT_LT((vector_direction(d, m.v_swd) - Eigen::Vector3d(0, 1, 0)).norm(), 1e-9) << name;
    // The TCP lies ahead of the flange, between the fingers.
    const Eigen::Vector3d tcp = point_position(d, m.tcp);
    EXPECT_GT(tcp.x(), 0.60) << name;
    EXPECT_LT(tcp.x(), 0.80) << name;
  }
}

Eigen::VectorXd random_q(const RobotModel& m, std::mt19937_64& rng) {
  Eigen::VectorXd q(m.dof());
  for (int i = 0; i < m.dof(); ++i) {
    std::uniform_real_distribution<double> u(m.joints[i].lower, m.joints[i].upper);
    q[i] = u(rng);
  }
  return q;
}

Eigen::Vector3d rotation_vector(const Eigen::Matrix3d& R) {
  const Eigen::AngleAxisd aa(R);
  return aa.angle() * aa.axis();
}

TEST(Kinematics, JacobiansMatchCentralDifferences) {
  std::mt19937_64 rng(20130423);
  const double h = 1e-6;
  for (const std::string& name : builtin_robots()) {
    const RobotModel m = load_robot(name);
    RobotData d(m), dp(m), dm(m);
    FingerCurvesData curves, cp, cm;
    for (int trial = 0; trial < 5; ++trial) {
      const Eigen::VectorXd q = random_q(m, rng);
      finger_curves(m, q, d, curves, true);
      // A random point on every link, its angular Jacobian, and v_fwd / v_swd.
      std::vector<Eigen::Matrix<double, 3, Eigen::Dynamic>> J_point, J_angular;
      std::vector<Eigen::Vector3d> local;
      std::uniform_real_distribution<double> u(-0.1, 0.1);
      for (size_t l = 0; l < m.links.size(); ++l) {
        local.emplace_back(u(rng), u(rng), u(rng));
        J_point.push_back(point_jacobian(m, d, static_cast<int>(l), local.back()));
        J_angular.push_back(angular_jacobian(m, d, static_cast<int>(l)));
      }
      const auto J_fwd = vector_jacobian(m, d, m.v_fwd);
      const auto J_swd = vector_jacobian(m, d, m.v_swd);
      for (int i = 0; i < m.dof(); ++i) {
        Eigen::VectorXd qp = q, qm = q;
        qp[i] += h;
        qm[i] -= h;
        finger_curves(m, qp, dp, cp, false);
        finger_curves(m, qm, dm, cm, false);
        for (size_t c = 0; c < curves.points.size(); ++c) {
          for (size_t k = 0; k < curves.points[c].size(); ++k) {
            const Eigen::Vector3d fd = (cp.points[c][k] - cm.points[c][k]) / (2 * h);
            const Eigen::Vector3d an = curves.jacobians[c][k].col(i);
            EXPECT_LT((fd - an).norm(), 1e-6)
                << name << " curve " << c << " point " << k << " joint " << m.joints[i].name;
          }
        }
        for (size_t l = 0; l < m.links.size(); ++l) {
          const Eigen::Vector3d fd =
              (dp.link_poses[l] * local[l] - dm.link_poses[l] * local[l]) / (2 * h);
          EXPECT_LT((fd - J_point[l].col(i)).norm(), 1e-6) << name << " link " << m.links[l].name;
          const Eigen::Vector3d w =
              rotation_vector(dp.link_poses[l].linear() * dm.link_poses[l].linear().transpose()) /
              (2 * h);
          EXPECT_LT((w - J_angular[l].col(i)).norm(), 1e-6) << name << " link " << m.links[l].name;
        }
        const Eigen::Vector3d fwd =
            (vector_direction(dp, m.v_fwd) - vector_direction(dm, m.v_fwd)) / (2 * h);
        const Eigen::Vector3d swd =
            (vector_direction(dp, m.v_swd) - vector_direction(dm, m.v_swd)) / (2 * h);
        EXPECT_LT((fwd - J_fwd.col(i)).norm(), 1e-6) << name;
        EXPECT_LT((swd - J_swd.col(i)).norm(), 1e-6) << name;
      }
    }
  }
}

// The DLR's coupled distal joint: the PIP column includes the DIP's share (chain rule).
TEST(Kinematics, MimicJointsFollowTheirLeader) {
  const RobotModel m = load_robot("kr5_dlr");
  RobotData d(m);
  Eigen::VectorXd q = m.home;
  const int pip = m.joint_index("middle_pip");
  q[pip] = 0.6;
  forward_kinematics(m, q, d);
  const Eigen::Matrix3d rel = d.link_poses[m.link_index("middle_middle")].linear().transpose() *
                              d.link_poses[m.link_index("middle_distal")].linear();
  EXPECT_NEAR(Eigen::AngleAxisd(rel).angle(), 0.6 * 1.047619, 1e-9);
  // Hand joints do not move the arm; arm joints move everything.
  const auto J = point_jacobian(m, d, m.link_index("middle_tip"), Eigen::Vector3d::Zero());
  EXPECT_GT(J.col(pip).norm(), 0.05);
  EXPECT_EQ(J.col(m.joint_index("index_pip")).norm(), 0.0);
  const auto J_tool = point_jacobian(m, d, m.tool_link, Eigen::Vector3d::Zero());
  EXPECT_EQ(J_tool.rightCols(m.hand_dof).norm(), 0.0);
}

}  // namespace
}  // namespace claspplan::robots
