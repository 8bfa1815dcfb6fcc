#include "perception/loops.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>
#include <optional>
#include <stdexcept>

#include <Eigen/Eigenvalues>

#include "core/polygon.hpp"
#include "perception/cloud_filters.hpp"
#include "perception/loop_probes.hpp"
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

std::string point_text(const Eigen::Vector3d& p) {
  char buf[96];
  std::snprintf(buf, sizeof buf, "(%.2f, %.2f, %.2f)", p.x(), p.y(), p.z());
  return buf;
}

// The hole a loop bounds, in the loop's least-squares plane: samples of the planar polygon's
// interior with their clearance from the cloud.
struct Hole {
  Eigen::Vector3d normal = Eigen::Vector3d::UnitZ();
  std::vector<Eigen::Vector3d> samples;
  std::vector<double> clearance;
  double radius = 0.0;  // the largest clearance: at loop.centre
};

// Sets loop.normal (deterministic sign, the loop counter-clockwise about it: the points and
// vertices may be reversed), loop.centre and loop.hole_width; false (with the verdict) for a
// degenerate loop.
bool measure_hole(Loop& loop, const PointIndex& index, Hole& hole) {
  auto& pts = loop.points;
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
  loop.normal = hole.normal = n;
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
  for (double x = box.min().x() + step / 2; x < box.max().x(); x += step) {
    for (double y = box.min().y() + step / 2; y < box.max().y(); y += step) {
      if (!inside_polygon(poly, {x, y})) continue;
      const Eigen::Vector3d q = c + x * e1 + y * e2;
      const double cl = index.nearest(q).second;
      hole.samples.push_back(q);
      hole.clearance.push_back(cl);
      if (cl > hole.radius) {
        hole.radius = cl;
        loop.centre = q;
      }
    }
  }
  if (hole.samples.empty()) {
    loop.centre = c;
    loop.verdict = LoopVerdict::kDegenerate;
    loop.reason = "degenerate loop (its plane projection has no interior)";
    return false;
  }
  loop.hole_width = 2.0 * hole.radius;
  return true;
}

// Seen through? Only the central part of the hole (away from the loop's own surface). False
// (with the verdict) when most of it lies on or behind measured surface in every camera.
bool seen_through(Loop& loop, const std::vector<DepthView>& views, const Hole& hole) {
  if (views.empty()) return true;
  const double tol = std::max(0.005, 0.1 * loop.hole_width);
  int free = 0, blocked = 0;
  for (size_t i = 0; i < hole.samples.size(); ++i) {
    if (hole.clearance[i] < 0.5 * hole.radius) continue;
    const Seen s = seen_from(views, hole.samples[i], tol);
    free += s == Seen::kFree;
    blocked += s == Seen::kBlocked;
  }
  if (free + blocked == 0 || free >= blocked) return true;
  const int hidden = static_cast<int>(std::lround(100.0 * blocked / (free + blocked)));
  loop.verdict = LoopVerdict::kOcclusionShadow;
  loop.reason = "occlusion shadow: " + std::to_string(hidden) +
                "% of the hole lies on or behind measured surface in every camera (never "
                "seen through: a gap behind a nearer part, or in sparse data)";
  return false;
}

// What the open-passage probe found.
struct Passage {
  bool found = false;
  int tilt = 0;  // degrees from the normal of the line that passed
  double rho = 0.0, reach = 0.0, far_length = 0.0;
  double blocked_at = 0.0;      // the first blocked line's distance, for the reason
  bool surrounded_end = false;  // a line whose ends are a tube's inside
  const SensedSpace* sensed = nullptr;
  double hole_free = 1.0;  // the share of the hole, away from its rim, seen free
  bool hole_seen = true;
  std::optional<FarSide> closed_side;  // the first line whose far side was not free
  Eigen::Vector3d closed_view = Eigen::Vector3d::Zero();
};

