#include "tsrrt/clasp_problem.hpp"

#include <algorithm>
#include <cmath>

#include "core/random_draws.hpp"
#include "robots/kinematics.hpp"
#include "tsrrt/approach.hpp"

namespace claspplan::tsrrt {

ClaspProblem::ClaspProblem(servo::ClaspController& controller, robots::CollisionWorld& world,
                           double goal_linking, double position_tolerance, double resolution,
                           std::function<bool(const Eigen::VectorXd&)> acceptance)
    : controller_(controller),
      world_(world),
      goal_linking_(goal_linking),
      position_tolerance_(position_tolerance),
      resolution_(resolution),
      acceptance_(std::move(acceptance)) {
  // The open hand's reach from its centre.
  const robots::RobotModel& model = controller_.model();
  robots::RobotData data(model);
  robots::FingerCurvesData curves;
  robots::finger_curves(model, model.home, data, curves, false);
  Eigen::AlignedBox3d box;
  for (const auto& curve : curves.points)
    for (const auto& point : curve) box.extend(point);
  const double reach = box.isEmpty() ? 0.0 : 0.5 * box.diagonal().norm();
  approach_distance_ = std::clamp(reach + 0.02, 0.08, 0.12);
}

TaskPoint ClaspProblem::project(const Eigen::VectorXd& q) {
  const servo::TaskState x = controller_.project(q);
  return {x.position, x.linking};
}

Eigen::VectorXd ClaspProblem::control(const Eigen::VectorXd& q0, const TaskPoint& x0,
                                      const TaskPoint& x1) {
  (void)x0;  // the controller recomputes the features at q0 itself
  // The alignment task keeps its last direction only along one continuous trajectory.
  if (last_q_.size() != q0.size() || last_q_ != q0) controller_.forget_direction();
  last_q_ = controller_.step(q0, x1.position, x1.linking);
  limited_ = false;
  const robots::RobotModel& model = controller_.model();
  for (int j = 0; j < model.dof() && !limited_; ++j) {
    const robots::Joint& joint = model.joints[j];
    limited_ = !joint.hand && last_q_[j] == q0[j] &&
               (q0[j] <= joint.lower + kLimitMargin || q0[j] >= joint.upper - kLimitMargin);
  }
  return last_q_;
}

MotionCheck ClaspProblem::check_motion(const Eigen::VectorXd& q0, const Eigen::VectorXd& q1) {
  robots::CollisionReport report;
  if (world_.motion_free(q0, q1, resolution_, &report)) return MotionCheck::kFree;
  if (report.second == "object") return MotionCheck::kObject;
  if (report.second_link >= 0) return MotionCheck::kSelf;
  if (report.second == "unseen space") {
    if (unseen_hits_.size() < kMaxContacts) unseen_hits_.push_back(world_.environment_hit());
    return MotionCheck::kUnseen;
  }
  return MotionCheck::kEnvironment;  // "box <i>", "cylinder <i>"
}

bool ClaspProblem::shortcut_free(const Eigen::VectorXd& q0, const Eigen::VectorXd& q1) {
  const double travel = world_.motion_travel();
  return world_.motion_free(q0, q1, resolution_,
                            travel > 0.0 ? std::min(travel, kShortcutTravel) : kShortcutTravel);
}

std::vector<Eigen::Vector3d> ClaspProblem::unseen_contacts() const {
  return world_.contact_points(unseen_hits_);
}

bool ClaspProblem::sample_configuration(const std::function<std::uint64_t()>& bits,
                                        Eigen::VectorXd& q) {
  const robots::RobotModel& model = controller_.model();
  for (int draw = 0; draw < 20; ++draw) {
    q = model.home;
    for (int j = 0; j < model.arm_dof; ++j) {
      const robots::Joint& joint = model.joints[j];
      q[j] = joint.lower + uniform01(bits()) * (joint.upper - joint.lower);
    }
    if (!world_.in_collision(q)) return true;
  }
  return false;
}

std::vector<TaskPoint> ClaspProblem::approaches(int goal) {
  const auto& targets = controller_.targets();
  if (goal < 0 || goal >= static_cast<int>(targets.size())) return {};
  std::vector<TaskPoint> points;
  for (const auto& p : clasp_approaches(controller_.loop(), targets[goal], approach_distance_)) {
    points.push_back({p, 0.0});  // the hand open on the way
  }
  return points;
}

bool ClaspProblem::reached(const TaskPoint& x, const TaskPoint& goal) const {
  return x.linking >= goal_linking_ &&
         (position_tolerance_ <= 0.0 || (x.position - goal.position).norm() <= position_tolerance_);
}

}  // namespace claspplan::tsrrt
