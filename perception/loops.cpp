#include "perception/loops.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>
#include <optional>
#include <stdexcept>

#include <Eigen/Eigenvalues>

#include "core/polygon.hpp"
#include "perception/point_index.hpp"
#include "perception/sensed_space.hpp"

namespace claspplan::perception {

namespace {

std::string metres(double v) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "%.3f m", v);
  return buf;
}

// A margin in reasons, from its constant: 0.013 -> "1.3 cm", 0.01 -> "1 cm".
std::string centimetres(double v) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "%g cm", std::round(1000.0 * v) / 10.0);
  return buf;
}

enum class Seen { kUnknown, kFree, kBlocked };

// What the cameras say about a point of the hole: seen through (a camera measured something
// behind it), blocked (every camera that covers it measured a surface in front of it or on it),
// or unknown (outside every image, or no reading).
Seen seen_from(const std::vector<DepthView>& views, const Eigen::Vector3d& q, double tol) {
  bool blocked = false;
  for (const auto& v : views) {
    const Eigen::Vector3d uvz = v.camera.project(q);
    if (uvz.z() <= 0) continue;
    const int u = static_cast<int>(std::lround(uvz.x())),
              r = static_cast<int>(std::lround(uvz.y()));
    if (u < 0 || r < 0 || u >= v.image.width || r >= v.image.height) continue;
    const double z = v.image.at(u, r);
    if (z <= 0) continue;
    if (z > uvz.z() + tol) return Seen::kFree;
    blocked = true;
  }
  return blocked ? Seen::kBlocked : Seen::kUnknown;
}

}  // namespace

double closed_length(const std::vector<Eigen::Vector3d>& loop) {
  double l = 0.0;
  for (size_t i = 0; i < loop.size(); ++i) l += (loop[(i + 1) % loop.size()] - loop[i]).norm();
  return l;
}

