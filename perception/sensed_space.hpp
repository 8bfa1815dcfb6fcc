// What the sensors saw of the space around the object: each voxel of the object's region is free
// (a camera ray passed through all of it before meeting a surface), occupied (a measured surface
// lies in it) or unknown (no ray reached it: behind a surface, in a shadow, outside every view).
//
// Why: a depth image or a cloud holds surfaces, not space. A hole that no camera saw through, the
// back wall behind a mug's rim or a gap between two boxes look the same in the points as a handle
// does; only the rays that were cast tell them apart. The planner moves the robot near the object
// through known-free space only, and a loop is claspable only when its hole opens into known-free
// space on both sides (loops.hpp).
//
// The model is built by casting every camera's rays, read backwards: a voxel's centre is projected
// into each depth image (a pinhole camera, camera.hpp), and the pixels whose rays cross the voxel
// say whether they passed it (each depth lies beyond where its ray leaves the voxel's cube), ended
// in it (the centre's depth within the voxel), or ended before it. This is exact for the pixel
// grid, costs one projection per voxel and view (no ray traversal; a voxel whose footprint
// rectangle all reads beyond its far corner needs no ray of its own), and gives the same answer
// on any number of threads. Pixels without a reading (0: out of range, absorbed, shadowed by the
// projector) say nothing: what lies along them is unknown. Only in a rendering of a complete
// synthetic scene (CameraModel::no_reading_is_free) did such a ray see nothing up to any range.
//
// The rule for unknown space:
//  - inside the object's region (its points' bounds grown by `margin`): unknown counts as
//    occupied for the robot (blocked_voxels()): nothing that was not seen is assumed empty;
//  - outside it: unknown counts as free, like every part of the workspace that the scenario does
//    not declare (environment boxes). Cameras see the object, not the room: the arm's way from its
//    start is the user's to keep clear, as with any planner given a static scene.
// Inputs without a sensor origin (a cloud with no viewpoint, a mesh) build no model: the space is
// then unknown, and loops cannot be seen through (loops.hpp says so in their reasons).
#pragma once

#include <array>
#include <cstdint>
#include <memory>
#include <optional>
#include <vector>

#include <Eigen/Core>
#include <Eigen/Geometry>

#include "perception/camera.hpp"

namespace claspplan::perception {

enum class Sensed : std::uint8_t { kUnknown = 0, kFree = 1, kOccupied = 2 };

struct SensedSpaceOptions {
  double resolution = 0.005;  ///< voxel edge (m)
  /// The object's region: the object points' bounds grown by this (m): the hand's reach around a
  /// bar it clasps (fingers 5-8 cm long) fits in it.
  double margin = 0.08;
  /// A depth within this of a voxel's centre along the ray ends in it (m), at least half a voxel's
  /// diagonal: sensor noise (1-3 mm for a Kinect at 1 m) on top of the voxel's own depth.
  double surface_tolerance = 0.004;
  /// Voxels in the region at most this many (the grid is coarsened to fit): bounds the memory and
  /// the time for very large regions.
  long max_voxels = 4'000'000;
  /// Near the loop the robot clasps, the planner's map is cast again on a finer grid (edge at
  /// least this, m: a third of 5 mm; SensedSpace::refined()), over the loop's bounds grown by
  /// `loop_margin` (m), where the fingers pass the hole and curl around the bar. At `resolution`
  /// alone a voxel that a surface or a shadow only partly fills is not free, so every measured
  /// edge of a hole grows by up to a voxel: a 3 cm handle keeps about 2 cm of known-free room,
  /// too little for a 1.4 cm finger to pass and curl. 0: no finer grid. The finer grid holds at
  /// most `loop_max_voxels` (coarser if need be).
  double loop_resolution = 0.0016;
  double loop_margin = 0.03;
  long loop_max_voxels = 500'000;
};

/// The sensed map of one object's region. Model (constant after construction, shared read-only).
class SensedSpace {
 public:
  SensedSpace() = default;  ///< no sensor: every point unknown, no region
  /// The views' rays through `region` (world frame; grown by nothing: pass the object's bounds
  /// grown by options.margin, see object_region()), cast when first needed. Throws
  /// std::invalid_argument for an empty or non-finite region, a non-positive resolution, or an
  /// invalid camera.
  SensedSpace(const std::vector<DepthView>& views, const Eigen::AlignedBox3d& region,
              const SensedSpaceOptions& options = {});

