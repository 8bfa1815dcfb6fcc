#include "robots/triangle_tree.hpp"

#include <algorithm>
#include <cmath>
#include <numeric>

namespace claspplan::robots {
namespace {

using Eigen::Vector3d;

// The point of triangle (a, b, c) nearest p, by the Voronoi region p lies in.
Vector3d closest_on_triangle(const Vector3d& p, const Vector3d& a, const Vector3d& b,
                             const Vector3d& c) {
  const Vector3d ab = b - a, ac = c - a, ap = p - a;
  const double d1 = ab.dot(ap), d2 = ac.dot(ap);
  if (d1 <= 0 && d2 <= 0) return a;
  const Vector3d bp = p - b;
  const double d3 = ab.dot(bp), d4 = ac.dot(bp);
  if (d3 >= 0 && d4 <= d3) return b;
  const double vc = d1 * d4 - d3 * d2;
  if (vc <= 0 && d1 >= 0 && d3 <= 0) return a + d1 / (d1 - d3) * ab;
  const Vector3d cp = p - c;
  const double d5 = ab.dot(cp), d6 = ac.dot(cp);
  if (d6 >= 0 && d5 <= d6) return c;
  const double vb = d5 * d2 - d1 * d6;
  if (vb <= 0 && d2 >= 0 && d6 <= 0) return a + d2 / (d2 - d6) * ac;
  const double va = d3 * d6 - d5 * d4;
  if (va <= 0 && d4 - d3 >= 0 && d5 - d6 >= 0)
    return b + (d4 - d3) / ((d4 - d3) + (d5 - d6)) * (c - b);
  const double denom = 1.0 / (va + vb + vc);
  return a + ab * (vb * denom) + ac * (vc * denom);
}

// Squared distance between segments [p1, q1] and [p2, q2] (parameters clamped to [0, 1]).
double segment_segment_distance_sq(const Vector3d& p1, const Vector3d& q1, const Vector3d& p2,
                                   const Vector3d& q2) {
  const Vector3d d1 = q1 - p1, d2 = q2 - p2, r = p1 - p2;
  const double a = d1.squaredNorm(), e = d2.squaredNorm(), f = d2.dot(r);
  constexpr double kTiny = 1e-300;
  double s = 0, t = 0;
  if (a <= kTiny && e <= kTiny) return r.squaredNorm();
  if (a <= kTiny) {
    t = std::clamp(f / e, 0.0, 1.0);
  } else {
    const double c = d1.dot(r);
    if (e <= kTiny) {
      s = std::clamp(-c / a, 0.0, 1.0);
    } else {
      const double b = d1.dot(d2), denom = a * e - b * b;
      s = denom > kTiny ? std::clamp((b * f - c * e) / denom, 0.0, 1.0) : 0.0;
      t = (b * s + f) / e;
      if (t < 0) {
        t = 0;
        s = std::clamp(-c / a, 0.0, 1.0);
      } else if (t > 1) {
        t = 1;
        s = std::clamp((b - c) / a, 0.0, 1.0);
      }
    }
  }
  return (p1 + s * d1 - (p2 + t * d2)).squaredNorm();
}

// Does segment [p0, p1] cross triangle (a, b, c)? (Points on opposite sides of its plane and
// the crossing point inside it.)
bool segment_crosses_triangle(const Vector3d& p0, const Vector3d& p1, const Vector3d& a,
                              const Vector3d& b, const Vector3d& c) {
  const Vector3d n = (b - a).cross(c - a);
  const double s0 = n.dot(p0 - a), s1 = n.dot(p1 - a);
  if ((s0 > 0 && s1 > 0) || (s0 < 0 && s1 < 0) || s0 == s1) return false;
  const Vector3d x = p0 + (s0 / (s0 - s1)) * (p1 - p0);
  const double e0 = n.dot((b - a).cross(x - a)), e1 = n.dot((c - b).cross(x - b)),
               e2 = n.dot((a - c).cross(x - c));
  return (e0 >= 0 && e1 >= 0 && e2 >= 0) || (e0 <= 0 && e1 <= 0 && e2 <= 0);
}

}  // namespace

double segment_triangle_distance_sq(const Vector3d& p0, const Vector3d& p1, const Vector3d& a,
                                    const Vector3d& b, const Vector3d& c) {
  if (segment_crosses_triangle(p0, p1, a, b, c)) return 0.0;
  // Otherwise the nearest pair has an end of the segment or a point of an edge.
  double best = std::min((closest_on_triangle(p0, a, b, c) - p0).squaredNorm(),
                         (closest_on_triangle(p1, a, b, c) - p1).squaredNorm());
  best = std::min(best, segment_segment_distance_sq(p0, p1, a, b));
  best = std::min(best, segment_segment_distance_sq(p0, p1, b, c));
  return std::min(best, segment_segment_distance_sq(p0, p1, c, a));
}

namespace {

// segment_triangle_distance_sq(...) <= r2, stopping at the first candidate pair within reach
// (the same answer: the distance is the least of the candidates).
bool segment_triangle_within(const Vector3d& p0, const Vector3d& p1, const Vector3d& a,
                             const Vector3d& b, const Vector3d& c, double r2) {
  return segment_crosses_triangle(p0, p1, a, b, c) ||
         (closest_on_triangle(p0, a, b, c) - p0).squaredNorm() <= r2 ||
         (closest_on_triangle(p1, a, b, c) - p1).squaredNorm() <= r2 ||
         segment_segment_distance_sq(p0, p1, a, b) <= r2 ||
         segment_segment_distance_sq(p0, p1, b, c) <= r2 ||
         segment_segment_distance_sq(p0, p1, c, a) <= r2;
}

}  // namespace

TriangleTree::TriangleTree(const std::vector<Eigen::Vector3d>& vertices,
                           const std::vector<Eigen::Vector3i>& triangles) {
  std::vector<Vector3d> centres;
  for (const Eigen::Vector3i& t : triangles) {
    if (t[0] == t[1] || t[1] == t[2] || t[0] == t[2]) continue;
    const Vector3d& a = vertices[t[0]];
    Vector3d n = (vertices[t[1]] - a).cross(vertices[t[2]] - a);
    n = n.norm() > 1e-300 ? Vector3d(n.normalized()) : Vector3d::Zero();
    const Vector3d centre = (a + vertices[t[1]] + vertices[t[2]]) / 3.0;
    const double reach =
        std::sqrt(std::max({(a - centre).squaredNorm(), (vertices[t[1]] - centre).squaredNorm(),
                            (vertices[t[2]] - centre).squaredNorm()}));
    triangles_.push_back({a, vertices[t[1]], vertices[t[2]], n, centre, reach});
    centres.push_back(centre);
  }
  if (!triangles_.empty()) build(0, static_cast<int>(triangles_.size()), centres);
}

// Splits at the median along the box's longest axis; leaves hold up to 4 triangles.
int TriangleTree::build(int first, int count, std::vector<Vector3d>& centres) {
  const int index = static_cast<int>(nodes_.size());
  nodes_.emplace_back();
  Eigen::AlignedBox3d box;
  for (int i = first; i < first + count; ++i) {
    box.extend(triangles_[i].a).extend(triangles_[i].b).extend(triangles_[i].c);
  }
  nodes_[index].box = box;
  if (count <= 4) {
    nodes_[index].first = first;
    nodes_[index].count = count;
    return index;
  }
  int axis = 0;
  box.sizes().maxCoeff(&axis);
  std::vector<int> order(count);
  std::iota(order.begin(), order.end(), first);
  const int half = count / 2;
  std::nth_element(order.begin(), order.begin() + half, order.end(),
                   [&](int i, int j) { return centres[i][axis] < centres[j][axis]; });
  std::vector<Triangle> tris;
  std::vector<Vector3d> cs;
  for (int i : order) tris.push_back(triangles_[i]), cs.push_back(centres[i]);
  std::copy(tris.begin(), tris.end(), triangles_.begin() + first);
  std::copy(cs.begin(), cs.end(), centres.begin() + first);
  const int left = build(first, half, centres);
  const int right = build(first + half, count - half, centres);
  nodes_[index].left = left;
  nodes_[index].right = right;
  return index;
}

bool TriangleTree::touches_capsule(const Vector3d& p0, const Vector3d& p1, double radius) const {
  if (nodes_.empty()) return false;
  const Vector3d r = Vector3d::Constant(radius);
  const Eigen::AlignedBox3d reach(p0.cwiseMin(p1) - r, p0.cwiseMax(p1) + r);
  const double r2 = radius * radius;
  const Vector3d d = p1 - p0;
  const double dd = std::max(d.squaredNorm(), 1e-300);
  // Does the segment meet the box grown by the radius (slabs)? The capsule lies inside that
  // segment's sweep, so a miss is a miss of the capsule.
  const auto near_box = [&](const Eigen::AlignedBox3d& box) {
    double t0 = 0.0, t1 = 1.0;
    for (int k = 0; k < 3; ++k) {
      const double lo = box.min()[k] - radius - p0[k], hi = box.max()[k] + radius - p0[k];
      if (std::abs(d[k]) < 1e-300) {
        if (lo > 0 || hi < 0) return false;
        continue;
      }
      double a = lo / d[k], b = hi / d[k];
      if (a > b) std::swap(a, b);
      t0 = std::max(t0, a);
      t1 = std::min(t1, b);
      if (t0 > t1) return false;
    }
    return true;
  };
  int stack[128];  // a median-split tree is at most log2(triangles) deep: far below this
  int top = 0;
  stack[top++] = 0;
  while (top > 0) {
    const Node& node = nodes_[stack[--top]];
    if (!node.box.intersects(reach) || !near_box(node.box)) continue;
    if (node.count > 0) {
      for (int i = node.first; i < node.first + node.count; ++i) {
        const Triangle& t = triangles_[i];
        // Both ends farther than the radius on one side of the triangle's plane: apart.
        const double s0 = t.normal.dot(p0 - t.a), s1 = t.normal.dot(p1 - t.a);
        if ((s0 > radius && s1 > radius) || (s0 < -radius && s1 < -radius)) continue;
        // The segment farther than the radius from the triangle's bounding sphere: apart.
        const double along = std::clamp((t.centre - p0).dot(d) / dd, 0.0, 1.0);
        const double apart = radius + t.reach;
        if ((p0 + along * d - t.centre).squaredNorm() > apart * apart) continue;
        if (segment_triangle_within(p0, p1, t.a, t.b, t.c, r2)) return true;
      }
    } else {
      stack[top++] = node.left;
      stack[top++] = node.right;
    }
  }
  return false;
}

}  // namespace claspplan::robots