namespace {

// Room a hand needs beyond a hole, before the table, to curl its fingers (m).
constexpr double kMinRoom = 0.05;
// Seen through into known-free space (with a sensed map): the hole itself, away from its rim,
// must be seen free (kHoleFree of it), and on both sides the space where fingertips come out (a
// cap of directions within 60 degrees of the passage, twice the hole's width out, 4-10 cm) must be
// at least kFarSideFree known free. A bar seen from above leaves a thin shadow behind it that may
// hold more of the bar (the bag's strap, a jug's handle: a 1-2 cm fin just behind the hole), which
// the cap's share allows for; a container's mouth, a neck, a slit or a gap between objects leads
// into walls or unknown space all round.
constexpr double kFarSideMin = 0.04, kFarSideMax = 0.10;
constexpr double kHoleFree = 0.7, kFarSideFree = 0.5;

// Material on every side of an axis at p (direction u): among the points within `radius` of p
// and `half` of its cross-section plane (at least 3), no angular gap over 90 degrees.
bool surrounded(const PointIndex& index, const Eigen::Vector3d& p, const Eigen::Vector3d& u,
                double radius, double half) {
  const Eigen::Vector3d u1 = u.unitOrthogonal(), u2 = u.cross(u1);
  std::vector<std::pair<unsigned, double>> near;
  index.radius(p, radius, near);
  std::vector<double> angles;
  for (const auto& [i, d2] : near) {
    const Eigen::Vector3d v = index.points()[i] - p;
    if (std::abs(v.dot(u)) > half) continue;
    const double x = v.dot(u1), y = v.dot(u2);
    if (x * x + y * y > 1e-18) angles.push_back(std::atan2(y, x));
  }
  if (angles.size() < 3) return false;
  std::sort(angles.begin(), angles.end());
  double gap = angles.front() + 2 * M_PI - angles.back();
  for (std::size_t k = 1; k < angles.size(); ++k) gap = std::max(gap, angles[k] - angles[k - 1]);
  return gap < M_PI / 2;
}

// A line of the open-passage probe: its unit direction and its tilt from the loop's normal.
struct ProbeLine {
  Eigen::Vector3d u;
  int tilt = 0;  // degrees
};

// The loop's normal n, then (if `tilted`) lines 15 and 30 degrees from it at 8 azimuths each.
std::vector<ProbeLine> probe_lines(const Eigen::Vector3d& n, bool tilted) {
  std::vector<ProbeLine> out{{n, 0}};
  if (!tilted) return out;
  const Eigen::Vector3d a = n.unitOrthogonal(), b = n.cross(a);
  for (int tilt : {15, 30}) {
    const double c = std::cos(tilt * M_PI / 180.0), s = std::sin(tilt * M_PI / 180.0);
    for (int k = 0; k < 8; ++k) {
      const double phi = 2.0 * M_PI * k / 8.0;
      out.push_back({c * n + s * (std::cos(phi) * a + std::sin(phi) * b), tilt});
    }
  }
  return out;
}

// Distance from p along the unit direction u to where the ray leaves the box (0 if outside).
double exit_distance(const Eigen::AlignedBox3d& box, const Eigen::Vector3d& p,
                     const Eigen::Vector3d& u) {
  double t = std::numeric_limits<double>::infinity();
  for (int k = 0; k < 3; ++k) {
    if (u[k] > 1e-12) t = std::min(t, (box.max()[k] - p[k]) / u[k]);
    if (u[k] < -1e-12) t = std::min(t, (box.min()[k] - p[k]) / u[k]);
  }
  return std::max(0.0, t);
}

// The bar's cross-section at loop point p with tangent t: the cloud points in a slab across the
// loop, grown from p over gaps shorter than `link`; its diameter. +inf when it reaches `cap` (a
// wall or a body), or when the ring where closed fingers would lie around it (its radius plus
// half a finger) meets material, space no camera saw (the bar may be deeper than it looked) or
// the supporting surface.
double bar_at(const PointIndex& index, const std::vector<DepthView>& views,
              const std::optional<Eigen::Vector4d>& support, const Eigen::Vector3d& p,
              const Eigen::Vector3d& t, double link, double cap, double finger) {
  constexpr double kInf = std::numeric_limits<double>::infinity();
  const PointCloud& cloud = index.points();
  std::vector<std::pair<unsigned, double>> near;
  index.radius(p, cap, near);
  std::vector<Eigen::Vector3d> slab;
  for (const auto& [i, d2] : near) {
    const Eigen::Vector3d v = cloud[i] - p;
    if (std::abs(v.dot(t)) <= 0.5 * link) slab.push_back(v - t * v.dot(t));
  }
  std::sort(slab.begin(), slab.end(), [](const Eigen::Vector3d& a, const Eigen::Vector3d& b) {
    return a.squaredNorm() < b.squaredNorm();
  });
  if (slab.empty() || slab.front().norm() > link) return 0.0;  // no material measured here
  std::vector<char> in(slab.size(), 0);
  std::vector<int> blob{0}, stack{0};
  in[0] = 1;
  while (!stack.empty()) {
    const int a = stack.back();
    stack.pop_back();
    for (std::size_t b = 0; b < slab.size(); ++b) {
      if (in[b] || (slab[b] - slab[a]).norm() > link) continue;
      if (slab[b].norm() > 0.95 * cap) return kInf;
      in[b] = 1;
      blob.push_back(static_cast<int>(b));
      stack.push_back(static_cast<int>(b));
    }
  }
  double diameter = 0.0;
  Eigen::Vector3d centre = Eigen::Vector3d::Zero();
  for (std::size_t i = 0; i < blob.size(); ++i) {
    centre += slab[blob[i]];
    for (std::size_t j = i + 1; j < blob.size(); ++j)
      diameter = std::max(diameter, (slab[blob[i]] - slab[blob[j]]).norm());
  }
  centre = p + centre / static_cast<double>(blob.size());
  // Where the fingers go: 12 places around the bar; at most one may hold material or lie below
  // the support (noise). A bar seen from one side hides part of its back from every camera: up to
  // a quarter of the ring may be unseen (a handle's back: 1-3 places). More means the material's
  // extent is unknown (a wall seen from its top hides 4-6: it may reach down to the support).
  const Eigen::Vector3d u1 = t.unitOrthogonal(), u2 = t.cross(u1);
  const double ring = 0.5 * diameter + 0.5 * finger + 0.5 * link;
  int blocked = 0, hidden = 0;
  for (int k = 0; k < 12; ++k) {
    const double a = 2.0 * M_PI * k / 12.0;
    const Eigen::Vector3d q = centre + ring * (std::cos(a) * u1 + std::sin(a) * u2);
    const bool material = index.count_within(q, 0.5 * finger, 1) > 0;
    const bool below = support && (support->head<3>().dot(q) + (*support)[3]) <
                                      0.5 * finger * support->head<3>().norm();
    blocked += material || below;
    hidden += !material && !below && !views.empty() && seen_from(views, q, 0.005) == Seen::kBlocked;
  }
  return blocked > 1 || hidden > 3 ? kInf : diameter;
}

void measure_bar(Loop& loop, const PointIndex& index, const std::vector<DepthView>& views,
                 const RankingOptions& o) {
  double link = o.link_distance;
  if (!(link > 0)) link = 1.5 * loop.length / static_cast<double>(loop.points.size());
  const double cap = o.closed_aperture > 0 ? std::max(0.06, 1.5 * o.closed_aperture) : 0.15;
  const double finger = o.finger_thickness > 0 ? o.finger_thickness : 0.5 * o.min_hole;
  loop.bar_profile.clear();
  std::vector<double> measured;
  // The places: kBarSamples points equally spaced by arc length, with their tangents.
  for (const auto& place : clasp_targets(loop.points, kBarSamples)) {
    const double b =
        bar_at(index, views, o.support_plane, place.point, place.tangent, link, cap, finger);
    loop.bar_profile.push_back(b);
    if (b > 0) measured.push_back(b);
  }
  // The third thinnest place: one or two partial cross-sections (sparse points) read too thin.
  std::sort(measured.begin(), measured.end());
  loop.bar_thickness = measured.size() >= 3 ? measured[2] : std::numeric_limits<double>::infinity();
}

// `bounds`: the cloud's bounding box (computed once for all loops).
// What the sensed map says of the space beyond a hole on one side (direction u): a spherical cap
// of radius `length` (directions within 60 degrees of u) where the fingertips come out. Points
// outside the map's region count as free (sensed_space.hpp's rule for space far from the object).
struct FarSide {
  int free = 0, unknown = 0, occupied = 0;
  double share_free() const {
    const int all = free + unknown + occupied;
    return all > 0 ? static_cast<double>(free) / all : 1.0;
  }
};

Sensed robot_view(const SensedSpace& space, const Eigen::Vector3d& q) {
  return space.region().contains(q) ? space.at(q) : Sensed::kFree;
}

FarSide far_side(const SensedSpace& space, const Eigen::Vector3d& centre, const Eigen::Vector3d& u,
                 double length) {
  FarSide f;
  const Eigen::Vector3d a = u.unitOrthogonal(), b = u.cross(a);
  // Rings at 0, 20, 40 and 60 degrees from u, 6 points per 20 degrees of tilt.
  for (int ring = 0; ring <= 3; ++ring) {
    const double tilt = ring * M_PI / 9.0;
    const int count = ring == 0 ? 1 : 6 * ring;
    for (int k = 0; k < count; ++k) {
      const double phi = 2.0 * M_PI * k / count;
      const Eigen::Vector3d d =
          std::cos(tilt) * u + std::sin(tilt) * (std::cos(phi) * a + std::sin(phi) * b);
      const Sensed s = robot_view(space, centre + length * d);
      (s == Sensed::kFree ? f.free : s == Sensed::kOccupied ? f.occupied : f.unknown) += 1;
    }
  }
  return f;
}

// A camera position from which the hole would be seen through: on its axis, 0.6 m out, on the
// side whose space was seen (else the upper side), and above the support (a camera under the table
// is no advice): a side whose position is not 5 cm above it is swapped for the other, and failing
// both, the position is raised along the support's normal.
Eigen::Vector3d next_best_view(const Eigen::Vector3d& centre, const Eigen::Vector3d& u,
                               const FarSide& plus, const FarSide& minus,
                               const std::optional<Eigen::Vector4d>& support) {
  constexpr double kDistance = 0.6, kAbove = 0.05;
  double side = plus.free >= minus.free ? 1.0 : -1.0;
  if (plus.free == minus.free) side = u.z() >= 0 ? 1.0 : -1.0;
  Eigen::Vector3d view = centre + side * kDistance * u;
  if (!support) return view;
  const Eigen::Vector3d up = support->head<3>().normalized();
  const double offset = (*support)[3] / support->head<3>().norm();
  const auto height = [&](const Eigen::Vector3d& p) { return up.dot(p) + offset; };
  if (height(view) < kAbove) view = centre - side * kDistance * u;
  if (height(view) < kAbove) view += (kAbove - height(view)) * up;
  return view;
}

std::string point_text(const Eigen::Vector3d& p) {
  char buf[96];
  std::snprintf(buf, sizeof buf, "(%.2f, %.2f, %.2f)", p.x(), p.y(), p.z());
  return buf;
}

void assess(Loop& loop, const PointIndex& index, const Eigen::AlignedBox3d& bounds,
            const std::vector<DepthView>& views, const RankingOptions& options) {
  auto& pts = loop.points;
  loop.length = closed_length(pts);
  loop.claspable = false;
  loop.hole_width = 0.0;
  if (pts.size() < 3 || !(loop.length > 0)) {
    loop.verdict = LoopVerdict::kDegenerate;
    loop.reason = "degenerate loop (fewer than 3 distinct points)";
    return;
  }
  // Least-squares plane of the loop (segment-length weighted).
  Eigen::Vector3d c = Eigen::Vector3d::Zero();
  double wsum = 0.0;
  for (size_t i = 0; i < pts.size(); ++i) {
    const Eigen::Vector3d& a = pts[i];
    const Eigen::Vector3d& b = pts[(i + 1) % pts.size()];
    const double w = (b - a).norm();
    c += w * 0.5 * (a + b);
    wsum += w;
  }
  c /= wsum;
  Eigen::Matrix3d cov = Eigen::Matrix3d::Zero();
  for (const auto& p : pts) cov += (p - c) * (p - c).transpose();
  Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> es(cov);
  Eigen::Vector3d n = es.eigenvectors().col(0);
  // A deterministic normal sign, then the loop counter-clockwise about it.
  if (std::abs(n.z()) > 1e-6) {
    if (n.z() < 0) n = -n;
  } else if (std::abs(n.y()) > 1e-6) {
    if (n.y() < 0) n = -n;
  } else if (n.x() < 0) {
    n = -n;
  }
  Eigen::Vector3d area = Eigen::Vector3d::Zero();
  for (size_t i = 0; i < pts.size(); ++i) area += (pts[i] - c).cross(pts[(i + 1) % pts.size()] - c);
  if (area.dot(n) < 0) {
    std::reverse(pts.begin() + 1, pts.end());
    if (loop.vertices.size() == pts.size())
      std::reverse(loop.vertices.begin() + 1, loop.vertices.end());
  }
  loop.normal = n;
  const Eigen::Vector3d e1 = es.eigenvectors().col(2).normalized();
  const Eigen::Vector3d e2 = n.cross(e1);
  std::vector<Eigen::Vector2d> poly;
  Eigen::AlignedBox2d box;
  for (const auto& p : pts) {
    poly.emplace_back((p - c).dot(e1), (p - c).dot(e2));
    box.extend(poly.back());
  }
  // The hole's centre: the interior point of the planar polygon farthest from every cloud point.
  const Eigen::Vector2d ext = box.sizes();
  const double step = std::max(std::max(ext.x(), ext.y()) / 48.0, 1e-5);
  std::vector<Eigen::Vector3d> samples;
  std::vector<double> clearance;
  double best = 0.0;
  for (double x = box.min().x() + step / 2; x < box.max().x(); x += step) {
    for (double y = box.min().y() + step / 2; y < box.max().y(); y += step) {
      if (!inside_polygon(poly, {x, y})) continue;
      const Eigen::Vector3d q = c + x * e1 + y * e2;
      const double cl = index.nearest(q).second;
      samples.push_back(q);
      clearance.push_back(cl);
      if (cl > best) {
        best = cl;
        loop.centre = q;
      }
    }
  }
  if (samples.empty()) {
    loop.centre = c;
    loop.verdict = LoopVerdict::kDegenerate;
    loop.reason = "degenerate loop (its plane projection has no interior)";
    return;
  }
  loop.hole_width = 2.0 * best;
  // With a hand, the narrowest hole is its fingers' (min_hole is for an unknown hand).
  const bool hand = options.finger_thickness > 0;
  const double min_hole = hand ? options.finger_thickness + kFingerClearance : options.min_hole;
  const double needed = hand ? min_hole + kHoleWidthExcess : min_hole;
  if (loop.hole_width < needed) {
    loop.verdict = hand ? LoopVerdict::kHandTooLarge : LoopVerdict::kTooNarrow;
    loop.reason = hand ? "too narrow for this hand: hole " + metres(loop.hole_width) +
                             " wide < fingers " + metres(options.finger_thickness) + " + " +
                             centimetres(kFingerClearance + kHoleWidthExcess)
                       : "too narrow: hole " + metres(loop.hole_width) + " wide < min-hole " +
                             metres(options.min_hole);
    return;
  }
  // Seen through? Only the central part of the hole (away from the loop's own surface).
  if (!views.empty()) {
    const double tol = std::max(0.005, 0.1 * loop.hole_width);
    int free = 0, blocked = 0;
    for (size_t i = 0; i < samples.size(); ++i) {
      if (clearance[i] < 0.5 * best) continue;
      const Seen s = seen_from(views, samples[i], tol);
      free += s == Seen::kFree;
      blocked += s == Seen::kBlocked;
    }
    if (free + blocked > 0 && free < blocked) {
      const int hidden = static_cast<int>(std::lround(100.0 * blocked / (free + blocked)));
      loop.verdict = LoopVerdict::kOcclusionShadow;
      loop.reason = "occlusion shadow: " + std::to_string(hidden) +
                    "% of the hole lies on or behind measured surface in every camera (never "
                    "seen through: a gap behind a nearer part, or in sparse data)";
      return;
    }
  }
  // Open passage: a finger-wide probe must pass straight through the hole without meeting
  // material, and free space must open up beyond the object on both sides. A finger need not
  // pass along the loop's normal: beside a bulging body (a teapot's handle) a line tilted away from
  // the body is free where the normal grazes it, so with cameras lines up to 30 degrees from the
  // normal are tried too; a loop around a tube's wall has material inside it along every line.
  const double rho = 0.45 * min_hole;
  const double reach = std::max(2.0 * loop.hole_width, 0.1);
  const double dt = std::max(rho / 2.0, 1e-4);
  const SensedSpace* sensed = options.sensed && !options.sensed->empty() ? options.sensed : nullptr;
  const double far_length = std::clamp(2.0 * loop.hole_width, kFarSideMin, kFarSideMax);
  std::optional<FarSide> closed_side;  // the first line whose far side was not free
  Eigen::Vector3d closed_view = Eigen::Vector3d::Zero();
  // The hole itself, away from its rim (voxels near it straddle the bar), seen free?
  double hole_free = 1.0;
  if (sensed) {
    int free = 0, all = 0;
    for (size_t i = 0; i < samples.size(); ++i) {
      if (clearance[i] < 0.5 * best) continue;
      ++all;
      free += robot_view(*sensed, samples[i]) == Sensed::kFree;
    }
    hole_free = all > 0 ? static_cast<double>(free) / all : 0.0;
  }
  const bool hole_seen = hole_free >= kHoleFree;
  double blocked_at = 0.0;
  bool surrounded_end = false, passage = false;
  int tilt = 0;  // degrees from the normal of the line that passed
  for (const ProbeLine& line : probe_lines(n, !views.empty())) {
    const Eigen::Vector3d& u = line.u;
    double hit = 0.0;
    for (double t = dt; t <= reach + 1e-12 && hit == 0.0; t += dt) {
      for (double sgn : {1.0, -1.0}) {
        const Eigen::Vector3d q = loop.centre + sgn * t * u;
        // A tilted line must run through space a camera saw: behind a tube's near wall, unseen
        // space would let it through.
        if (index.count_within(q, rho, 2) >= 2 ||
            (line.tilt > 0 && seen_from(views, q, 0.005) == Seen::kBlocked))
          hit = t;
      }
    }
    if (hit > 0.0) {
      if (blocked_at == 0.0) blocked_at = hit;  // the first blocked line's, for the reason
      continue;
    }
    // At each end of the probe, material all around the axis (no angular gap wider than 90
    // degrees among the points within 1.5 hole radii) means the passage is a tube's inside.
    bool ends_open = true;
    for (double sgn : {1.0, -1.0})
      ends_open = ends_open && !surrounded(index, loop.centre + sgn * reach * u, u, 1.5 * best,
                                           std::numeric_limits<double>::infinity());
    if (!ends_open) {
      surrounded_end = true;
      continue;
    }
    // Seen into known-free space on both sides, where the fingertips come out.
    if (sensed && hole_seen) {
      const FarSide plus = far_side(*sensed, loop.centre, u, far_length);
      const FarSide minus = far_side(*sensed, loop.centre, -u, far_length);
      if (plus.share_free() < kFarSideFree || minus.share_free() < kFarSideFree) {
        if (!closed_side) {
          closed_side = plus.share_free() < minus.share_free() ? plus : minus;
          closed_view = next_best_view(loop.centre, u, plus, minus, options.support_plane);
        }
        continue;
      }
    }
    passage = true;
    tilt = line.tilt;
    break;
  }
  // A passage whose hole was not seen free, or none whose far sides were: refused, with a view.
  if (sensed && ((passage && !hole_seen) || (!passage && closed_side))) {
    std::string what;
    if (passage) {
      loop.verdict = LoopVerdict::kUnseenFarSide;
      what = "never seen through: only " + std::to_string(std::lround(100.0 * hole_free)) +
             "% of the hole is known free space (a slit in a partly seen wall, or a shadow "
             "between objects)";
      closed_view = next_best_view(loop.centre, n, FarSide{}, FarSide{}, options.support_plane);
    } else {
      const FarSide& f = *closed_side;
      const int share = static_cast<int>(std::lround(100.0 * (1.0 - f.share_free())));
      const std::string beyond =
          " of the space " + metres(far_length) + " beyond the hole, where fingertips come out, ";
      loop.verdict = f.occupied > f.unknown ? LoopVerdict::kEnclosed : LoopVerdict::kUnseenFarSide;
      what = f.occupied > f.unknown
                 ? "leads into enclosed space: " + std::to_string(share) + "%" + beyond +
                       "is measured surface or unseen (a container's mouth, a bowl's or pot's "
                       "rim)"
                 : "never seen through: " + std::to_string(share) + "%" + beyond +
                       "is unknown (a container's mouth or neck, a slit in a partly seen wall, "
                       "or a shadow between objects)";
    }
    loop.reason = what + "; a camera at " + point_text(closed_view) +
                  " m looking along the hole's axis would see through it";
    return;
  }
  if (!passage) {
    loop.verdict = LoopVerdict::kTubeWall;
    loop.reason = surrounded_end
                      ? "loop around a tube wall: material all around the passage " +
                            metres(reach) + " from the hole (the inside of a tube, not a hole)"
                      : "loop around a tube wall: material inside the loop (a " + metres(2 * rho) +
                            " probe through it is blocked " + metres(blocked_at) +
                            " from the hole)";
    return;
  }
  if (!sensed && options.sensor_origin_missing) {
    loop.verdict = LoopVerdict::kNoSensorOrigin;
    loop.reason =
        "not known to be a hole: the cloud has no sensor origin, so a hole cannot be told from an "
        "unseen gap (give the sensor's pose, or a PCD with its VIEWPOINT)";
    return;
  }
  // A passage, not a cavity's opening. Followed downwards until it leaves the object's bounds,
  // the passage must not meet the supporting surface soon (a hole lying on the table: no room
  // for fingers beyond it), nor meet it after running between walls on every side (a container's
  // mouth whose inside bottom was unseen or removed with the table).
  if (options.support_plane) {
    const Eigen::Vector3d up = options.support_plane->head<3>().normalized();
    const double height =
        (options.support_plane->head<3>().dot(loop.centre) + (*options.support_plane)[3]) /
        options.support_plane->head<3>().norm();
    const double descent = -up.dot(n);  // height lost per metre along +n
    const Eigen::Vector3d down = (descent > 0 ? 1.0 : -1.0) * n;
    if (std::abs(descent) > 1e-9) {
      const double t_floor = height / std::abs(descent);
      if (t_floor < std::max(kMinRoom, 2.0 * options.finger_thickness)) {
        loop.verdict = LoopVerdict::kBlockedBySupport;
        loop.reason =
            "blocked by the support: the passage through the loop meets the "
            "supporting surface " +
            metres(t_floor) + " from the hole (no room for fingers beyond it)";
        return;
      }
      // Within the object's extent (its lowest points may be cropped just above the table).
      const double link = options.link_distance > 0 ? options.link_distance : 0.01;
      if (t_floor <= exit_distance(bounds, loop.centre, down) + 2.0 * link) {
        for (double t = std::max(best, link); t < t_floor - link; t += link) {
          if (surrounded(index, loop.centre + t * down, down, 1.5 * best, link)) {
            loop.verdict = LoopVerdict::kCavity;
            loop.reason = "opening into a cavity: walls all around the passage " + metres(t) +
                          " in, and it ends at the supporting surface " + metres(t_floor) +
                          " from the hole (a container's mouth)";
            return;
          }
        }
      }
    }
  }
  // The closed hand around the bar.
  measure_bar(loop, index, views, options);
  if (options.closed_aperture > 0 && !(loop.bar_thickness <= widest_bar(options.closed_aperture))) {
    loop.verdict = LoopVerdict::kBarTooThick;
    loop.reason = "bar too thick for this hand: the thinnest material along the loop is " +
                  (std::isfinite(loop.bar_thickness) ? metres(loop.bar_thickness)
                                                     : std::string("a wall or body")) +
                  " across > the closed hand's " + metres(options.closed_aperture) + " less " +
                  centimetres(kFingerClearance);
    return;
  }
  loop.claspable = true;
  loop.verdict = LoopVerdict::kClaspable;
  loop.reason = "claspable: open hole " + metres(loop.hole_width) + " wide (" +
                (hand ? "fingers need " : "min-hole ") + metres(needed) + ")" +
                (views.empty() ? "" : ", seen through") +
                (tilt > 0 ? ", passable " + std::to_string(tilt) + " degrees from its axis" : "");
  if (hand || options.closed_aperture > 0) {
    const double hole_slack = (loop.hole_width - min_hole) / min_hole;
    const double bar_slack =
        options.closed_aperture > 0
            ? (options.closed_aperture - loop.bar_thickness) / options.closed_aperture
            : hole_slack;
    loop.fit = std::min(hole_slack, bar_slack);
    loop.reason += ", bar " + metres(loop.bar_thickness) + " fits the hand";
  }
}

}  // namespace

