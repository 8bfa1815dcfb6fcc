// The sizes of a hand that decide which loops it can clasp, computed from the robot model (never
// typed in): how wide a hole its fingers need, and how thick a bar its closed hand can enclose.
#pragma once

#include <vector>

#include <Eigen/Core>

#include "robots/robot_model.hpp"

namespace claspplan::robots {

struct HandSize {
  /// The widest cross-section of any finger link (the diameter of the circle around it): a hole
  /// must be at least this wide for the fingers to pass through it (m).
  double finger_thickness = 0.0;
  int thickest_link = -1;  ///< the finger link whose shape gives finger_thickness
  /// The diameter of the largest bar the hand encloses when it is closed just enough to reach its
  /// virtual-linking goal: the largest circle inside every finger curve closed by its cord, less
  /// the fingers' own thickness (m). A thicker bar cannot be clasped.
  double closed_aperture = 0.0;
  /// The hand joints at that closure (the open pre-shape moved along the closing directions).
  Eigen::VectorXd closed_q;
  /// The curves' mean cord ratio there: below vlink_goal when the joints' limits stopped the
  /// closing first (the goal cannot be reached).
  double closed_ratio = 0.0;
  /// Where a bar sits in the closed hand: the mean of those circles' centres, in the world frame
  /// with the arm at its home pose (m).
  Eigen::Vector3d closed_centre = Eigen::Vector3d::Zero();
};

/// The diameter of the circle around a shape's cross-section, across its longest axis (a mesh:
/// its box's, in the mesh's frame): how wide a hole the link needs.
double cross_section(const CollisionShape& s);

/// Computes the sizes above. Finger closing follows each hand joint's `closing` direction in
/// small steps from the open pre-shape, without an object, until every curve's cord ratio
/// 1 - cord / closed length (the factor of paper eq. 2) reaches the hand's `vlink_goal`, or the
/// joints reach their limits.
HandSize hand_size(const RobotModel& model);

/// hand_size(model) with vlink_goal = goals[i], for each of the goals (ascending), from one
/// closing sweep. Throws std::invalid_argument when the goals are not in ascending order.
std::vector<HandSize> hand_sizes(const RobotModel& model, const std::vector<double>& goals);

}  // namespace claspplan::robots
