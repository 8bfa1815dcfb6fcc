// The whole perception path of paper Sec. IV-A in one call: inputs (depth images with cameras,
// clouds, meshes) -> object points -> K_d -> shortest loops -> ranked loops -> clasp targets.
//
// Steps, in order:
//  1. Depth views (clouds with a sensor origin are views too: add_cloud): back-projection, world
//     transform, crop to the workspace box, supporting-plane removal (RANSAC), statistical outlier
//     removal (both PCL). All views are merged first; clouds without an origin join them there.
//     Meshes are sampled uniformly by area with 4 N points, over the whole surface or only where
//     visible from the --view positions. The views' sensed space (sensed_space.hpp) is set up
//     over the object's region, cast when the ranking or the planner asks.
//  2. Down-sampling to N points: a seeded random subset of at most 4 N points; depth points are
//     first thinned evenly over space to 3 N (a random pool of 16 N, one point per grid cell:
//     a thin handle seen by few pixels keeps its points), before the outlier filter, to bound its
//     cost. Then farthest-point sampling to N from a seeded start: nearly uniform spacing,
//     deterministic with the seed; the N points are then put in Morton order (locality).
//  3. d: given, or automatic_d() = 3.5 x the mean nearest-neighbour spacing of the N points.
//  4. K_d from the CGAL 3-D Delaunay triangulation.
//  5. Only stable loops: the shortest cycles of K_d whose classes stay independent and non-zero in
//     K_d' (d' = persistence x d, and at least 0.8 x the narrowest hole a finger passes: min_hole,
//     or the hand's fingers + 1 cm if less), exactly, over Z2. A loop that K_d' fills is a sampling
//     gap or a thin tube's wall, not a hole a hand can use; so more points (a smaller d) never mean
//     more loops. Holes a finger can pass survive.
//  6. Loops ranked (loops.hpp), for the hand if its sizes are given; k clasp targets on the best
//     loop if it is claspable, where its bar fits the hand.
//  7. No claspable loop, and the crop holds several objects (clusters 2 cm, or 4 spacings of the
//     points, apart, each with 10% of the points): steps 2-6 again with the farthest points taken
//     until the largest object holds N (at most 2 N in all). A second object spreads the N points
//     of step 2 over more surface, and the coarser d' then fills a handle's hole; this pass keeps
//     each object's spacing. Its model is kept when it has a claspable loop. Only then: one d
//     cannot serve both a handle beside a second object and a wire seen with gaps, which closes
//     only at the coarser d (examples/scenarios/conditions/README.md).
#pragma once

#include <cstdint>
#include <functional>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "core/input_error.hpp"
#include "core/mesh.hpp"
#include "perception/camera.hpp"
#include "perception/complex.hpp"
#include "perception/homology.hpp"
#include "perception/loops.hpp"
#include "perception/sensed_space.hpp"