void assess_loop(Loop& loop, const PointCloud& cloud, const std::vector<DepthView>& views,
                 const RankingOptions& options) {
  const PointIndex index(cloud);
  assess(loop, index, bounds(cloud), views, options);
}

void rank_loops(std::vector<Loop>& loops, const PointCloud& cloud,
                const std::vector<DepthView>& views, const RankingOptions& options) {
  const PointIndex index(cloud);
  const Eigen::AlignedBox3d box = bounds(cloud);
  for (auto& l : loops) assess(l, index, box, views, options);
  const bool hand = options.finger_thickness > 0 || options.closed_aperture > 0;
  std::stable_sort(loops.begin(), loops.end(), [hand](const Loop& a, const Loop& b) {
    if (a.claspable != b.claspable) return a.claspable;
    if (a.claspable && hand && a.fit != b.fit) return a.fit > b.fit;
    if (a.claspable && a.hole_width != b.hole_width) return a.hole_width > b.hole_width;
    return a.length < b.length;
  });
  for (size_t i = 0; i < loops.size(); ++i) loops[i].rank = static_cast<int>(i) + 1;
}

std::vector<ClaspTarget> clasp_targets(const std::vector<Eigen::Vector3d>& loop, int k) {
  if (k < 1) throw std::invalid_argument("the number of clasp targets must be >= 1");
  const size_t n = loop.size();
  std::vector<double> cum(n + 1, 0.0);
  for (size_t i = 0; i < n; ++i) cum[i + 1] = cum[i] + (loop[(i + 1) % n] - loop[i]).norm();
  const double total = cum[n];
  if (n < 3 || !(total > 0))
    throw std::invalid_argument("clasp targets need a non-degenerate loop");
  auto at = [&](double s) -> Eigen::Vector3d {
    s = std::fmod(s, total);
    if (s < 0) s += total;
    size_t i = std::upper_bound(cum.begin(), cum.end(), s) - cum.begin();
    i = std::min(std::max<size_t>(i, 1), n) - 1;
    const double seg = cum[i + 1] - cum[i];
    const double t = seg > 0 ? (s - cum[i]) / seg : 0.0;
    return loop[i] + t * (loop[(i + 1) % n] - loop[i]);
  };
  const double h = total / (2.0 * k);
  std::vector<ClaspTarget> out;
  for (int i = 0; i < k; ++i) {
    const double s = total * i / k;
    Eigen::Vector3d t = at(s + h) - at(s - h);
    if (!(t.norm() > 1e-12)) t = at(s + 1e-6 * total) - at(s);
    out.push_back({at(s), t.normalized()});
  }
  return out;
}

