// Loops of the object (closed polylines of K_d), their ranking (which can a hand pass through?),
// and clasp targets G = {(p_i, p'_i)} (paper Sec. IV-A).
//
// Ranking, per loop (the hole's plane is the loop's least-squares plane, its centre the point of
// the loop's planar polygon farthest from every cloud point):
//  - hole width = 2 x that largest clearance (the widest ball that fits in the hole);
//    < min_hole -> "too narrow".
//  - seen through (only with cameras: depth input, or meshes sampled from --view positions): the
//    hole's interior is projected into each camera; where a camera measured a surface in front of
//    it, the hole was not seen. If most of the hole was never seen through -> "occlusion shadow"
//    (a gap in a single view behind a nearer part, or a loop around material facing the camera).
//  - open passage: a probe of radius 0.45 min_hole goes from the hole's centre along both normal
//    directions for max(2 x width, 0.1 m). If cloud points fall inside it, or at either end the
//    points within 1.5 hole radii surround the axis (no angular gap over 90 degrees), the loop runs
//    around material (a tube's wall), not around a hole -> "loop around a tube wall".
//  - otherwise claspable.
// Order: claspable loops first, widest hole first; then the others, shortest first.
#pragma once

#include <string>
#include <vector>

#include "perception/camera.hpp"
#include "perception/mesh.hpp"

namespace claspplan::perception {

struct Loop {
  std::vector<Eigen::Vector3d> points;  ///< closed polyline; the last point joins the first
  std::vector<int> vertices;            ///< indices into the object's cloud / K_d
  double length = 0.0;                  ///< metres
  int rank = 0;                         ///< 1 = best
  bool claspable = false;
  std::string reason;                                 ///< one line: the verdict and its measure
  double hole_width = 0.0;                            ///< metres (0 if not measured)
  Eigen::Vector3d centre = Eigen::Vector3d::Zero();   ///< hole centre (largest clearance)
  Eigen::Vector3d normal = Eigen::Vector3d::UnitZ();  ///< of the loop's plane
};

struct RankingOptions {
  double min_hole = 0.03;  ///< metres: a hole narrower than this cannot take a finger
};

/// Orients the loop (counter-clockwise about the normal with a positive z, else y, else x
/// component), measures it and sets claspable/reason; `views` may be empty (no occlusion test).
void assess_loop(Loop& loop, const PointCloud& cloud, const std::vector<DepthView>& views,
                 const RankingOptions& options);

/// assess_loop() for each loop, then sorts (order above) and numbers the ranks from 1.
void rank_loops(std::vector<Loop>& loops, const PointCloud& cloud,
                const std::vector<DepthView>& views, const RankingOptions& options);

/// A clasp target: a point on the loop and the loop's unit tangent there.
struct ClaspTarget {
  Eigen::Vector3d p;
  Eigen::Vector3d tangent;
};

/// `k` points equally spaced by arc length along the closed polyline, starting at its first point
/// and following its order; each tangent is the unit chord between the points half a target
/// spacing before and after. Throws std::invalid_argument for k < 1 or a degenerate loop.
std::vector<ClaspTarget> clasp_targets(const std::vector<Eigen::Vector3d>& loop, int k);

/// Length of a closed polyline.
double closed_length(const std::vector<Eigen::Vector3d>& loop);

}  // namespace claspplan::perception
