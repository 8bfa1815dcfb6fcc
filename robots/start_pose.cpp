#include "robots/start_pose.hpp"

#include <algorithm>
#include <cmath>
#include <random>

#include <Eigen/Cholesky>

#include "core/random_draws.hpp"
#include "robots/collision_world.hpp"
#include "robots/kinematics.hpp"

namespace claspplan::robots {
namespace {

constexpr int kIterations = 300;
constexpr double kDamping = 0.05;     // λ of the damped least squares
constexpr double kMaxStep = 0.2;      // rad: the longest joint move of one iteration
constexpr double kAngleWeight = 0.3;  // m per unit of v_fwd's error: 30 cm of lever

struct Target {
  Eigen::Vector3d position;
  Eigen::Vector3d down{0, 0, -1};
};

// Damped least squares on the arm's joints toward the target; true when it converges.
bool solve(const RobotModel& model, const Target& target, const StartPoseOptions& o,
           Eigen::VectorXd& q, RobotData& data, StartPose& out) {
  const int n = model.arm_dof;
  const Eigen::VectorXd lower = model.lower(), upper = model.upper();
  for (int it = 0; it < kIterations; ++it) {
    forward_kinematics(model, q, data);
    const Eigen::Vector3d dp = target.position - point_position(data, model.tcp);
    const Eigen::Vector3d v = vector_direction(data, model.v_fwd);
    out.position_error = dp.norm();
    out.angle_error = std::acos(std::clamp(v.dot(target.down), -1.0, 1.0));
    if (out.position_error <= o.position_tolerance && out.angle_error <= o.angle_tolerance)
      return true;
    Eigen::Matrix<double, 6, Eigen::Dynamic> J(6, n);
    J.topRows<3>() = point_jacobian(model, data, model.tcp.link, model.tcp.point).leftCols(n);
    J.bottomRows<3>() = kAngleWeight * vector_jacobian(model, data, model.v_fwd).leftCols(n);
    Eigen::Matrix<double, 6, 1> e;
    e << dp, kAngleWeight * (target.down - v);
    const Eigen::Matrix<double, 6, 6> A =
        J * J.transpose() + kDamping * kDamping * Eigen::Matrix<double, 6, 6>::Identity();
    Eigen::VectorXd dq = J.transpose() * A.ldlt().solve(e);
    const double longest = dq.cwiseAbs().maxCoeff();
    if (longest > kMaxStep) dq *= kMaxStep / longest;
    q.head(n) = (q.head(n) + dq).cwiseMax(lower.head(n)).cwiseMin(upper.head(n));
  }
  return false;
}

}  // namespace

std::optional<StartPose> find_start_above(const RobotModel& model, const Eigen::Vector3d& point,
                                          const StartPoseOptions& o) {
  const Target target{point + Eigen::Vector3d(0, 0, o.height)};
  CollisionWorld world(model);
  Eigen::Isometry3d floor = Eigen::Isometry3d::Identity();
  floor.translation() = Eigen::Vector3d(0, 0, -0.5);
  world.add_box(floor, Eigen::Vector3d(20, 20, 1));  // links rigid with the root are not checked
  RobotData data(model);
  std::mt19937_64 rng(o.seed);
  const Eigen::VectorXd lower = model.lower(), upper = model.upper();
  for (int restart = 0; restart < std::max(1, o.restarts); ++restart) {
    Eigen::VectorXd q = model.home;
    if (restart > 0)
      for (int j = 0; j < model.arm_dof; ++j)
        q[j] = lower[j] + uniform01(rng()) * (upper[j] - lower[j]);
    StartPose pose;
    if (!solve(model, target, o, q, data, pose) || world.in_collision(q)) continue;
    pose.q = q;
    pose.restart = restart;
    return pose;
  }
  return std::nullopt;
}

}  // namespace claspplan::robots
