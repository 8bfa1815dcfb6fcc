// The probes behind the loop ranking (loops.cpp): what the cameras and the sensed map say around
// a loop, the open-passage lines, a bar's cross-section and the camera that would see a hole
// through. Internal to perception.
#pragma once

#include <optional>
#include <vector>

#include <Eigen/Geometry>

#include "perception/camera.hpp"
#include "perception/loops.hpp"
#include "perception/point_index.hpp"
#include "perception/sensed_space.hpp"

namespace claspplan::perception {

enum class Seen { kUnknown, kFree, kBlocked };

/// What the cameras say about a point of the hole: seen through (a camera measured something
/// behind it), blocked (every camera that covers it measured a surface in front of it or on it),
/// or unknown (outside every image, or no reading).
Seen seen_from(const std::vector<DepthView>& views, const Eigen::Vector3d& q, double tol);

/// Material on every side of an axis at p (direction u): among the points within `radius` of p
/// and `half` of its cross-section plane (at least 3), no angular gap over 90 degrees.
bool surrounded(const PointIndex& index, const Eigen::Vector3d& p, const Eigen::Vector3d& u,
                double radius, double half);

/// A line of the open-passage probe: its unit direction and its tilt from the loop's normal.
struct ProbeLine {
  Eigen::Vector3d u;
  int tilt = 0;  // degrees
};

/// The loop's normal n, then (if `tilted`) lines 15 and 30 degrees from it at 8 azimuths each.
std::vector<ProbeLine> probe_lines(const Eigen::Vector3d& n, bool tilted);

/// Distance from p along the unit direction u to where the ray leaves the box (0 if outside).
double exit_distance(const Eigen::AlignedBox3d& box, const Eigen::Vector3d& p,
                     const Eigen::Vector3d& u);

/// The bar's cross-section at loop point p with tangent t: the cloud points in a slab across the
/// loop, grown from p over gaps shorter than `link`; its diameter. +inf when it reaches `cap` (a
/// wall or a body), or when the ring where closed fingers would lie around it (its radius plus
/// half a finger) meets material, space no camera saw (the bar may be deeper than it looked) or
/// the supporting surface.
double bar_at(const PointIndex& index, const std::vector<DepthView>& views,
              const std::optional<Eigen::Vector4d>& support, const Eigen::Vector3d& p,
              const Eigen::Vector3d& t, double link, double cap, double finger);

/// The loop's bar_profile (bar_at() at kBarSamples places) and bar_thickness (the third
/// thinnest place: one or two partial cross-sections read too thin).
void measure_bar(Loop& loop, const PointIndex& index, const std::vector<DepthView>& views,
                 const RankingOptions& o);

/// What the sensed map says of the space beyond a hole on one side (direction u): a spherical cap
/// of radius `length` (directions within 60 degrees of u) where the fingertips come out. Points
/// outside the map's region count as free (sensed_space.hpp's rule for space far from the object).
/// `under_support` of the points not free lie under the supporting surface: no camera sees there.
struct FarSide {
  int free = 0, unknown = 0, occupied = 0;
  int under_support = 0;
  double share_free() const {
    const int all = free + unknown + occupied;
    return all > 0 ? static_cast<double>(free) / all : 1.0;
  }
};

/// The map as the robot sees it: outside its region, free (far from the object).
Sensed robot_view(const SensedSpace& space, const Eigen::Vector3d& q);

FarSide far_side(const SensedSpace& space, const Eigen::Vector3d& centre, const Eigen::Vector3d& u,
                 double length, const std::optional<Eigen::Vector4d>& support);

/// A camera position from which the hole would be seen through: on its axis, 0.6 m out, on the
/// side whose space was seen (else the upper side), and above the support (a camera under the table
/// is no advice): a side whose position is not 5 cm above it is swapped for the other, and failing
/// both, the position is raised along the support's normal.
Eigen::Vector3d next_best_view(const Eigen::Vector3d& centre, const Eigen::Vector3d& u,
                               const FarSide& plus, const FarSide& minus,
                               const std::optional<Eigen::Vector4d>& support);

}  // namespace claspplan::perception