namespace claspplan::perception {

struct PerceptionInputs {
  std::vector<DepthView> depth_views;  ///< depth images with their cameras (world frame)
  std::vector<PointCloud> clouds;      ///< point clouds, world frame
  std::vector<TriangleMesh> meshes;    ///< sampled on their surface
  /// Camera positions for meshes: if any, meshes are sampled only where visible from them (and
  /// the rendered views join the occlusion test of the ranking).
  std::vector<Eigen::Vector3d> view_positions;
};

/// A cloud file as sensor data (sensor_cloud.hpp).
struct CloudFile {
  std::string path;
  /// The cloud's frame in the world (for a cloud in its sensor's frame: the sensor's pose).
  Eigen::Isometry3d pose = Eigen::Isometry3d::Identity();
  /// The sensor's pose in the cloud's frame: replaces a PCD's VIEWPOINT, and is the only sensor
  /// origin a .ply or .xyz cloud can have.
  std::optional<Eigen::Isometry3d> viewpoint;
};

/// Adds a cloud file to the inputs as what its sensor saw: an organized PCD as its own depth view
/// (its camera fitted to its grid), a cloud with a sensor origin (`viewpoint`, or a PCD VIEWPOINT
/// other than the format's default identity, which writers put in whatever the sensor was) as a
/// synthetic depth view from that origin, so that the depth stages and the sensed space apply; a
/// cloud without an origin as plain points that still go through the crop, plane and outlier
/// stages (its loops cannot be seen through: loops.hpp). NaN points are skipped. Throws
/// InputError for a bad file or one in millimetres.
void add_cloud(PerceptionInputs& inputs, const CloudFile& file);

/// Reads inputs by extension: `.png` files pair, in order, with `cameras` (one camera file per
/// PNG); `.pcd .xyz` are clouds (add_cloud, in the world frame), `.obj .stl .off` meshes, `.ply`
/// either. Throws
/// InputError for a count mismatch or any bad file.
PerceptionInputs load_inputs(const std::vector<std::string>& paths,
                             const std::vector<std::string>& cameras,
                             const std::vector<Eigen::Vector3d>& view_positions = {});

/// The most points K_d is built on. Its Delaunay complex and shortest basis grow faster than
/// linearly (a torus cloud: 20,000 points 9 s, 50,000 63 s, 100,000 108 s), so more is refused
/// rather than left to run for hours; the input before down-sampling is not limited by this.
constexpr int kMaxPoints = 50000;

struct PerceptionOptions {
  int points = 2000;       ///< N (the paper uses 2000), at most kMaxPoints
  double d = 0.0;          ///< 0: automatic
  double d_factor = 3.5;   ///< automatic d = d_factor x mean spacing
  double min_hole = 0.03;  ///< metres, see loops.hpp
  int targets = 12;        ///< clasp targets on the best loop (the paper uses 9 to 24)
  std::uint64_t seed = 1;
  Eigen::AlignedBox3d workspace;  ///< crop box for depth points; empty = no crop
  bool remove_plane = true;       ///< supporting-plane removal for depth input
  int outlier_k = 10;             ///< statistical outlier removal (depth input); 0 = off
  double outlier_stddev = 2.0;
  /// Loops must persist to d' = max(persistence x d, 0.8 x narrowest hole); 0 keeps every loop.
  double persistence = 1.25;
  /// Step 7: a second pass that samples each object of the crop with N points.
  bool per_object_pass = true;
  /// The hand to rank loops for (robots::hand_size()); 0 = none. See RankingOptions.
  double finger_thickness = 0.0;
  double closed_aperture = 0.0;
  HomologyOptions homology;
  /// The sensed map of the object's region, cast from the depth views (sensed_space.hpp).
  SensedSpaceOptions sensed;
  /// Optional progress messages for long steps (the CLI prints them on stderr).
  std::function<void(const std::string&)> progress;
  /// Polled between the steps; true ends the call with claspplan::Stopped (core/stopped.hpp).
  std::function<bool()> stop;
};

/// Seconds per step; with a second pass (step 7), the steps of the model kept, and the total of
/// both.
struct PerceptionTimings {
  double preprocess = 0, downsample = 0, delaunay = 0, complex = 0, homology = 0, sensed = 0,
         ranking = 0, total = 0;  ///< seconds
};

/// The object representation (S, K_d, G) of paper Sec. IV-A, plus what it was made from.
struct ObjectModel {
  PointCloud cloud;                  ///< the N points used
  SimplicialComplex complex;         ///< K_d
  double d = 0.0;                    ///< the d used
  std::string d_rule;                ///< how d was chosen, one line
  double mean_spacing = 0.0;         ///< of the N points
  int beta1 = 0;                     ///< of K_d
  double persistence_d = 0.0;        ///< d' of the stability test (0: not tested)
  int unstable_loops = 0;            ///< beta1 minus the stable loops: K_d' fills them in
  std::vector<Loop> loops;           ///< the stable ones, ranked, best first
  std::vector<ClaspTarget> targets;  ///< on loops[0] if it is claspable, else empty
  std::vector<DepthView> views;      ///< cameras used by the occlusion test
  /// What the views saw of the object's region (free, occupied, unknown); null without views.
  std::shared_ptr<const SensedSpace> sensed;
  /// Some input had no sensor origin and no view saw the space (RankingOptions).
  bool sensor_origin_missing = false;
  int input_points = 0;  ///< points before down-sampling
  int plane_points_removed = 0;
  std::optional<Eigen::Vector4d> support_plane;  ///< the removed supporting plane, n up
  int outliers_removed = 0;
  int objects = 1;  ///< step 7: the objects sampled one by one (1: the first pass's model)
  PerceptionTimings timings;

  /// The best claspable loop, or nullptr.
  const Loop* best() const { return !loops.empty() && loops[0].claspable ? &loops[0] : nullptr; }
};

/// Runs the pipeline. Throws InputError for invalid inputs: no input, an empty cloud
/// after filtering (e.g. an all-zero depth image), fewer than 4 distinct points, points that do
/// not span 3-D, bad options. An object without loops is a valid result (beta1 = 0).
ObjectModel build_object_model(const PerceptionInputs& inputs, const PerceptionOptions& options);

/// The object points only (steps 1-2), for callers that want the cloud.
PointCloud object_points(const PerceptionInputs& inputs, const PerceptionOptions& options,
                         std::vector<DepthView>* views_out = nullptr);

}  // namespace claspplan::perception
