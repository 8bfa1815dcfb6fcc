#include "tsrrt/clasp_planning.hpp"

#include <algorithm>
#include <cmath>

#include <Eigen/Geometry>

#include "perception/random_draws.hpp"
#include "robots/kinematics.hpp"
#include "servo/linking.hpp"

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
  if (report.second == "unseen space") return MotionCheck::kUnseen;
  return MotionCheck::kEnvironment;  // "box <i>", "cylinder <i>"
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

ApproachFrame approach_frame(const servo::Points& loop, const servo::ClaspTarget& target) {
  // The loop's centroid, weighting each point by its two half segments (uneven sampling).
  Eigen::Vector3d centre = Eigen::Vector3d::Zero();
  double total = 0.0;
  const std::size_t n = loop.size();
  for (std::size_t i = 0; i < n; ++i) {
    const double w = (loop[(i + 1) % n] - loop[i]).norm();
    centre += w * 0.5 * (loop[i] + loop[(i + 1) % n]);
    total += w;
  }
  centre = total > 0.0 ? Eigen::Vector3d(centre / total) : target.point;
  ApproachFrame f;
  f.t = target.tangent.normalized();
  f.r = target.point - centre;
  f.r -= f.t * f.t.dot(f.r);
  f.r = f.r.norm() > 1e-9 ? Eigen::Vector3d(f.r.normalized()) : f.t.unitOrthogonal();
  f.n = f.t.cross(f.r);
  return f;
}

std::vector<Eigen::Vector2d> approach_angles() {
  const double s = std::sqrt(0.5);
  return {{1, 0}, {0, 1}, {0, -1}, {s, s}, {s, -s}};
}

