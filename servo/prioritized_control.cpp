#include "servo/prioritized_control.hpp"

#include <cmath>

#include <Eigen/Eigenvalues>

namespace claspplan::servo {

Eigen::MatrixXd damped_pseudo_inverse(const Eigen::MatrixXd& J, double damping, double threshold) {
  // Task Jacobians have 1–3 rows: work with the small Gram matrix J Jᵀ = V diag(σ²) Vᵀ.
  const Eigen::MatrixXd gram = J * J.transpose();
  const Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd> eig(gram);
  const Eigen::VectorXd sigma2 = eig.eigenvalues().cwiseMax(0.0);
  const double sigma_min = std::sqrt(sigma2.minCoeff());
  double lambda2 = 0.0;
  if (damping > 0.0 && sigma_min < threshold) {
    const double r = sigma_min / threshold;
    lambda2 = (1.0 - r * r) * damping * damping;
  }
  // Directions with (numerically) no singular value are dropped, as the Moore–Penrose inverse does.
  const double tolerance = 1e-12 * std::max(1.0, sigma2.maxCoeff());
  Eigen::VectorXd inverse(sigma2.size());
  for (Eigen::Index i = 0; i < sigma2.size(); ++i) {
    const double s = sigma2[i] + lambda2;
    inverse[i] = (sigma2[i] > tolerance) ? 1.0 / s : 0.0;
  }
  return J.transpose() * eig.eigenvectors() * inverse.asDiagonal() * eig.eigenvectors().transpose();
}

double priority_gain(double position_error, const PriorityParameters& p) {
  return 1.0 / (1.0 + std::exp(-(position_error - p.gain_distance) / p.gain_width));
}

namespace {

// A task restricted to the joints its mask allows: returns q̇ = M (J M)⁺ u and, through `pinv` and
// `scaled`, the pieces needed for null-space projection in the scaled coordinates z (q̇ = M z).
struct WeightedTask {
  Eigen::MatrixXd scaled;  // J M
  Eigen::MatrixXd pinv;    // (J M)⁺
};

WeightedTask weigh(const TaskTerm& t, const Eigen::VectorXd& mask, const PriorityParameters& p) {
  WeightedTask w;
  w.scaled = t.jacobian * mask.asDiagonal();
  w.pinv = damped_pseudo_inverse(w.scaled, p.damping, p.singular_threshold);
  return w;
}

}  // namespace

PrioritizedStep prioritized_velocity(const TaskTerm& position, const TaskTerm& alignment,
                                     const TaskTerm& linking, double gain,
                                     const Eigen::VectorXd& arm_mask,
                                     const Eigen::VectorXd& hand_mask,
                                     const Eigen::Array<bool, Eigen::Dynamic, 1>& locked,
                                     const PriorityParameters& p,
                                     const Eigen::VectorXd& pose_bias) {
  const Eigen::Index n = arm_mask.size();
  const Eigen::VectorXd free = (!locked).cast<double>().matrix();
  const Eigen::VectorXd m_arm = arm_mask.cwiseProduct(free);
  const Eigen::VectorXd m_hand = hand_mask.cwiseProduct(free);

  // Line 10: position first, alignment in its null space (in the arm's scaled coordinates).
  const WeightedTask pos = weigh(position, m_arm, p);
  const WeightedTask align = weigh(alignment, m_arm, p);
  const Eigen::MatrixXd null_pos = Eigen::MatrixXd::Identity(n, n) - pos.pinv * pos.scaled;
  PrioritizedStep step;
  Eigen::VectorXd z = pos.pinv * position.error + null_pos * (align.pinv * alignment.error);
  if (pose_bias.size() == n) {
    // The pose bias in the null space of position and alignment together.
    Eigen::MatrixXd both(pos.scaled.rows() + align.scaled.rows(), n);
    both << pos.scaled, align.scaled;
    const Eigen::MatrixXd both_pinv = damped_pseudo_inverse(both, 0.0, p.singular_threshold);
    z += pose_bias - both_pinv * (both * pose_bias);
  }
  step.arm = m_arm.asDiagonal() * z;

  // Line 11: the hand's virtual-linking task.
  const WeightedTask vlink = weigh(linking, m_hand, p);
  step.hand = m_hand.asDiagonal() * (vlink.pinv * linking.error);

  // Lines 12–14: the arm's motion continues in the null space of the linking task.
  step.gain = gain;
  const Eigen::MatrixXd J_vlink = linking.jacobian * free.asDiagonal();
  const Eigen::MatrixXd vlink_pinv =
      damped_pseudo_inverse(J_vlink, p.damping, p.singular_threshold);
  const Eigen::VectorXd arm_in_null = step.arm - vlink_pinv * (J_vlink * step.arm);
  step.velocity = step.gain * step.arm + (1.0 - step.gain) * (step.hand + arm_in_null);
  return step;
}

Eigen::VectorXd limit_step_size(const Eigen::VectorXd& velocity, const PriorityParameters& p) {
  Eigen::VectorXd step = p.dt * velocity;
  const double largest = step.cwiseAbs().maxCoeff();
  if (largest > p.max_step) step *= p.max_step / largest;
  return step;
}

}  // namespace claspplan::servo
