// Loops of the object (closed polylines of K_d), their ranking (which can a hand pass through?),
// and clasp targets G = {(p_i, p'_i)} (paper Sec. IV-A).
//
// Ranking, per loop (the hole's plane is the loop's least-squares plane, its centre the point of
// the loop's planar polygon farthest from every cloud point), in this order:
//  - hole width = 2 x that largest clearance (the widest ball that fits in the hole);
//    < min_hole -> "too narrow".
//  - seen through (only with cameras: depth input, or meshes sampled from --view positions): the
//    hole's interior is projected into each camera; where a camera measured a surface in front of
//    it, the hole was not seen. If most of the hole was never seen through -> "occlusion shadow"
//    (a gap in a single view behind a nearer part, or a loop around material facing the camera).
//  - open passage: a probe of radius 0.45 min_hole goes from the hole's centre along a line for
//    max(2 x width, 0.1 m) each way: the normal, or (with cameras) a line tilted 15 or 30 degrees
//    from it that runs through space some camera saw. If cloud points fall inside the probe along
//    every line, or at either end of each free line the points within 1.5 hole radii surround it
//    (no angular gap over 90 degrees), the loop runs around material (a tube's wall), not around
//    a hole -> "loop around a tube wall".
//  - seen through into known-free space (with a sensed map, sensed_space.hpp): along the line that
//    passed, a finger-wide probe out to twice the hole's width (4-10 cm) on both sides must read
//    80% known free; else "enclosed" (measured surface beyond the hole: a container's mouth, a
//    bowl's rim) or "never seen through" (unknown beyond it: a neck, a slit, a shadow between
//    objects), with a camera position from which the hole would be seen through (a next best
//    view). Without a sensor origin (a cloud with neither viewpoint nor pose) -> "no sensor
//    origin": such data cannot tell a hole from an unseen gap.
//  - through, not into a cavity (with a known supporting plane): followed downwards, the passage
//    must not meet the support within max(5 cm, two finger thicknesses) -> "blocked by the
//    support" (a hole lying on the table), nor meet it, inside the object's bounds, after running
//    between walls on every side -> "opening into a cavity" (a container's mouth, its inside
//    bottom unseen or removed with the table).
//  - hand fit (only when a hand's sizes are given): the hole must be wider than the fingers
//    (hole width >= finger thickness + 1.3 cm, checked first) -> else "too narrow for this hand";
//    the bar (the material the loop runs along, measured across the loop at 48 places, with room
//    for the closed fingers around it: no material there, and at most a quarter of it unseen by
//    every camera, as a handle's back is) must fit inside the closed hand with 1 cm to spare
//    (widest_bar()) at three places at least -> else "bar too thick for this hand".
//  - otherwise claspable.
// Order: claspable loops first, the best fit for the hand first (widest hole without a hand); then
// the others, shortest first.
#pragma once

#include <algorithm>
#include <optional>
#include <string>
#include <vector>

#include "core/clasp_target.hpp"
#include "core/mesh.hpp"
#include "perception/camera.hpp"
#include "perception/sensed_space.hpp"

