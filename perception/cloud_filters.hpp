// Cloud clean-up and down-sampling: workspace crop, supporting-plane removal (PCL RANSAC),
// statistical outlier removal (PCL), seeded thinning and farthest-point down-sampling.
#pragma once

#include <cstdint>
#include <limits>
#include <optional>

#include <Eigen/Geometry>

#include "core/mesh.hpp"

namespace claspplan::perception {

/// Keeps the points inside the box (inclusive). An empty box (the default-constructed
/// Eigen::AlignedBox3d) means "no crop".
PointCloud crop_to_box(const PointCloud& cloud, const Eigen::AlignedBox3d& box);

struct PlaneRemovalOptions {
  double distance = 0.006;       ///< RANSAC inlier distance, metres
  double min_fraction = 0.10;    ///< the plane must hold at least this fraction of the points
  double max_tilt = 0.5;         ///< radians between the plane normal and world +z
  double above_fraction = 0.90;  ///< of the non-plane points that must lie above the plane
  int ransac_sample = 20000;     ///< RANSAC runs on a seeded subset of at most this many points
  std::uint64_t seed = 1;
};

struct PlaneRemovalResult {
  PointCloud kept;
  bool removed = false;               ///< a supporting plane was found and removed
  Eigen::Vector4d plane{0, 0, 1, 0};  ///< n·p + c = 0, n towards the object (+z side)
  int plane_points = 0;               ///< points removed as on (or below) the plane
};

/// Heights above a supporting plane n·p + c = 0 (n up, of any length), in metres.
struct SupportHeight {
  explicit SupportHeight(const std::optional<Eigen::Vector4d>& plane);
  /// Signed height of p; +infinity without a plane (nothing is below it then).
  double operator()(const Eigen::Vector3d& p) const {
    return known ? up.dot(p) + offset : std::numeric_limits<double>::infinity();
  }
  Eigen::Vector3d up = Eigen::Vector3d::UnitZ();  ///< the plane's unit normal (+z without one)
  double offset = 0.0;
  bool known = false;
};

/// Removes the supporting surface (a table or floor): the largest RANSAC plane (PCL
/// SACSegmentation), but only if it is near-horizontal, large, and has the rest of the points above
/// it, so that a box's top or side face is never taken for the table. Points below the plane go
/// too.
PlaneRemovalResult remove_supporting_plane(const PointCloud& cloud,
                                           const PlaneRemovalOptions& options = {});

/// Statistical outlier removal (the statistics of PCL's StatisticalOutlierRemoval): drops points
/// whose mean distance to their k neighbours exceeds the mean of those by more than `stddev_mult`
/// sample standard deviations.
PointCloud remove_statistical_outliers(const PointCloud& cloud, int k = 16,
                                       double stddev_mult = 2.0);

/// A seeded uniform random subset of at most `count` points (order preserved).
PointCloud random_subset(const PointCloud& cloud, int count, std::uint64_t seed);

/// A spatially even subset of at most `count` points: one point (the first in input order) per
/// occupied cell of a grid whose cell size is adjusted until about 1.5 `count` cells are occupied,
/// then a seeded random subset of those. Unlike random_subset(), parts seen by few pixels (a thin
/// handle at a grazing angle, far from the camera) keep their share of points. Order preserved.
PointCloud even_subset(const PointCloud& cloud, int count, std::uint64_t seed);

/// Farthest-point down-sampling to `count` points (all points if there are fewer): starts at a
/// seeded random point, then repeatedly takes the point farthest from those taken. Spacing is
/// nearly uniform, which keeps K_d free of sampling gaps. O(M log M) with a k-d tree (a radius
/// update per pick). Returns indices into `cloud`, in pick order.
std::vector<int> farthest_point_indices(const PointCloud& cloud, int count, std::uint64_t seed);
PointCloud farthest_point_sample(const PointCloud& cloud, int count, std::uint64_t seed);

/// Farthest-point sampling of several objects at once (`labels`: one per point, >= 0; points
/// labelled -1 are sampled but do not count): picks until the object with the most picks holds
/// `count`, or `limit` points are picked, or only duplicates remain. Each object then keeps the
/// spacing that `count` points give the largest, however many other objects share the crop.
std::vector<int> farthest_point_indices(const PointCloud& cloud, int count, std::uint64_t seed,
                                        const std::vector<int>& labels, int limit);
PointCloud farthest_point_sample(const PointCloud& cloud, int count, std::uint64_t seed,
                                 const std::vector<int>& labels, int limit);

/// The objects of a cloud: PCL Euclidean clusters of points less than `gap` apart, those of at
/// least `min_share` of the points labelled 0, 1, ... (largest first), the rest -1.
std::vector<int> object_labels(const PointCloud& cloud, double gap, double min_share);

/// Mean distance from each point to its nearest other point. Throws for fewer than 2 points.
double mean_spacing(const PointCloud& cloud);

/// The points sorted along a Morton (Z-order) curve on a 2^21 grid over their bounds: neighbours
/// in space become neighbours in memory, which speeds up the graph searches on K_d.
PointCloud spatial_order(const PointCloud& cloud);

/// Removes exact duplicate points (keeps first occurrences, order preserved).
PointCloud unique_points(const PointCloud& cloud);

}  // namespace claspplan::perception