// Open passage: a finger-wide probe must pass straight through the hole without meeting
// material, and free space must open up beyond the object on both sides. A finger need not
// pass along the loop's normal: beside a bulging body (a teapot's handle) a line tilted away from
// the body is free where the normal grazes it, so with cameras lines up to 30 degrees from the
// normal are tried too; a loop around a tube's wall has material inside it along every line.
Passage probe_passage(const Loop& loop, const PointIndex& index,
                      const std::vector<DepthView>& views, const RankingOptions& options,
                      const Hole& hole, double min_hole) {
  Passage p;
  p.rho = 0.45 * min_hole;
  p.reach = std::max(2.0 * loop.hole_width, 0.1);
  const double dt = std::max(p.rho / 2.0, 1e-4);
  p.sensed = options.sensed && !options.sensed->empty() ? options.sensed : nullptr;
  p.far_length = std::clamp(2.0 * loop.hole_width, kFarSideMin, kFarSideMax);
  // The hole itself, away from its rim (voxels near it straddle the bar), seen free?
  if (p.sensed) {
    int free = 0, all = 0;
    for (size_t i = 0; i < hole.samples.size(); ++i) {
      if (hole.clearance[i] < 0.5 * hole.radius) continue;
      ++all;
      free += robot_view(*p.sensed, hole.samples[i]) == Sensed::kFree;
    }
    p.hole_free = all > 0 ? static_cast<double>(free) / all : 0.0;
  }
  p.hole_seen = p.hole_free >= kHoleFree;
  for (const ProbeLine& line : probe_lines(hole.normal, !views.empty())) {
    const Eigen::Vector3d& u = line.u;
    double hit = 0.0;
    for (double t = dt; t <= p.reach + 1e-12 && hit == 0.0; t += dt) {
      for (double sgn : {1.0, -1.0}) {
        const Eigen::Vector3d q = loop.centre + sgn * t * u;
        // A tilted line must run through space a camera saw: behind a tube's near wall, unseen
        // space would let it through.
        if (index.count_within(q, p.rho, 2) >= 2 ||
            (line.tilt > 0 && seen_from(views, q, 0.005) == Seen::kBlocked))
          hit = t;
      }
    }
    if (hit > 0.0) {
      if (p.blocked_at == 0.0) p.blocked_at = hit;
      continue;
    }
    // At each end of the probe, material all around the axis (no angular gap wider than 90
    // degrees among the points within 1.5 hole radii) means the passage is a tube's inside.
    bool ends_open = true;
    for (double sgn : {1.0, -1.0})
      ends_open =
          ends_open && !surrounded(index, loop.centre + sgn * p.reach * u, u, 1.5 * hole.radius,
                                   std::numeric_limits<double>::infinity());
    if (!ends_open) {
      p.surrounded_end = true;
      continue;
    }
    // Seen into known-free space on both sides, where the fingertips come out.
    if (p.sensed && p.hole_seen) {
      const FarSide plus = far_side(*p.sensed, loop.centre, u, p.far_length, options.support_plane);
      const FarSide minus =
          far_side(*p.sensed, loop.centre, -u, p.far_length, options.support_plane);
      if (plus.share_free() < kFarSideFree || minus.share_free() < kFarSideFree) {
        if (!p.closed_side) {
          p.closed_side = plus.share_free() < minus.share_free() ? plus : minus;
          p.closed_view = next_best_view(loop.centre, u, plus, minus, options.support_plane);
        }
        continue;
      }
    }
    p.found = true;
    p.tilt = line.tilt;
    break;
  }
  return p;
}

