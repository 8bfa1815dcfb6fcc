#include "perception/loops.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <stdexcept>

#include <Eigen/Eigenvalues>

#include "perception/point_index.hpp"

namespace claspplan::perception {

namespace {

std::string metres(double v) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "%.3f m", v);
  return buf;
}

// Even-odd point-in-polygon test in the plane.
bool inside(const std::vector<Eigen::Vector2d>& poly, const Eigen::Vector2d& q) {
  bool in = false;
  for (size_t i = 0, j = poly.size() - 1; i < poly.size(); j = i++) {
    const auto& a = poly[i];
    const auto& b = poly[j];
    if ((a.y() > q.y()) != (b.y() > q.y()) &&
        q.x() < (b.x() - a.x()) * (q.y() - a.y()) / (b.y() - a.y()) + a.x())
      in = !in;
  }
  return in;
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

void assess(Loop& loop, const PointIndex& index, const std::vector<DepthView>& views,
            const RankingOptions& options) {
  const PointCloud& cloud = index.points();
  auto& pts = loop.points;
  loop.length = closed_length(pts);
  loop.claspable = false;
  loop.hole_width = 0.0;
  if (pts.size() < 3 || !(loop.length > 0)) {
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
      if (!inside(poly, {x, y})) continue;
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
    loop.reason = "degenerate loop (its plane projection has no interior)";
    return;
  }
  loop.hole_width = 2.0 * best;
  if (loop.hole_width < options.min_hole) {
    loop.reason = "too narrow: hole " + metres(loop.hole_width) + " wide < min-hole " +
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
      loop.reason = "occlusion shadow: " + std::to_string(hidden) +
                    "% of the hole lies on or behind measured surface in every camera (never "
                    "seen through: a gap behind a nearer part, or in sparse data)";
      return;
    }
  }
  // Open passage: a finger-wide probe along the hole's axis must not meet material, and free
  // space must open up beyond the object on both sides.
  const double rho = 0.45 * options.min_hole;
  const double reach = std::max(2.0 * loop.hole_width, 0.1);
  const double dt = std::max(rho / 2.0, 1e-4);
  for (double t = dt; t <= reach + 1e-12; t += dt) {
    for (double sgn : {1.0, -1.0}) {
      if (index.count_within(loop.centre + sgn * t * n, rho, 2) >= 2) {
        loop.reason = "loop around a tube wall: material inside the loop (a " + metres(2 * rho) +
                      " probe through it is blocked " + metres(t) + " from the hole)";
        return;
      }
    }
  }
  // At each end of the probe, material all around the axis (no angular gap wider than 90 degrees
  // among the points within 1.5 hole radii) means the passage is a tube's inside.
  const Eigen::Vector3d u1 = e1, u2 = n.cross(e1);
  std::vector<std::pair<unsigned, double>> near;
  for (double sgn : {1.0, -1.0}) {
    const Eigen::Vector3d end = loop.centre + sgn * reach * n;
    index.radius(end, 1.5 * best, near);
    std::vector<double> angles;
    for (const auto& [i, d2] : near) {
      const Eigen::Vector3d v = cloud[i] - end;
      const double x = v.dot(u1), y = v.dot(u2);
      if (x * x + y * y > 1e-18) angles.push_back(std::atan2(y, x));
    }
    if (angles.size() < 3) continue;
    std::sort(angles.begin(), angles.end());
    double gap = angles.front() + 2 * M_PI - angles.back();
    for (size_t k = 1; k < angles.size(); ++k) gap = std::max(gap, angles[k] - angles[k - 1]);
    if (gap < M_PI / 2) {
      loop.reason = "loop around a tube wall: material all around the passage " + metres(reach) +
                    " from the hole (the inside of a tube, not a hole)";
      return;
    }
  }
  loop.claspable = true;
  loop.reason = "claspable: open hole " + metres(loop.hole_width) + " wide (min-hole " +
                metres(options.min_hole) + ")" + (views.empty() ? "" : ", seen through");
}

}  // namespace

void assess_loop(Loop& loop, const PointCloud& cloud, const std::vector<DepthView>& views,
                 const RankingOptions& options) {
  const PointIndex index(cloud);
  assess(loop, index, views, options);
}

void rank_loops(std::vector<Loop>& loops, const PointCloud& cloud,
                const std::vector<DepthView>& views, const RankingOptions& options) {
  const PointIndex index(cloud);
  for (auto& l : loops) assess(l, index, views, options);
  std::stable_sort(loops.begin(), loops.end(), [](const Loop& a, const Loop& b) {
    if (a.claspable != b.claspable) return a.claspable;
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

}  // namespace claspplan::perception
