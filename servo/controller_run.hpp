// Controller-only clasping (issue: "the controller must work on its own"): TS-CONTROL iterated
// from a start configuration toward the clasp target nearest to the hand, each step checked for
// collision, until the hand's virtual-linking goal is reached or progress stops.
#pragma once

#include <string>
#include <vector>

#include <Eigen/Core>

#include "robots/collision_world.hpp"
#include "servo/clasp_controller.hpp"

namespace claspplan::servo {

struct ControllerRunOptions {
  int max_steps = 2000;
  /// Progress stops when, for this many steps, the hand got no closer to the target, the
  /// alignment error did not shrink and the linking did not grow by the amounts below.
  int stall_steps = 60;
  double stall_position = 5e-4;  ///< metres
  double stall_alignment = 1e-3;
  double stall_linking = 2e-3;
  double collision_resolution = 0.01;  ///< rad between collision checks along each step
};

struct ControllerRun {
  bool success = false;
  std::string reason;  ///< why it stopped
  bool collided = false;
  robots::CollisionReport collision;       ///< when collided
  robots::EnvironmentHit environment_hit;  ///< when collided with the environment
  int target = -1;                         ///< the clasp target driven to
  std::vector<Eigen::VectorXd> waypoints;  ///< start to final configuration
  TaskState final_state;
  std::vector<double> linking_history;  ///< Π_vlink after every step (the start included)
};

/// Success once Π_vlink (eq. 4) reaches goal_linking (the hand's: RobotModel::vlink_goal).
ControllerRun run_controller(ClaspController& controller, robots::CollisionWorld& world,
                             const Eigen::VectorXd& q_start, double goal_linking,
                             const ControllerRunOptions& options);

}  // namespace claspplan::servo
