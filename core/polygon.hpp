// Planar polygon tests, for loops projected into their plane (a hole's width, a closed hand's
// aperture).
#pragma once

#include <algorithm>
#include <vector>

#include <Eigen/Core>

namespace claspplan {

/// Is q inside the closed polygon (even-odd rule; the last vertex joins the first)?
inline bool inside_polygon(const std::vector<Eigen::Vector2d>& polygon, const Eigen::Vector2d& q) {
  bool in = false;
  for (std::size_t i = 0, j = polygon.size() - 1; i < polygon.size(); j = i++) {
    const Eigen::Vector2d& a = polygon[i];
    const Eigen::Vector2d& b = polygon[j];
    if ((a.y() > q.y()) != (b.y() > q.y()) &&
        q.x() < (b.x() - a.x()) * (q.y() - a.y()) / (b.y() - a.y()) + a.x())
      in = !in;
  }
  return in;
}

/// Distance from p to the segment [a, b].
inline double segment_distance(const Eigen::Vector2d& p, const Eigen::Vector2d& a,
                               const Eigen::Vector2d& b) {
  const Eigen::Vector2d ab = b - a;
  const double t = std::clamp((p - a).dot(ab) / std::max(ab.squaredNorm(), 1e-300), 0.0, 1.0);
  return (a + t * ab - p).norm();
}

}  // namespace claspplan
