// The task hierarchy of Alg. 4 on random task Jacobians.
#include "servo/prioritized_control.hpp"

#include <random>

#include <Eigen/QR>
#include <gtest/gtest.h>

namespace claspplan::test {
namespace {

using servo::PriorityParameters;
using servo::TaskTerm;

Eigen::MatrixXd random_matrix(std::mt19937_64& rng, int rows, int cols) {
  std::normal_distribution<double> n01;
  Eigen::MatrixXd m(rows, cols);
  for (int i = 0; i < rows; ++i)
    for (int j = 0; j < cols; ++j) m(i, j) = n01(rng);
  return m;
}

TaskTerm random_task(std::mt19937_64& rng, int rows, int cols) {
  return {random_matrix(rng, rows, 1), random_matrix(rng, rows, cols)};
}

Eigen::Array<bool, Eigen::Dynamic, 1> none_locked(int n) {
  return Eigen::Array<bool, Eigen::Dynamic, 1>::Constant(n, false);
}

TEST(DampedPseudoInverse, IsMoorePenroseWithoutDamping) {
  std::mt19937_64 rng(1);
  for (int rows = 1; rows <= 3; ++rows) {
    const Eigen::MatrixXd J = random_matrix(rng, rows, 21);
    const Eigen::MatrixXd expected = J.completeOrthogonalDecomposition().pseudoInverse();
    EXPECT_LT((servo::damped_pseudo_inverse(J, 0.0, 0.01) - expected).norm(), 1e-12);
  }
  // Rank-deficient: two equal rows, and a zero task.
  Eigen::MatrixXd J = random_matrix(rng, 2, 8);
  J.row(1) = J.row(0);
  const Eigen::MatrixXd expected = J.completeOrthogonalDecomposition().pseudoInverse();
  EXPECT_LT((servo::damped_pseudo_inverse(J, 0.0, 0.01) - expected).norm(), 1e-9);
  EXPECT_EQ(servo::damped_pseudo_inverse(Eigen::MatrixXd::Zero(1, 5), 0.1, 0.01).norm(), 0.0);
}

TEST(DampedPseudoInverse, DampsOnlyNearSingularities) {
  std::mt19937_64 rng(2);
  const Eigen::MatrixXd J = random_matrix(rng, 3, 12);
  // Well conditioned: still an exact right inverse with damping on.
  EXPECT_LT(
      (J * servo::damped_pseudo_inverse(J, 0.1, 0.01) - Eigen::MatrixXd::Identity(3, 3)).norm(),
      1e-12);
  // Nearly singular: the damped inverse stays bounded where the exact one explodes.
  Eigen::MatrixXd S = J;
  S.row(2) = S.row(1) + 1e-5 * random_matrix(rng, 1, 12);
  EXPECT_GT(servo::damped_pseudo_inverse(S, 0.0, 0.01).norm(), 1e4);
  EXPECT_LT(servo::damped_pseudo_inverse(S, 0.1, 0.01).norm(), 100.0);
}

TEST(PrioritizedVelocity, AlignmentStaysInTheNullSpaceOfPosition) {
  std::mt19937_64 rng(3);
  PriorityParameters p;
  p.damping = 0.0;
  const int n = 21;
  const Eigen::VectorXd ones = Eigen::VectorXd::Ones(n);
  for (int trial = 0; trial < 20; ++trial) {
    const TaskTerm pos = random_task(rng, 3, n), align = random_task(rng, 2, n);
    const TaskTerm vlink = random_task(rng, 1, n);
    const auto with =
        servo::prioritized_velocity(pos, align, vlink, 0.5, ones, ones, none_locked(n), p);
    const TaskTerm no_align{Eigen::VectorXd::Zero(2), align.jacobian};
    const auto without =
        servo::prioritized_velocity(pos, no_align, vlink, 0.5, ones, ones, none_locked(n), p);
    // The alignment task changes the position task's rate by less than 1e-9 ...
    EXPECT_LT((pos.jacobian * (with.arm - without.arm)).norm(), 1e-9);
    // ... while it does move the joints, and position is reached exactly.
    EXPECT_GT((with.arm - without.arm).norm(), 1e-3);
    EXPECT_LT((pos.jacobian * with.arm - pos.error).norm(), 1e-9);
  }
}

TEST(PrioritizedVelocity, MasksSplitArmAndHandJoints) {
  std::mt19937_64 rng(4);
  PriorityParameters p;
  const int arm = 6, n = 16;
  Eigen::VectorXd arm_mask = Eigen::VectorXd::Zero(n), hand_mask = Eigen::VectorXd::Zero(n);
  arm_mask.head(arm).setOnes();
  hand_mask.tail(n - arm).setOnes();
  const TaskTerm pos = random_task(rng, 3, n), align = random_task(rng, 2, n);
  TaskTerm vlink = random_task(rng, 1, n);
  vlink.jacobian.leftCols(arm).setZero();  // linking depends on the hand's shape only
  const auto s =
      servo::prioritized_velocity(pos, align, vlink, 0.3, arm_mask, hand_mask, none_locked(n), p);
  EXPECT_EQ(s.arm.tail(n - arm).norm(), 0.0);
  EXPECT_EQ(s.hand.head(arm).norm(), 0.0);
  // Each task is still met exactly on its own joints.
  EXPECT_LT((pos.jacobian * s.arm - pos.error).norm(), 1e-9);
  EXPECT_LT((vlink.jacobian * s.hand - vlink.error).norm(), 1e-9);
  // The blend: q̇ = α q̇_arm + (1 − α)(q̇_hand + q̇_arm), as q̇_arm is already in the null space of
  // the linking task.
  EXPECT_LT((s.velocity - (s.arm + (1.0 - s.gain) * s.hand)).norm(), 1e-12);
}

TEST(PrioritizedVelocity, GainShiftsPriorityFromPositionToHand) {
  PriorityParameters p;
  EXPECT_NEAR(servo::priority_gain(p.gain_distance, p), 0.5, 1e-12);
  EXPECT_GT(servo::priority_gain(p.gain_distance + 10 * p.gain_width, p), 0.999);
  EXPECT_LT(servo::priority_gain(0.0, p), 0.01);
  std::mt19937_64 rng(5);
  const int n = 10;
  const Eigen::VectorXd ones = Eigen::VectorXd::Ones(n);
  TaskTerm pos = random_task(rng, 3, n);
  const TaskTerm align = random_task(rng, 2, n), vlink = random_task(rng, 1, n);
  pos.error = pos.error.normalized() * 1.0;  // far away: the hand task is off
  auto far = servo::prioritized_velocity(pos, align, vlink, servo::priority_gain(1.0, p), ones,
                                         ones, none_locked(n), p);
  EXPECT_LT((far.velocity - far.arm).norm(), 1e-6 * far.arm.norm());
}

TEST(PrioritizedVelocity, LockedJointsDoNotMove) {
  std::mt19937_64 rng(6);
  PriorityParameters p;
  const int n = 9;
  const Eigen::VectorXd ones = Eigen::VectorXd::Ones(n);
  auto locked = none_locked(n);
  locked[2] = locked[7] = true;
  const auto s = servo::prioritized_velocity(random_task(rng, 3, n), random_task(rng, 2, n),
                                             random_task(rng, 1, n), 0.5, ones, ones, locked, p);
  EXPECT_EQ(s.velocity[2], 0.0);
  EXPECT_EQ(s.velocity[7], 0.0);
  EXPECT_GT(s.velocity.norm(), 0.0);
}

TEST(LimitStepSize, CapsTheLargestJointChangeKeepingDirection) {
  PriorityParameters p;
  p.max_step = 0.05;
  const Eigen::VectorXd v = (Eigen::VectorXd(3) << 1.0, -0.5, 0.1).finished();
  const Eigen::VectorXd s = servo::limit_step_size(v, p);
  EXPECT_NEAR(s.cwiseAbs().maxCoeff(), 0.05, 1e-15);
  EXPECT_NEAR(s.normalized().dot(v.normalized()), 1.0, 1e-15);
  const Eigen::VectorXd small = 0.001 * v;
  EXPECT_EQ(servo::limit_step_size(small, p), small);
}

}  // namespace
}  // namespace claspplan::test
