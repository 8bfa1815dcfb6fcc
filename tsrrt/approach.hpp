// How the hand comes to a clasp target: the directions it approaches a loop point from (outside
// the loop, from both sides of its plane), and the open hand's straight advance to contact.
#pragma once

#include <vector>

#include <Eigen/Core>

#include "robots/collision_world.hpp"
#include "robots/robot_model.hpp"
#include "servo/clasp_controller.hpp"

namespace claspplan::tsrrt {

/// The frame clasp target `target` of `loop` is approached in: with c the loop's centroid, r the
/// unit component of (p − c) orthogonal to the tangent t (outward from the hole) and n = t × r.
struct ApproachFrame {
  Eigen::Vector3d r, n, t;
  /// The unit direction from the target toward the approach at angle θ, given as
  /// (cos θ, sin θ): cos θ r + sin θ n.
  Eigen::Vector3d direction(const Eigen::Vector2d& angle) const {
    return angle.x() * r + angle.y() * n;
  }
};
ApproachFrame approach_frame(const servo::Points& loop, const ClaspTarget& target);

/// The approach angles θ, each as (cos θ, sin θ): 0, +90°, −90°, +45°, −45°, in that order.
std::vector<Eigen::Vector2d> approach_angles();

/// Where to approach clasp target `target` of `loop` from: the points p + distance·direction(θ)
/// of its approach_frame() for θ in approach_angles(): from outside the loop and from both sides
/// of its plane, never from inside the hole.
std::vector<Eigen::Vector3d> clasp_approaches(const servo::Points& loop, const ClaspTarget& target,
                                              double distance);

struct ApproachOptions {
  double step = 0.004;     ///< m per step along the approach direction
  double distance = 0.05;  ///< the longest advance (m); 0: none
  /// The advance stops before any link of the hand comes nearer the object than this (m). The
  /// seen surface lies within the depth noise of the true one, so a hand advanced to contact may
  /// graze the real object; a clearance of twice the noise avoids that, at the cost of clasps
  /// that need the hand deep (an 8 mm wire ring). 0: to contact.
  double clearance = 0.0;
};

/// The open hand moved straight along its approach direction (v_fwd) by the arm alone, the tool's
/// orientation kept, until the next step (tried whole, then at a half and a quarter) would touch
/// anything (object, environment, itself), bring a hand link within `clearance` of the object,
/// leave the joint limits or lose the line, or `distance` is covered: the approach to contact
/// that precedes a grasp, so that the fingers close around the bar from deep rather than hook it
/// with their tips. Returns the poses after q, each collision-free (empty: no step was free).
std::vector<Eigen::VectorXd> approach_until_contact(const robots::RobotModel& model,
                                                    robots::CollisionWorld& world,
                                                    const Eigen::VectorXd& q,
                                                    const ApproachOptions& options);

}  // namespace claspplan::tsrrt
