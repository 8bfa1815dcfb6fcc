#include "servo/clasp_controller.hpp"

#include <stdexcept>
#include <utility>

namespace claspplan::servo {
namespace {

// The task term u = c − Π(q), J = ∂Π/∂q of a feature against its goal, through ViSP's interface:
// error() gives s − s*, interaction() the joint-space Jacobian.
TaskTerm task_term(JointSpaceFeature& feature, const FeatureGoal& goal) {
  const vpColVector e = feature.error(goal);
  const vpMatrix L = feature.interaction();
  TaskTerm t;
  t.error = -Eigen::Map<const Eigen::VectorXd>(e.data, e.getRows());
  t.jacobian =
      Eigen::Map<const Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, Eigen::RowMajor>>(
          L.data, L.getRows(), L.getCols());
  return t;
}

}  // namespace

ClaspController::ClaspController(const robots::RobotModel& model, Points loop,
                                 std::vector<ClaspTarget> targets,
                                 const ControllerParameters& parameters)
    : model_(model),
      p_(parameters),
      data_(model),
      alignment_(std::move(targets), parameters.hold_distance),
      linking_(std::move(loop)) {
  if (alignment_.targets().empty())
    throw std::invalid_argument("the controller needs at least one clasp target");
  if (model.curves.empty())
    throw std::invalid_argument(model.name + ": the hand has no finger curves");
  arm_mask_.resize(model.dof());
  hand_mask_.resize(model.dof());
  for (int j = 0; j < model.dof(); ++j) {
    const bool hand = model.joints[j].hand;
    arm_mask_[j] = hand ? p_.hand_in_arm_tasks : 1.0;
    hand_mask_[j] = hand ? 1.0 : p_.arm_in_hand_task;
  }
  mid_ = 0.5 * (model.lower() + model.upper());
  const Eigen::VectorXd half = 0.5 * (model.upper() - model.lower());
  bias_weight_ = Eigen::VectorXd::Zero(model.dof());
  for (int j = 0; j < model.dof(); ++j) {
    if (!model.joints[j].hand && half[j] > 0.0)
      bias_weight_[j] = p_.pose_bias_gain / (half[j] * half[j]);
  }
}

void ClaspController::update(const Eigen::VectorXd& q) {
  if (updated_ && q.size() == updated_q_.size() && q == updated_q_) return;
  robots::forward_kinematics(model_, q, data_);
  // Reuse the hand's buffers: robots fills the same layout.
  std::swap(curves_.points, hand_.curves);
  std::swap(curves_.jacobians, hand_.curve_jacobians);
  robots::finger_curves(model_, data_, curves_, true);
  std::swap(curves_.points, hand_.curves);
  std::swap(curves_.jacobians, hand_.curve_jacobians);
  hand_.forward = robots::vector_direction(data_, model_.v_fwd);
  hand_.sideways = robots::vector_direction(data_, model_.v_swd);
  hand_.forward_jacobian = robots::vector_jacobian(model_, data_, model_.v_fwd);
  hand_.sideways_jacobian = robots::vector_jacobian(model_, data_, model_.v_swd);
  position_.update(hand_);
  alignment_.update(hand_, position_);
  linking_.update(hand_);
  updated_q_ = q;
  updated_ = true;
}

TaskState ClaspController::project(const Eigen::VectorXd& q) {
  update(q);
  TaskState x;
  x.position = position_.position();
  x.alignment = Eigen::Vector2d(alignment_.value(0), alignment_.value(1));
  x.linking = linking_.value(0);
  x.finger_linking = linking_.finger_values();
  x.nearest_target = alignment_.nearest_target();
  return x;
}

Eigen::VectorXd ClaspController::step(const Eigen::VectorXd& q0, const Eigen::Vector3d& c_pos,
                                      double c_vlink) {
  update(q0);
  // Alg. 4 lines 1–9: task errors and Jacobians.
  TaskTerm pos = task_term(position_, FeatureGoal(c_pos));
  const double distance = pos.error.norm();
  const TaskTerm align = task_term(alignment_, FeatureGoal(Eigen::Vector2d(1.0, 1.0)));
  const TaskTerm vlink = task_term(linking_, FeatureGoal(Eigen::VectorXd::Constant(1, c_vlink)));

  // Lines 10–15, holding joints that a step would push past their limits.
  const Eigen::VectorXd lower = model_.lower(), upper = model_.upper();
  const Eigen::VectorXd pose_bias = bias_weight_.cwiseProduct(mid_ - q0);
  Eigen::Array<bool, Eigen::Dynamic, 1> locked =
      Eigen::Array<bool, Eigen::Dynamic, 1>::Constant(q0.size(), false);
  Eigen::VectorXd q1 = q0;
  const double gain = priority_gain(distance, p_.priority);  // line 12, on the true distance
  if (p_.max_position_error > 0.0 && distance > p_.max_position_error) {
    pos.error *= p_.max_position_error / distance;
  }
  for (int attempt = 0; attempt < 3; ++attempt) {
    last_ = prioritized_velocity(pos, align, vlink, gain, arm_mask_, hand_mask_, locked,
                                 p_.priority, pose_bias);
    q1 = q0 + limit_step_size(last_.velocity, p_.priority);
    bool changed = false;
    for (Eigen::Index j = 0; j < q1.size(); ++j) {
      if (!locked[j] && (q1[j] > upper[j] || q1[j] < lower[j])) locked[j] = changed = true;
    }
    if (!changed) break;
  }
  return model_.couple(q1.cwiseMax(lower).cwiseMin(upper));
}

}  // namespace claspplan::servo
