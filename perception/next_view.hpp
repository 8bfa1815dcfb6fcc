// A next best view for the space a hand needs: where to put one more camera so that the unknown
// space around a loop, which the planner may not enter (sensed_space.hpp), would be seen.
//
// Why: a hole can be seen through and still leave the hand no known-free way in: the gap between
// a handle and a second object, the shadow under a ring. The planner then runs into unseen space
// on every attempt, and the useful answer is not "no clasp" but where a camera would help. The
// loop ranking names a view for a hole that was never seen through (loops.hpp); this one is for
// the hand's way around a hole that was.
#pragma once

#include <functional>
#include <optional>
#include <string>
#include <vector>

#include <Eigen/Core>

#include "perception/sensed_space.hpp"

namespace claspplan::perception {

struct ViewSuggestion {
  Eigen::Vector3d position = Eigen::Vector3d::Zero();  ///< the camera (world frame, m)
  Eigen::Vector3d target = Eigen::Vector3d::Zero();    ///< what it looks at
  double visible = 0.0;  ///< of the unknown voxels below, how many its rays are expected to reach
  int unknown = 0;       ///< unknown voxels within the radius of the points (sampled, at most 600)
};

struct ViewOptions {
  double radius = 0.02;    ///< unknown space this near the points counts (m)
  double distance = 0.6;   ///< camera to target (m): a depth camera's working range
  double half_fov = 0.37;  ///< voxels within this angle of the optical axis count (rad; 21 deg)
  double above = 0.05;     ///< the camera at least this high above the support plane (m)
  /// A ray's chance to pass unknown space halves with every this much of it (m): a thin shadow
  /// is likely empty, a thick one may hide a solid (the unseen inside of a box).
  double unknown_half_depth = 0.015;
  /// No camera is named that is expected to see less than this share of the unknown voxels.
  double min_share = 0.05;
  /// Where a camera may stand (none: anywhere above the support): clear of the robot and of the
  /// environment, which perception does not know.
  std::function<bool(const Eigen::Vector3d&)> allowed;
};

/// The camera, among positions `distance` from the unknown voxels' centroid (elevations 0-90
/// degrees over the support plane, or world +z without one, every 15 degrees of azimuth), whose
/// straight rays are expected to reach most of the unknown voxels within `radius` of `points` (a
/// point inside the grid stands for its voxel's centre): a ray through an occupied voxel reaches
/// nothing, one through unknown space the less likely the more of it it crosses. Nothing when that
/// space has no unknown voxel or no position is expected to see `min_share` of it.
std::optional<ViewSuggestion> view_into_unknown(const SensedSpace& space,
                                                const std::vector<Eigen::Vector3d>& points,
                                                const std::optional<Eigen::Vector4d>& support,
                                                const ViewOptions& options = {});

/// "a camera {position: [x, y, z], target: [x, y, z]} (m) would see 72% of it": the share of
/// `unknown` it sees, the camera as a scenario's `object: cameras` entry.
std::string view_text(const ViewSuggestion& view);

}  // namespace claspplan::perception