  /// The same views cast over `box` (clipped to this region and snapped outwards to its voxels,
  /// so that each voxel of this grid lies wholly inside or outside it) on a finer grid: the
  /// finest whose edge is at least `resolution`, divides this grid's edge at least in two and
  /// gives at most `max_voxels` voxels. Empty when there is none or the box misses the region.
  SensedSpace refined(const Eigen::AlignedBox3d& box, double resolution, long max_voxels) const;

  bool empty() const { return !casting_; }
  /// The voxel grid's box (the region, snapped outwards to multiples of the resolution).
  const Eigen::AlignedBox3d& region() const { return box_; }
  double resolution() const { return resolution_; }
  Eigen::Vector3i dims() const { return dims_; }

  /// The state of the voxel holding p; kUnknown outside the region (see free_for_robot()).
  Sensed at(const Eigen::Vector3d& p) const;
  /// What the robot may assume at p: inside the region, at(p); outside it, free (the rule above).
  bool free_for_robot(const Eigen::Vector3d& p) const;
  /// Voxels per state: unknown, free, occupied.
  std::array<long, 3> counts() const;

  /// The centres of the voxels the robot must not enter: every unknown voxel of the region, and
  /// occupied voxels at or below `support` (n.p + c <= margin, n up: the table the object stands
  /// on, whose surface the object's own mesh leaves out). Measured surfaces above it are modelled
  /// by the depth surface mesh (depth_surface.hpp) and are not repeated here; the measurements
  /// that mesh leaves out (a rod too thin for its grid) are not here either: a planner adds them.
  std::vector<Eigen::Vector3d> blocked_voxels(
      const std::optional<Eigen::Vector4d>& support = std::nullopt, double margin = 0.005) const;

  /// The centres of the voxels holding `points`, each once, in grid order (points outside the
  /// region are skipped).
  std::vector<Eigen::Vector3d> voxels_holding(const std::vector<Eigen::Vector3d>& points) const;

  /// Voxel centre of grid index (i, j, k).
  Eigen::Vector3d centre(int i, int j, int k) const {
    return box_.min() + resolution_ * Eigen::Vector3d(i + 0.5, j + 0.5, k + 0.5);
  }
  /// The state of voxel (i, j, k).
  Sensed cell(int i, int j, int k) const;

 private:
  struct Casting;  // the views, and the grid once cast
  // The whole grid, cast on first need (counts(), blocked_voxels()), once, on all cores; point
  // queries before that classify their voxel from the views directly, with the same rule.
  const std::vector<std::uint8_t>& cells() const;
  /// The grid index of the voxel holding p (p inside the region; clamped at its far faces).
  Eigen::Vector3i voxel_of(const Eigen::Vector3d& p) const;

  Eigen::AlignedBox3d box_;
  double resolution_ = 0.0;
  double tolerance_ = 0.0;
  Eigen::Vector3i dims_ = Eigen::Vector3i::Zero();
  std::shared_ptr<Casting> casting_;  // null: no sensor (default-constructed)
};

/// The state at p of a map with a finer one over part of it (SensedSpace::refined(); null:
/// none): the finer map's inside its region, the map's elsewhere.
Sensed sensed_at(const SensedSpace& space, const SensedSpace* finer, const Eigen::Vector3d& p);

/// The object's region: `bounds` grown by `margin` on every side.
Eigen::AlignedBox3d object_region(const Eigen::AlignedBox3d& bounds, double margin);

}  // namespace claspplan::perception
