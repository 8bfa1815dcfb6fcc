// Closing the fingers until contact (paper Sec. V): each finger curls around what it meets.
#pragma once

#include <vector>

#include <Eigen/Core>

#include "robots/collision_world.hpp"
#include "robots/robot_model.hpp"

namespace claspplan::tsrrt {

struct FingerClosingOptions {
  double step = 0.01;  ///< rad per closing step of a finger's joints
  /// A link stops where it comes within this of the object (m); the final pose is free.
  double clearance = 0.002;
  int max_steps = 400;
};

/// Closes each finger (the thumb included) along its joints' closing directions until its links,
/// or any other link its closing joints move through mimic joints, are within the clearance of the
/// object or its joints reach their limits; every step stays collision-free. A link that comes
/// within the clearance (or touches the robot) stops the joints that move it, and the joints beyond
/// it go on closing: the finger curls around what it meets. Returns the closed configuration (the
/// path's last pose). `unseen_stops` (optional) gets the hit each time a link stops against unseen
/// space: where a camera would have to look for the fingers to close on (world.contact_point()
/// makes a hit a point, only when one is needed).
Eigen::VectorXd close_fingers(const robots::RobotModel& model, robots::CollisionWorld& world,
                              const Eigen::VectorXd& q, const FingerClosingOptions& options,
                              std::vector<robots::EnvironmentHit>* unseen_stops = nullptr);

}  // namespace claspplan::tsrrt