std::vector<ClaspTarget> clasp_targets(const Loop& loop, int k, double max_bar) {
  const int n = static_cast<int>(loop.bar_profile.size());
  std::vector<int> fits;
  for (int i = 0; i < n; ++i)
    if (loop.bar_profile[i] > 0 && loop.bar_profile[i] <= max_bar) fits.push_back(i);
  if (!(max_bar > 0) || fits.empty() || static_cast<int>(fits.size()) == n)
    return clasp_targets(loop.points, k);
  if (k < 1) throw std::invalid_argument("the number of clasp targets must be >= 1");
  // The fitting samples stand for equal arcs; spread k targets over them evenly.
  const auto fine = clasp_targets(loop.points, n);
  std::vector<ClaspTarget> out;
  for (int i = 0; i < k; ++i) {
    const double at = i * static_cast<double>(fits.size()) / k;
    out.push_back(fine[fits[std::min(static_cast<int>(at), static_cast<int>(fits.size()) - 1)]]);
  }
  return out;
}

const char* verdict_name(LoopVerdict verdict) {
  switch (verdict) {
    case LoopVerdict::kUnranked:
      return "unranked";
    case LoopVerdict::kClaspable:
      return "claspable";
    case LoopVerdict::kTooNarrow:
      return "too_narrow";
    case LoopVerdict::kHandTooLarge:
      return "hand_too_large";
    case LoopVerdict::kOcclusionShadow:
      return "occlusion_shadow";
    case LoopVerdict::kTubeWall:
      return "tube_wall";
    case LoopVerdict::kEnclosed:
      return "enclosed";
    case LoopVerdict::kUnseenFarSide:
      return "unseen_far_side";
    case LoopVerdict::kNoSensorOrigin:
      return "no_sensor_origin";
    case LoopVerdict::kBlockedBySupport:
      return "blocked_by_support";
    case LoopVerdict::kCavity:
      return "cavity";
    case LoopVerdict::kBarTooThick:
      return "bar_too_thick";
    case LoopVerdict::kDegenerate:
      return "degenerate";
    case LoopVerdict::kNoRoom:
      return "no_room";
  }
  return "unranked";
}

}  // namespace claspplan::perception
