#include "tsrrt/approach.hpp"

#include <cmath>

#include <Eigen/Geometry>

#include "robots/kinematics.hpp"

namespace claspplan::tsrrt {

ApproachFrame approach_frame(const servo::Points& loop, const ClaspTarget& target) {
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

std::vector<Eigen::Vector3d> clasp_approaches(const servo::Points& loop, const ClaspTarget& target,
                                              double distance) {
  const ApproachFrame frame = approach_frame(loop, target);
  std::vector<Eigen::Vector3d> points;
  for (const auto& angle : approach_angles())
    points.push_back(target.point + distance * frame.direction(angle));
  return points;
}

namespace {

bool hand_near_object(const robots::RobotModel& model, robots::CollisionWorld& world,
                      const robots::RobotData& data, double clearance) {
  if (!(clearance > 0)) return false;
  for (std::size_t l = 0; l < model.links.size(); ++l)
    if (model.links[l].hand && !model.links[l].shapes.empty() &&
        world.link_near_object(data, static_cast<int>(l), clearance))
      return true;
  return false;
}

}  // namespace

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
  // Full steps while they are free; the step that is not is tried at a half and a quarter (the
  // hand ends within a quarter step of where it would touch or come within the clearance).
  double done = 0.0, step = o.step;
  while (done + step <= o.distance + 1e-9) {
    const Eigen::Vector3d goal = start + (done + step) * direction;
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
    if (error.norm() > kLineTolerance || !model.within_limits(next) || world.in_collision(data) ||
        hand_near_object(model, world, data, o.clearance)) {
      if (step < 0.3 * o.step) break;
      step *= 0.5;
      continue;
    }
    poses.push_back(next);
    current = next;
    done += step;
  }
  return poses;
}

}  // namespace claspplan::tsrrt
