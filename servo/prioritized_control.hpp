// The task hierarchy of TS-CONTROL (paper Alg. 4, lines 10–15), on task errors and Jacobians:
//   q̇_arm  = J_pos⁺ u_pos + (I − J_pos⁺ J_pos) J_align⁺ u_align + N_pos,align q̇_pose
//   q̇_hand = J_vlink⁺ u_vlink
//   q̇      = α q̇_arm + (1 − α) (q̇_hand + (I − J_vlink⁺ J_vlink) q̇_arm),  α = GAIN(‖u_pos‖)
//   q      = q₀ + LIMIT-STEP-SIZE(Δt q̇)
// The masks M_arm and M_hand weight the joints inside each pseudo-inverse, q̇ = M (J M)⁺ u, so that
// each task is solved exactly on the joints it may use (arm tasks on the arm, linking on the
// hand). Multiplying by M after the pseudo-inverse, as Alg. 4 writes it, would leave the position
// task short by whatever the pseudo-inverse had given to the hand joints.
// q̇_pose is the paper's "permanent robot pose bias" (Sec. III-C), lowest in priority: projected
// into the null space of both arm tasks, it only chooses among poses that serve them equally.
#pragma once

#include <Eigen/Core>

namespace claspplan::servo {

/// Damped least-squares pseudo-inverse J⁺ = Jᵀ (J Jᵀ + λ² I)⁻¹ of a task Jacobian with at most a
/// few rows. λ is zero while the smallest singular value σ stays above `threshold` and grows
/// smoothly to `damping` as σ → 0, so exact tasks stay exact away from singularities. With damping
/// = 0 it is the Moore–Penrose pseudo-inverse (rank-deficient directions are dropped).
Eigen::MatrixXd damped_pseudo_inverse(const Eigen::MatrixXd& J, double damping, double threshold);

/// Parameters of the hierarchy. Distances in metres, angles in radians.
struct PriorityParameters {
  /// GAIN(‖u_pos‖) = 1/(1 + exp(−(‖u_pos‖ − gain_distance)/gain_width)): the arm tasks lead while
  /// the hand is farther than gain_distance from its goal, the linking task leads once it is
  /// closer.
  double gain_distance = 0.02;
  double gain_width = 0.004;
  double dt = 1.0;         ///< Δt: the fraction of the Gauss–Newton correction taken per step
  double max_step = 0.05;  ///< LIMIT-STEP-SIZE: the largest joint change per step (rad)
  double damping = 0.02;   ///< λ_max of the damped pseudo-inverses
  double singular_threshold = 0.01;  ///< σ below which damping starts
};

/// The sigmoid GAIN of Alg. 4, line 12.
double priority_gain(double position_error, const PriorityParameters& p);

/// One task: its error u = c − Π(q) and Jacobian J = ∂Π/∂q (rows × dof).
struct TaskTerm {
  Eigen::VectorXd error;
  Eigen::MatrixXd jacobian;
};

/// What one step decided, for logging and tests.
struct PrioritizedStep {
  Eigen::VectorXd velocity;  ///< q̇ before LIMIT-STEP-SIZE
  Eigen::VectorXd arm;       ///< q̇_arm
  Eigen::VectorXd hand;      ///< q̇_hand
  double gain = 0.0;         ///< α
};

/// Alg. 4 lines 10–14 with α = `gain` (priority_gain() of the hand's distance to its goal).
/// `arm_mask` and `hand_mask` are the diagonals of M_arm and M_hand (one weight per joint, 0 to
/// 1). Joints flagged in `locked` (e.g. at a joint limit, moving outward) get no motion.
/// `pose_bias` (empty: none) is q̇_pose, a joint velocity served in the arm tasks' null space.
PrioritizedStep prioritized_velocity(const TaskTerm& position, const TaskTerm& alignment,
                                     const TaskTerm& linking, double gain,
                                     const Eigen::VectorXd& arm_mask,
                                     const Eigen::VectorXd& hand_mask,
                                     const Eigen::Array<bool, Eigen::Dynamic, 1>& locked,
                                     const PriorityParameters& p,
                                     const Eigen::VectorXd& pose_bias = Eigen::VectorXd());

/// LIMIT-STEP-SIZE(Δt q̇): scales the step so that no joint moves more than p.max_step.
Eigen::VectorXd limit_step_size(const Eigen::VectorXd& velocity, const PriorityParameters& p);

}  // namespace claspplan::servo