// A passage whose hole was not seen free, or none whose far sides were (refused with a next best
// view), none at all (a tube wall), or a cloud without a sensor origin: false with the verdict.
bool passage_open(Loop& loop, Passage p, const RankingOptions& options) {
  if (p.sensed && ((p.found && !p.hole_seen) || (!p.found && p.closed_side))) {
    std::string what;
    if (p.found) {
      loop.verdict = LoopVerdict::kUnseenFarSide;
      what = "never seen through: only " + std::to_string(std::lround(100.0 * p.hole_free)) +
             "% of the hole is known free space (a slit in a partly seen wall, or a shadow "
             "between objects)";
      p.closed_view =
          next_best_view(loop.centre, loop.normal, FarSide{}, FarSide{}, options.support_plane);
    } else {
      const FarSide& f = *p.closed_side;
      const int share = static_cast<int>(std::lround(100.0 * (1.0 - f.share_free())));
      const std::string beyond =
          " of the space " + metres(p.far_length) + " beyond the hole, where fingertips come out, ";
      if (2 * f.under_support >= f.unknown + f.occupied) {
        // A hole facing the table (or a shallow container's mouth): no camera would see
        // through it.
        loop.verdict = LoopVerdict::kBlockedBySupport;
        loop.reason = "blocked by the support: " + std::to_string(share) + "%" + beyond +
                      "lies under the supporting surface (a hole facing the table, or a shallow "
                      "container's mouth)";
        return false;
      }
      loop.verdict = f.occupied > f.unknown ? LoopVerdict::kEnclosed : LoopVerdict::kUnseenFarSide;
      what = f.occupied > f.unknown
                 ? "leads into enclosed space: " + std::to_string(share) + "%" + beyond +
                       "is measured surface or unseen (a container's mouth, a bowl's or pot's "
                       "rim)"
                 : "never seen through: " + std::to_string(share) + "%" + beyond +
                       "is unknown (a container's mouth or neck, a slit in a partly seen wall, "
                       "or a shadow between objects)";
    }
    loop.reason = what + "; a camera at " + point_text(p.closed_view) +
                  " m looking along the hole's axis would see through it";
    return false;
  }
  if (!p.found) {
    loop.verdict = LoopVerdict::kTubeWall;
    loop.reason = p.surrounded_end
                      ? "loop around a tube wall: material all around the passage " +
                            metres(p.reach) + " from the hole (the inside of a tube, not a hole)"
                      : "loop around a tube wall: material inside the loop (a " +
                            metres(2 * p.rho) + " probe through it is blocked " +
                            metres(p.blocked_at) + " from the hole)";
    return false;
  }
  if (!p.sensed && options.sensor_origin_missing) {
    loop.verdict = LoopVerdict::kNoSensorOrigin;
    loop.reason =
        "not known to be a hole: the cloud has no sensor origin, so a hole cannot be told from an "
        "unseen gap (give the sensor's pose, or a PCD with its VIEWPOINT)";
    return false;
  }
  return true;
}

// The passage through the loop followed downwards (`down`, along the hole's normal) meets the
// supporting surface (the table) `distance` from the hole; infinitely far without a support or
// for a passage parallel to it.
struct PassageDown {
  Eigen::Vector3d down = Eigen::Vector3d::Zero();
  double distance = std::numeric_limits<double>::infinity();
};
PassageDown passage_down(const Loop& loop, const RankingOptions& options, const Hole& hole) {
  PassageDown p;
  if (!options.support_plane) return p;
  const SupportHeight support(options.support_plane);
  const double descent = -support.up.dot(hole.normal);  // height lost per metre along +normal
  if (std::abs(descent) <= 1e-9) return p;
  p.down = (descent > 0 ? 1.0 : -1.0) * hole.normal;
  p.distance = support(loop.centre) / std::abs(descent);
  return p;
}

// A hole lying on the table (the passage meets it at below.distance): no room for fingers beyond
// it, and no camera could see through it. False with the verdict.
bool room_above_support(Loop& loop, const RankingOptions& options, const PassageDown& below) {
  const double t_floor = below.distance;
  if (t_floor >= std::max(kMinRoom, 2.0 * options.finger_thickness)) return true;
  loop.verdict = LoopVerdict::kBlockedBySupport;
  loop.reason =
      "blocked by the support: the passage through the loop meets the supporting surface " +
      metres(t_floor) + " from the hole (no room for fingers beyond it)";
  return false;
}

