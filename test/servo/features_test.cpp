// The task features (position, alignment eq. 3, virtual linking eq. 4) on the four built-in robots.
#include <random>

#include <gtest/gtest.h>

#include "robots/robot_model.hpp"
#include "servo/clasp_controller.hpp"
#include "test/support/curves.hpp"

namespace claspplan::test {
namespace {

using Eigen::Vector3d;
using Eigen::VectorXd;

const char* const kRobots[] = {"kr5_sdh", "kr5_dlr", "kr5_icub", "kr5_armar3"};

const robots::RobotModel& robot(const std::string& name) {
  static std::map<std::string, robots::RobotModel> cache;
  auto it = cache.find(name);
  if (it == cache.end()) it = cache.emplace(name, robots::load_robot(name)).first;
  return it->second;
}

// A random configuration around home, within the limits.
VectorXd random_q(const robots::RobotModel& m, std::mt19937_64& rng, double spread) {
  std::uniform_real_distribution<double> u(-spread, spread);
  VectorXd q = m.home;
  for (int j = 0; j < m.dof(); ++j) q[j] += u(rng);
  return m.clamp(q);
}

// A ring of radius 0.15 whose strand runs through the hand's centre along v_swd, the ring lying
// ahead of the hand: the geometry of a hand reaching around a handle.
servo::Points ring_through_hand(const servo::HandKinematics& hand, const Vector3d& centre) {
  return circle(centre + 0.15 * hand.forward, 0.15, -hand.forward, hand.sideways, 96);
}

std::vector<ClaspTarget> far_target(const Vector3d& at) {
  return {{at, Vector3d::UnitY()}};
}

// Central differences of a feature's value at q, column by column.
template <class F>
Eigen::MatrixXd numeric_jacobian(const VectorXd& q, int rows, F value, double h = 1e-6) {
  Eigen::MatrixXd J(rows, q.size());
  for (int j = 0; j < q.size(); ++j) {
    VectorXd plus = q, minus = q;
    plus[j] += h;
    minus[j] -= h;
    J.col(j) = (value(plus) - value(minus)) / (2.0 * h);
  }
  return J;
}

void expect_close(const Eigen::MatrixXd& analytic, const Eigen::MatrixXd& numeric,
                  const std::string& what) {
  ASSERT_EQ(analytic.rows(), numeric.rows());
  ASSERT_EQ(analytic.cols(), numeric.cols());
  for (int i = 0; i < analytic.rows(); ++i) {
    for (int j = 0; j < analytic.cols(); ++j) {
      const double a = analytic(i, j), n = numeric(i, j);
      EXPECT_TRUE(std::abs(a - n) <= 1e-7 || std::abs(a - n) <= 1e-5 * std::abs(n))
          << what << " (" << i << ", " << j << "): analytic " << a << " numeric " << n;
    }
  }
}

TEST(TaskFeatures, JacobiansMatchCentralDifferencesOnAllHands) {
  std::mt19937_64 rng(17);
  for (const char* name : kRobots) {
    const robots::RobotModel& m = robot(name);
    for (int trial = 0; trial < 3; ++trial) {
      const VectorXd q = random_q(m, rng, 0.3);
      // First place a loop through the hand at q, then build the controller around it.
      servo::ClaspController probe(
          m, circle(Vector3d(5, 0, 0), 0.1, Vector3d::UnitX(), Vector3d::UnitY(), 8),
          far_target(Vector3d(5, 0, 0)));
      const Vector3d centre = probe.project(q).position;
      const servo::Points loop = ring_through_hand(probe.hand(), centre);
      // The target ahead and to the side, so that t_near is well defined.
      const std::vector<ClaspTarget> targets = {
          {centre + Vector3d(0.2, 0.1, -0.05), Vector3d(0.3, 1.0, 0.2).normalized()}};
      servo::ClaspController c(m, loop, targets);
      const servo::TaskState x = c.project(q);
      ASSERT_GT(x.linking, 0.0) << name << ": the ring should pass through the hand";
      const Eigen::MatrixXd J_pos = c.position_feature().jacobian();
      const Eigen::MatrixXd J_align = c.alignment_feature().jacobian();
      const Eigen::MatrixXd J_vlink = c.linking_feature().jacobian();
      // ViSP's interaction() is the same Jacobian.
      const vpMatrix L = const_cast<servo::PositionFeature&>(c.position_feature()).interaction();
      ASSERT_EQ(L.getRows(), 3u);
      EXPECT_EQ(L[2][m.dof() - 1], J_pos(2, m.dof() - 1));
      expect_close(J_pos,
                   numeric_jacobian(
                       q, 3, [&](const VectorXd& p) { return VectorXd(c.project(p).position); }),
                   std::string(name) + " position");
      expect_close(J_align,
                   numeric_jacobian(
                       q, 2, [&](const VectorXd& p) { return VectorXd(c.project(p).alignment); }),
                   std::string(name) + " alignment");
      expect_close(
          J_vlink,
          numeric_jacobian(
              q, 1, [&](const VectorXd& p) { return VectorXd::Constant(1, c.project(p).linking); }),
          std::string(name) + " virtual linking");
      // Linking depends on the hand's shape only: its arm columns vanish.
      EXPECT_LT(J_vlink.leftCols(m.arm_dof).norm(), 1e-9) << name;
    }
  }
}

TEST(TaskFeatures, AlignmentIsOneOneExactlyWhenAligned) {
  for (const char* name : kRobots) {
    const robots::RobotModel& m = robot(name);
    servo::ClaspController probe(
        m, circle(Vector3d(5, 0, 0), 0.1, Vector3d::UnitX(), Vector3d::UnitY(), 8),
        far_target(Vector3d(5, 0, 0)));
    const Vector3d centre = probe.project(m.home).position;
    const servo::HandKinematics hand = probe.hand();
    const servo::Points loop = ring_through_hand(hand, centre);
    // Aligned: the target straight ahead of the hand, its tangent along v_swd (either sign).
    for (double sign : {1.0, -1.0}) {
      servo::ClaspController c(m, loop, {{centre + 0.1 * hand.forward, sign * hand.sideways}});
      const Eigen::Vector2d a = c.project(m.home).alignment;
      EXPECT_NEAR(a[0], 1.0, 1e-12) << name;
      EXPECT_NEAR(a[1], 1.0, 1e-12) << name;
    }
    // Off to the side, or with the tangent turned: below (1, 1).
    servo::ClaspController side(
        m, loop, {{centre + 0.1 * hand.forward + 0.05 * hand.sideways, hand.sideways}});
    EXPECT_LT(side.project(m.home).alignment[1], 0.99) << name;
    servo::ClaspController turned(
        m, loop,
        {{centre + 0.1 * hand.forward, (hand.sideways + 0.5 * hand.forward).normalized()}});
    EXPECT_LT(turned.project(m.home).alignment[0], 0.95) << name;
  }
}

TEST(TaskFeatures, AlignmentWithoutTargetsIsRefused) {
  EXPECT_THROW(servo::AlignmentFeature({}, 0.01), std::invalid_argument);
}

TEST(TaskFeatures, AlignmentKeepsItsLastDirectionAtTheTarget) {
  const robots::RobotModel& m = robot("kr5_sdh");
  servo::ClaspController probe(
      m, circle(Vector3d(5, 0, 0), 0.1, Vector3d::UnitX(), Vector3d::UnitY(), 8),
      far_target(Vector3d(5, 0, 0)));
  const Vector3d centre = probe.project(m.home).position;
  const servo::HandKinematics hand = probe.hand();
  // Seen from slightly off-axis, then with the hand centre on the target.
  servo::ClaspController c(m, ring_through_hand(hand, centre), {{centre, hand.sideways}});
  const double at_target = c.project(m.home).alignment[1];
  EXPECT_TRUE(std::isfinite(at_target));
  EXPECT_DOUBLE_EQ(at_target, 1.0);  // no direction kept yet: v_fwd itself
}

TEST(TaskFeatures, AlignmentStaysInTheNullSpaceOfPositionOnARealRobot) {
  std::mt19937_64 rng(23);
  servo::PriorityParameters p;
  p.damping = 0.0;
  for (const char* name : kRobots) {
    const robots::RobotModel& m = robot(name);
    const VectorXd q = random_q(m, rng, 0.3);
    servo::ClaspController c(
        m, circle(Vector3d(0.8, 0, 0.5), 0.1, Vector3d::UnitX(), Vector3d::UnitY(), 16),
        {{Vector3d(0.9, 0.2, 0.4), Vector3d::UnitZ()}});
    c.project(q);
    const VectorXd ones = VectorXd::Ones(m.dof());
    const auto none = Eigen::Array<bool, Eigen::Dynamic, 1>::Constant(m.dof(), false);
    const servo::TaskTerm pos{Eigen::Vector3d(0.05, -0.02, 0.01), c.position_feature().jacobian()};
    const servo::TaskTerm align{Eigen::Vector2d(0.3, 0.2), c.alignment_feature().jacobian()};
    const servo::TaskTerm no_align{Eigen::Vector2d::Zero(), align.jacobian};
    const servo::TaskTerm vlink{VectorXd::Zero(1), c.linking_feature().jacobian()};
    const auto with = servo::prioritized_velocity(pos, align, vlink, 0.5, ones, ones, none, p);
    const auto without =
        servo::prioritized_velocity(pos, no_align, vlink, 0.5, ones, ones, none, p);
    EXPECT_LT((pos.jacobian * (with.arm - without.arm)).norm(), 1e-9) << name;
    EXPECT_GT((with.arm - without.arm).norm(), 1e-4) << name;
  }
}

TEST(ClaspController, StepsStayWithinJointLimits) {
  std::mt19937_64 rng(29);
  const robots::RobotModel& m = robot("kr5_icub");
  servo::ClaspController c(
      m, circle(Vector3d(0.7, 0, 0.4), 0.1, Vector3d::UnitX(), Vector3d::UnitY(), 16),
      {{Vector3d(0.6, 0.0, 0.4), Vector3d::UnitY()}});
  VectorXd q = m.home;
  // Drive toward a point far out of reach, with the hand asked to close fully.
  for (int i = 0; i < 200; ++i) {
    const VectorXd next = c.step(q, Vector3d(3.0, 2.0, 2.0), 1.0);
    ASSERT_TRUE(m.within_limits(next)) << "step " << i;
    EXPECT_LE((next - q).cwiseAbs().maxCoeff(), 0.05 + 1e-12);
    q = next;
  }
}

}  // namespace
}  // namespace claspplan::test
