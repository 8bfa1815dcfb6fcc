#include "perception/loop_probes.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

#include "perception/cloud_filters.hpp"

namespace claspplan::perception {

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

double exit_distance(const Eigen::AlignedBox3d& box, const Eigen::Vector3d& p,
                     const Eigen::Vector3d& u) {
  double t = std::numeric_limits<double>::infinity();
  for (int k = 0; k < 3; ++k) {
    if (u[k] > 1e-12) t = std::min(t, (box.max()[k] - p[k]) / u[k]);
    if (u[k] < -1e-12) t = std::min(t, (box.min()[k] - p[k]) / u[k]);
  }
  return std::max(0.0, t);
}

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
  const SupportHeight height(support);
  int blocked = 0, hidden = 0;
  for (int k = 0; k < 12; ++k) {
    const double a = 2.0 * M_PI * k / 12.0;
    const Eigen::Vector3d q = centre + ring * (std::cos(a) * u1 + std::sin(a) * u2);
    const bool material = index.count_within(q, 0.5 * finger, 1) > 0;
    const bool below = height(q) < 0.5 * finger;
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

Sensed robot_view(const SensedSpace& space, const Eigen::Vector3d& q) {
  return space.region().contains(q) ? space.at(q) : Sensed::kFree;
}

FarSide far_side(const SensedSpace& space, const Eigen::Vector3d& centre, const Eigen::Vector3d& u,
                 double length, const std::optional<Eigen::Vector4d>& support) {
  const SupportHeight height(support);
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
      const Eigen::Vector3d point = centre + length * d;
      const Sensed s = robot_view(space, point);
      (s == Sensed::kFree ? f.free : s == Sensed::kOccupied ? f.occupied : f.unknown) += 1;
      f.under_support += s != Sensed::kFree && height(point) < 0.0;
    }
  }
  return f;
}

Eigen::Vector3d next_best_view(const Eigen::Vector3d& centre, const Eigen::Vector3d& u,
                               const FarSide& plus, const FarSide& minus,
                               const std::optional<Eigen::Vector4d>& support) {
  constexpr double kDistance = 0.6, kAbove = 0.05;
  double side = plus.free >= minus.free ? 1.0 : -1.0;
  if (plus.free == minus.free) side = u.z() >= 0 ? 1.0 : -1.0;
  Eigen::Vector3d view = centre + side * kDistance * u;
  if (!support) return view;
  const SupportHeight height(support);
  if (height(view) < kAbove) view = centre - side * kDistance * u;
  if (height(view) < kAbove) view += (kAbove - height(view)) * height.up;
  return view;
}

}  // namespace claspplan::perception
