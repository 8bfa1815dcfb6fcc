// A start configuration for any robot: the hand open, its tcp above a given point and its approach
// direction (v_fwd) pointing straight down, free of self-collision and above the floor. What a
// scenario's `start` needs before planning, without a grid search over joint angles by hand.
#pragma once

#include <cstdint>
#include <optional>

#include <Eigen/Core>

#include "robots/robot_model.hpp"

namespace claspplan::robots {

struct StartPoseOptions {
  double height = 0.25;               ///< m: the tcp's target above the point
  double position_tolerance = 0.005;  ///< m from that target
  double angle_tolerance = 0.05;      ///< rad between v_fwd and straight down (−z)
  int restarts = 200;                 ///< from home first, then random arm configurations
  std::uint64_t seed = 1;
};

struct StartPose {
  Eigen::VectorXd q;  ///< all joints: the arm's solution, the hand's open pre-shape
  double position_error = 0.0, angle_error = 0.0;
  int restart = 0;  ///< which start it converged from (0: home)
};

/// Damped least squares on the arm joints (within their limits) from home, then from seeded random
/// configurations, until one converges to the tcp target with v_fwd down and the configuration
/// has no self-collision and no moving link below z = 0 (the floor the robot stands on). The same
/// options give the same answer. Nothing when every restart fails: the point is out of reach, or
/// every way to reach it collides.
std::optional<StartPose> find_start_above(const RobotModel& model, const Eigen::Vector3d& point,
                                          const StartPoseOptions& options = {});

}  // namespace claspplan::robots