namespace claspplan::perception {

/// Why a loop is, or is not, claspable (Loop::verdict; verdict_name() gives the word that
/// result files and reasons use).
enum class LoopVerdict {
  kUnranked,          ///< not ranked yet
  kClaspable,         ///< a seen-through hole the hand's fingers pass, around a bar it encloses
  kTooNarrow,         ///< the hole is narrower than min_hole
  kHandTooLarge,      ///< the hole is narrower than this hand's fingers need
  kOcclusionShadow,   ///< never seen through: a gap behind a nearer part, or sparse data
  kTubeWall,          ///< material inside the loop: it runs around a tube's wall
  kEnclosed,          ///< the hole leads into occupied space (a container's mouth or neck)
  kUnseenFarSide,     ///< the space where the fingertips come out was never seen
  kNoSensorOrigin,    ///< a cloud without a sensor origin: a hole cannot be told from a gap
  kBlockedBySupport,  ///< the table fills the hole
  kCavity,            ///< the loop bounds a cavity's rim, not a through-hole
  kBarTooThick,       ///< the bar is thicker than the closed hand's aperture
  kDegenerate,        ///< too few points or no extent
  kNoRoom,            ///< the planner found no room for the closed hand at any clasp target
};
/// The verdict as one word: "claspable", "too_narrow", "hand_too_large", ...
const char* verdict_name(LoopVerdict verdict);

struct Loop {
  std::vector<Eigen::Vector3d> points;  ///< closed polyline; the last point joins the first
  std::vector<int> vertices;            ///< indices into the object's cloud / K_d
  double length = 0.0;                  ///< metres
  int rank = 0;                         ///< 1 = best
  bool claspable = false;
  std::string reason;  ///< one line: the verdict and its measure
  LoopVerdict verdict = LoopVerdict::kUnranked;
  double hole_width = 0.0;  ///< metres (0 if not measured)
  /// Bar thickness across the loop at kBarSamples equally spaced places (arc length, from the
  /// first point): the diameter of the material's cross-section there; +inf where the material
  /// reaches farther than the measuring range (a wall or a body, not a bar). Empty if not measured.
  std::vector<double> bar_profile;
  double bar_thickness = 0.0;  ///< the thinnest of bar_profile (m)
  /// How well the hand fits (with a hand): the smaller relative slack of hole and bar; higher is
  /// better. 0 without a hand.
  double fit = 0.0;
  Eigen::Vector3d centre = Eigen::Vector3d::Zero();   ///< hole centre (largest clearance)
  Eigen::Vector3d normal = Eigen::Vector3d::UnitZ();  ///< of the loop's plane
};

constexpr int kBarSamples = 48;
/// A finger passes a hole this much wider than itself (m): 5 mm on each side, for the hole's
/// width as measured (from 2,000 points with 1 mm depth noise it moves by a few millimetres) and
/// for the controller's aim. With 5 mm in all, hands planned at holes 6-7 mm wider than their
/// fingers and failed (real suite, docs/real-objects.md).
constexpr double kFingerClearance = 0.010;
/// The hole width is measured in the loop's plane, where it reads wider than the passage's
/// narrowest place: by 3-5 mm at a pitcher's, a teapot's and a mug's handle (against their
/// meshes' cross-sections). So the width test asks for this much more; the passage probe and the
/// stable-loop scale, which look at the passage itself, do not. With 1 cm in all, the iCub
/// planned at a mug handle measured 2.5 cm wide (2.2 cm in the mesh, 1.4 cm fingers) and failed
/// at every seed.
constexpr double kHoleWidthExcess = 0.003;

/// The thickest bar a hand clasps: its closed aperture less kFingerClearance, the same room as the
/// fingers need in a hole (0 without a hand). A bar as thick as the aperture is touched all round
/// when the fingers reach the goal, and they close no further: the iCub (5.3 cm) reached a wheel
/// valve's 4.5-4.7 cm rim at VLk 0.72-0.75 but its closed fingers linked the loop by 0.09-0.15
/// only, and the valve got free at every seed; the widest bar verified on the paper's objects is
/// 59% of the hand's aperture (2 cm to spare). This decides whether a loop is worth trying; clasp
/// targets still cover every part whose bar is inside the aperture itself (clasp_targets'
/// max_bar), where the clasp check decides.
inline double widest_bar(double closed_aperture) {
  return closed_aperture > 0 ? std::max(0.0, closed_aperture - kFingerClearance) : 0.0;
}

/// The narrowest hole a hand's fingers are sent through: their thickness, kFingerClearance and
/// kHoleWidthExcess (the width test of a loop ranked for that hand).
inline double narrowest_hole(double finger_thickness) {
  return finger_thickness + kFingerClearance + kHoleWidthExcess;
}

struct RankingOptions {
  double min_hole = 0.03;  ///< metres: a hole narrower than this cannot take a finger
  /// The supporting surface (n.p + c = 0, n up), when one was found: a passage must not end on it.
  std::optional<Eigen::Vector4d> support_plane;
  /// Linking distance of the cloud's surface when measuring bars (m); 0: from the loop's edges.
  double link_distance = 0.0;
  /// The hand to rank for (robots::HandSize); 0 = no hand: min_hole and no bar test.
  double finger_thickness = 0.0;
  double closed_aperture = 0.0;
  /// The sensed map of the object's region (sensed_space.hpp), when its inputs had a sensor
  /// origin: a passage must open into known-free space on both sides of the hole.
  const SensedSpace* sensed = nullptr;
  /// Some input had no sensor origin (a cloud without a viewpoint or pose) and nothing else saw the
  /// space: no hole can be told from an unseen gap, so no loop is claspable.
  bool sensor_origin_missing = false;
};

/// Orients the loop (counter-clockwise about the normal with a positive z, else y, else x
/// component), measures it and sets claspable/reason; `views` may be empty (no occlusion test).
void assess_loop(Loop& loop, const PointCloud& cloud, const std::vector<DepthView>& views,
                 const RankingOptions& options);

/// assess_loop() for each loop, then sorts (order above) and numbers the ranks from 1.
void rank_loops(std::vector<Loop>& loops, const PointCloud& cloud,
                const std::vector<DepthView>& views, const RankingOptions& options);

/// `k` points equally spaced by arc length along the closed polyline, starting at its first point
/// and following its order; each tangent is the unit chord between the points half a target
/// spacing before and after. Throws std::invalid_argument for k < 1 or a degenerate loop.
std::vector<ClaspTarget> clasp_targets(const std::vector<Eigen::Vector3d>& loop, int k);

/// `k` targets equally spaced by arc length over the parts of the loop whose bar is at most
/// `max_bar` thick (loop.bar_profile); the whole loop when max_bar <= 0, the profile is empty, or
/// no part fits.
std::vector<ClaspTarget> clasp_targets(const Loop& loop, int k, double max_bar);

/// Length of a closed polyline.
double closed_length(const std::vector<Eigen::Vector3d>& loop);

}  // namespace claspplan::perception