std::vector<Eigen::Vector3d> clasp_approaches(const servo::Points& loop,
                                              const servo::ClaspTarget& target, double distance) {
  const ApproachFrame frame = approach_frame(loop, target);
  std::vector<Eigen::Vector3d> points;
  for (const auto& angle : approach_angles())
    points.push_back(target.point + distance * frame.direction(angle));
  return points;
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

Eigen::VectorXd close_fingers(const robots::RobotModel& model, robots::CollisionWorld& world,
                              const Eigen::VectorXd& q_start, const FingerClosingOptions& o) {
  Eigen::VectorXd q = q_start;
  robots::RobotData data(model);
  const Eigen::VectorXd lower = model.lower(), upper = model.upper();
  const auto blocked_link = [&](const robots::Finger& finger) {
    for (int link : finger.links) {
      if (world.link_near_object(data, link, o.clearance) ||
          world.link_in_collision(data, link, nullptr, /*include_self=*/true))
        return link;
    }
    return -1;
  };
  // All fingers close together, one step each per round, so that opposing fingers meet halfway.
  // A blocked link freezes the joints that move it while the joints beyond it keep closing, so
  // that a finger stopped at its base by a narrow hole still curls its tip around the bar.
  std::vector<std::vector<bool>> active;
  for (const auto& finger : model.fingers) active.emplace_back(finger.joints.size(), true);
  for (int round = 0; round < o.max_steps; ++round) {
    bool any = false;
    for (std::size_t f = 0; f < model.fingers.size(); ++f) {
      const robots::Finger& finger = model.fingers[f];
      for (;;) {
        Eigen::VectorXd trial = q;
        for (std::size_t k = 0; k < finger.joints.size(); ++k) {
          const int j = finger.joints[k];
          if (active[f][k]) trial[j] += model.joints[j].closing * o.step;
        }
        trial = trial.cwiseMax(lower).cwiseMin(upper);
        if (trial == q) break;  // no active joint, or all at their limits
        robots::forward_kinematics(model, trial, data);
        const int link = blocked_link(finger);
        if (link < 0) {
          q = trial;
          any = true;
          break;
        }
        // Freeze the joints that move the blocked link; when none is active the finger is done.
        bool froze = false;
        for (std::size_t k = 0; k < finger.joints.size(); ++k) {
          if (!active[f][k]) continue;
          for (int s : model.links[link].support) {
            if (model.links[s].q_index == finger.joints[k]) {
              active[f][k] = false;
              froze = true;
            }
          }
        }
        if (!froze) std::fill(active[f].begin(), active[f].end(), false);
      }
    }
    if (!any) break;
  }
  return q;
}

std::vector<Eigen::VectorXd> approach_until_contact(const robots::RobotModel& model,
                                                    robots::CollisionWorld& world,
                                                    const Eigen::VectorXd& q,
                                                    const ApproachOptions& o) {
  std::vector<Eigen::VectorXd> poses;
  if (!(o.step > 0) || !(o.distance > 0) || model.tool_link < 0) return poses;
  const int n = model.arm_dof;
  robots::RobotData data(model);
  robots::forward_kinematics(model, q, data);
  const Eigen::Vector3d direction = robots::vector_direction(data, model.v_fwd);
  const Eigen::Vector3d start = robots::point_position(data, model.tcp);
  const Eigen::Matrix3d orientation = data.link_poses[model.tool_link].linear();
  // The least squares' damping, and how far from the line (m, rad) a step may end.
  constexpr double kDamping = 1e-3, kLineTolerance = 1e-3;
  Eigen::VectorXd current = q;
  const int steps = static_cast<int>(std::floor(o.distance / o.step + 1e-9));
  for (int k = 1; k <= steps; ++k) {
    const Eigen::Vector3d goal = start + (k * o.step) * direction;
    Eigen::VectorXd next = current;
    Eigen::Matrix<double, 6, 1> error;
    for (int iteration = 0;; ++iteration) {  // Newton steps, damped least squares
      robots::forward_kinematics(model, next, data);
      error.head<3>() = goal - robots::point_position(data, model.tcp);
      const Eigen::AngleAxisd turn(orientation *
                                   data.link_poses[model.tool_link].linear().transpose());
      error.tail<3>() = turn.angle() * turn.axis();
      if (error.norm() < 1e-6 || iteration == 5) break;
      Eigen::Matrix<double, 6, Eigen::Dynamic> J(6, n);
      J.topRows<3>() =
          robots::point_jacobian(model, data, model.tcp.link, model.tcp.point).leftCols(n);
      J.bottomRows<3>() = robots::angular_jacobian(model, data, model.tool_link).leftCols(n);
      const Eigen::Matrix<double, 6, 6> JJt =
          J * J.transpose() + kDamping * kDamping * Eigen::Matrix<double, 6, 6>::Identity();
      next.head(n) += J.transpose() * JJt.ldlt().solve(error);
    }
    // `data` holds the kinematics at `next`: the Newton loop ends right after computing them.
    if (error.norm() > kLineTolerance || !model.within_limits(next) || world.in_collision(data))
      break;
    poses.push_back(next);
    current = next;
  }
  return poses;
}

std::vector<double> open_finger_linking(const robots::RobotModel& model, const Eigen::VectorXd& q,
                                        const servo::Points& loop) {
  robots::RobotData data(model);
  robots::FingerCurvesData curves;
  robots::finger_curves(model, q, data, curves, false);
  std::vector<double> values;
  for (const auto& curve : curves.points) {
    values.push_back(std::abs(servo::gauss_linking(loop, true, curve, false)));
  }
  return values;
}

void loop_tube(const servo::Points& loop, double radius, std::vector<Eigen::Vector3d>& vertices,
               std::vector<Eigen::Vector3i>& triangles) {
  constexpr int kSides = 6;
  const int n = static_cast<int>(loop.size());
  const int first = static_cast<int>(vertices.size());
  // Rings of vertices around each loop point, in the plane normal to the mean of its two
  // segments; the ring's frame is carried along the loop (parallel transport), so neighbouring
  // rings line up and the band between them does not twist.
  Eigen::Vector3d u = Eigen::Vector3d::Zero();
  for (int i = 0; i < n; ++i) {
    const Eigen::Vector3d tangent = (loop[(i + 1) % n] - loop[(i + n - 1) % n]).normalized();
    u = (i == 0) ? tangent.unitOrthogonal() : (u - tangent * tangent.dot(u));
    if (u.norm() < 1e-9) u = tangent.unitOrthogonal();  // a hairpin turn
    u.normalize();
    const Eigen::Vector3d v = tangent.cross(u);
    for (int k = 0; k < kSides; ++k) {
      const double a = 2.0 * 3.14159265358979323846 * k / kSides;
      vertices.push_back(loop[i] + radius * (std::cos(a) * u + std::sin(a) * v));
    }
  }
  for (int i = 0; i < n; ++i) {
    const int a = first + i * kSides, b = first + ((i + 1) % n) * kSides;
    for (int k = 0; k < kSides; ++k) {
      const int k1 = (k + 1) % kSides;
      triangles.emplace_back(a + k, a + k1, b + k1);
      triangles.emplace_back(a + k, b + k1, b + k);
    }
  }
}

}  // namespace claspplan::tsrrt