// A passage, not a cavity's opening: followed downwards (`below`) until it leaves the object's
// bounds, it must not meet the supporting surface after running between walls on every side (a
// container's mouth whose inside bottom was unseen or removed with the table). False with the
// verdict.
bool clear_of_support(Loop& loop, const PointIndex& index, const Eigen::AlignedBox3d& bounds,
                      const RankingOptions& options, const Hole& hole, const PassageDown& below) {
  const auto& [down, t_floor] = below;
  if (!std::isfinite(t_floor)) return true;
  // Within the object's extent (its lowest points may be cropped just above the table).
  const double link = options.link_distance > 0 ? options.link_distance : 0.01;
  if (t_floor > exit_distance(bounds, loop.centre, down) + 2.0 * link) return true;
  for (double t = std::max(hole.radius, link); t < t_floor - link; t += link) {
    if (surrounded(index, loop.centre + t * down, down, 1.5 * hole.radius, link)) {
      loop.verdict = LoopVerdict::kCavity;
      loop.reason = "opening into a cavity: walls all around the passage " + metres(t) +
                    " in, and it ends at the supporting surface " + metres(t_floor) +
                    " from the hole (a container's mouth)";
      return false;
    }
  }
  return true;
}

// `bounds`: the cloud's bounding box (computed once for all loops). The stages in order, each
// refusing with its verdict: the hole's size, seen through, an open passage into seen space, room
// above the support (told before the passage with cameras), not a cavity's opening, the closed
// hand around the bar.
void assess(Loop& loop, const PointIndex& index, const Eigen::AlignedBox3d& bounds,
            const std::vector<DepthView>& views, const RankingOptions& options) {
  loop.length = closed_length(loop.points);
  loop.claspable = false;
  loop.hole_width = 0.0;
  if (loop.points.size() < 3 || !(loop.length > 0)) {
    loop.verdict = LoopVerdict::kDegenerate;
    loop.reason = "degenerate loop (fewer than 3 distinct points)";
    return;
  }
  Hole hole;
  if (!measure_hole(loop, index, hole)) return;
  // With a hand, the narrowest hole is its fingers' (min_hole is for an unknown hand).
  const bool hand = options.finger_thickness > 0;
  const double min_hole = hand ? options.finger_thickness + kFingerClearance : options.min_hole;
  const double needed = hand ? narrowest_hole(options.finger_thickness) : min_hole;
  if (loop.hole_width < needed) {
    loop.verdict = hand ? LoopVerdict::kHandTooLarge : LoopVerdict::kTooNarrow;
    loop.reason = hand ? "too narrow for this hand: hole " + metres(loop.hole_width) +
                             " wide < fingers " + metres(options.finger_thickness) + " + " +
                             centimetres(kFingerClearance + kHoleWidthExcess)
                       : "too narrow: hole " + metres(loop.hole_width) + " wide < min-hole " +
                             metres(options.min_hole);
    return;
  }
  if (!seen_through(loop, views, hole)) return;
  const Passage passage = probe_passage(loop, index, views, options, hole, min_hole);
  const PassageDown below = passage_down(loop, options, hole);
  // What the cameras saw beyond a hole lying on the table does not matter: told first.
  if (passage.sensed && !room_above_support(loop, options, below)) return;
  if (!passage_open(loop, passage, options)) return;
  if (!passage.sensed && !room_above_support(loop, options, below)) return;
  if (!clear_of_support(loop, index, bounds, options, hole, below)) return;
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
  loop.reason =
      "claspable: open hole " + metres(loop.hole_width) + " wide (" +
      (hand ? "fingers need " : "min-hole ") + metres(needed) + ")" +
      (views.empty() ? "" : ", seen through") +
      (passage.tilt > 0 ? ", passable " + std::to_string(passage.tilt) + " degrees from its axis"
                        : "");
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
