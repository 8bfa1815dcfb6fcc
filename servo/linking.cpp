#include "servo/linking.hpp"

#include <cmath>

#include <Eigen/Geometry>

namespace claspplan::servo {
namespace {

using Eigen::Vector3d;

constexpr double kPi = 3.14159265358979323846;

// |z|² of a solid-angle term below which two of its unit vectors are antipodal: the origin of the
// difference space lies on an edge of the pair's quadrilateral, i.e. the segments touch.
constexpr double kTouch = 1e-20;
// A half solid angle this close to ±π means the origin lies inside the quadrilateral's plane
// region: the segments cross (or pass within ~1e-10 of their size of each other).
constexpr double kCross = 1e-10;

int segment_count(std::size_t points, bool closed) {
  return static_cast<int>(closed ? points : points - 1);
}

[[noreturn]] void throw_touch() {
  throw CurvesIntersect("the curves intersect or touch (the linking integral is undefined)");
}

// Unit vectors from one vertex of the first curve to every vertex of the second, with the
// inverse distances (needed by the gradient).
void unit_row(const Vector3d& from, const Points& to, std::vector<Vector3d>& unit,
              std::vector<double>& inv_norm) {
  for (std::size_t j = 0; j < to.size(); ++j) {
    const Vector3d r = to[j] - from;
    const double norm = r.norm();
    if (!(norm > 0.0)) throw_touch();
    inv_norm[j] = 1.0 / norm;
    unit[j] = r * inv_norm[j];
  }
}

// One spherical-triangle term of the Van Oosterom–Strackee formula: Ω = 2·arg(z) with
// z = (1 + a·b + b·c + c·a) + i a·(b×c). Throws when the segments meet.
struct SolidAngleTerm {
  double x, y;
  SolidAngleTerm(const Vector3d& a, const Vector3d& b, const Vector3d& c, double ab)
      : x(1.0 + ab + b.dot(c) + c.dot(a)), y(a.dot(b.cross(c))) {
    if (x * x + y * y < kTouch || (x < 0.0 && std::abs(y) <= -kCross * x)) throw_touch();
  }
  // dΩ/da = 2(x·∂y/∂a − y·∂x/∂a)/|z|² with ∂y/∂a = b×c and ∂x/∂a = b + c. Ω is cyclic in
  // (a, b, c), so dΩ/db = derivative(c, a) and dΩ/dc = derivative(a, b).
  Vector3d derivative(const Vector3d& b, const Vector3d& c) const {
    return (x * b.cross(c) - y * (b + c)) * (2.0 / (x * x + y * y));
  }
};

// Projects dF/du onto dF/dr for u = r/|r|: (I − u uᵀ) g / |r|.
Vector3d through_normalization(const Vector3d& u, double inv_norm, const Vector3d& g) {
  return (g - u * u.dot(g)) * inv_norm;
}

// The closed-form Gauss sum (eq. 1) over all segment pairs. For the pair p1→p2 of a and p3→p4 of
// b the contribution is [Ω(u13,u24,u14) + Ω(u13,u23,u24)]/(4π) with u_ij = unit(p_j − p_i): the
// signed solid angle of the planar difference quadrilateral {b − a}. That quadrilateral misses
// the origin when the segments are disjoint, so |Ω| < 2π and both terms combine exactly into one
// atan2 of the product of their complex numbers. Unit vectors are computed once per vertex pair,
// a row of b's vertices per vertex of a.
double gauss_sum(const Points& a, bool a_closed, const Points& b, bool b_closed, Points* grad_b) {
  const int n = static_cast<int>(a.size());
  const int m = static_cast<int>(b.size());
  const int segments_a = segment_count(a.size(), a_closed);
  const int segments_b = segment_count(b.size(), b_closed);
  std::vector<Vector3d> row0(m), row1(m);
  std::vector<double> inv0(m), inv1(m);
  if (grad_b) grad_b->assign(m, Vector3d::Zero());

  unit_row(a[0], b, row0, inv0);
  double twice_half_angles = 0.0;
  for (int i = 0; i < segments_a; ++i) {
    unit_row(a[(i + 1) % n], b, row1, inv1);
    for (int j = 0; j < segments_b; ++j) {
      const int j1 = (j + 1 == m) ? 0 : j + 1;
      const Vector3d& u13 = row0[j];
      const Vector3d& u14 = row0[j1];
      const Vector3d& u23 = row1[j];
      const Vector3d& u24 = row1[j1];
      const double d13_24 = u13.dot(u24);
      const SolidAngleTerm t1(u13, u24, u14, d13_24);
      const SolidAngleTerm t2(u13, u23, u24, u13.dot(u23));
      // arg(z1·z2) = Ω_pair / 2, exact because |Ω_pair| < 2π.
      twice_half_angles += std::atan2(t1.x * t2.y + t1.y * t2.x, t1.x * t2.x - t1.y * t2.y);

      if (grad_b) {
        // Ω1 = Ω(u13, u24, u14), Ω2 = Ω(u13, u23, u24); each derivative is cyclic in its triple.
        const Vector3d g13 = t1.derivative(u24, u14) + t2.derivative(u23, u24);
        const Vector3d g24 = t1.derivative(u14, u13) + t2.derivative(u13, u23);
        const Vector3d g14 = t1.derivative(u13, u24);
        const Vector3d g23 = t2.derivative(u24, u13);
        constexpr double s = 1.0 / (4.0 * kPi);
        // r13 = p3 − p1 and r23 = p3 − p2 move with p3 = b[j]; r14, r24 with p4 = b[j1].
        (*grad_b)[j] += s * (through_normalization(u13, inv0[j], g13) +
                             through_normalization(u23, inv1[j], g23));
        (*grad_b)[j1] += s * (through_normalization(u14, inv0[j1], g14) +
                              through_normalization(u24, inv1[j1], g24));
      }
    }
    std::swap(row0, row1);
    std::swap(inv0, inv1);
  }
  return twice_half_angles / (2.0 * kPi);
}

// Sign with a fixed symbolic tie-break: an exact zero counts as positive. Every predicate below
// is evaluated by the same expression wherever it is used, so the tie-break is one consistent
// infinitesimal perturbation and every crossing is counted exactly once.
int sign_of(double v) {
  return v < 0.0 ? -1 : 1;
}

// Orientation of the tetrahedron (p, q, r, s): det[q − p, r − p, s − p].
double orient(const Vector3d& p, const Vector3d& q, const Vector3d& r, const Vector3d& s) {
  return (q - p).dot((r - p).cross(s - p));
}

}  // namespace

void validate_curve(const Points& points, bool closed, const std::string& what) {
  const std::size_t minimum = closed ? 3 : 2;
  if (points.size() < minimum) {
    throw std::invalid_argument(what + ": a " + (closed ? "closed" : "open") +
                                " curve needs at least " + std::to_string(minimum) +
                                " points, got " + std::to_string(points.size()));
  }
  for (std::size_t i = 0; i < points.size(); ++i) {
    if (!points[i].allFinite()) {
      throw std::invalid_argument(what + ": point " + std::to_string(i + 1) +
                                  " has a NaN or infinite coordinate");
    }
  }
  const int segments = segment_count(points.size(), closed);
  for (int i = 0; i < segments; ++i) {
    const std::size_t next = (i + 1) % points.size();
    if (points[i] == points[next]) {
      throw std::invalid_argument(what + ": zero-length segment between points " +
                                  std::to_string(i + 1) + " and " + std::to_string(next + 1));
    }
  }
}

double gauss_linking(const Points& a, bool a_closed, const Points& b, bool b_closed) {
  validate_curve(a, a_closed, "first curve");
  validate_curve(b, b_closed, "second curve");
  return gauss_sum(a, a_closed, b, b_closed, nullptr);
}

double gauss_linking_gradient(const Points& a, bool a_closed, const Points& b, bool b_closed,
                              Points& grad_b) {
  validate_curve(a, a_closed, "first curve");
  validate_curve(b, b_closed, "second curve");
  return gauss_sum(a, a_closed, b, b_closed, &grad_b);
}

int linking_number(const Points& a, const Points& b) {
  const int n = static_cast<int>(a.size());
  const int m = static_cast<int>(b.size());
  if (n < 2 || m < 3) return 0;
  const Vector3d& apex = b[0];
  std::vector<int> side(n);
  int count = 0;
  // Fan triangle k = (b0, b_k, b_{k+1}); its normal follows b's direction by the right hand.
  for (int k = 1; k + 1 < m; ++k) {
    const Vector3d normal = (b[k] - apex).cross(b[k + 1] - apex);
    for (int i = 0; i < n; ++i) side[i] = sign_of(normal.dot(a[i] - apex));
    for (int i = 0; i < n; ++i) {
      const int i1 = (i + 1 == n) ? 0 : i + 1;
      if (side[i] == side[i1]) continue;
      // The line a_i → a_i1 passes through the triangle iff the three edge orientations agree.
      // The fan edge (b0, b_k) is shared with triangle k−1, which sees it reversed.
      const int e0 = sign_of(orient(a[i], a[i1], apex, b[k]));
      const int e1 = sign_of(orient(a[i], a[i1], b[k], b[k + 1]));
      const int e2 = -sign_of(orient(a[i], a[i1], apex, b[k + 1]));
      if (e0 == e1 && e1 == e2) count += side[i1];
    }
  }
  return count;
}

VirtualLinking virtual_linking(const Points& loop, const Points& finger) {
  VirtualLinking v;
  if (finger.size() < 2) return v;
  double length = 0.0;
  for (std::size_t i = 0; i + 1 < finger.size(); ++i) length += (finger[i + 1] - finger[i]).norm();
  v.cord = (finger.back() - finger.front()).norm();
  v.closed_length = length + v.cord;
  if (!(v.closed_length > 0.0)) return v;
  v.closed_linking = linking_number(loop, finger);
  v.value = v.closure() * v.closed_linking;
  return v;
}

void virtual_linking_gradient(const VirtualLinking& vlk, const Points& finger, Points& grad) {
  grad.assign(finger.size(), Vector3d::Zero());
  if (vlk.closed_linking == 0 || finger.size() < 2 || !(vlk.closed_length > 0.0)) return;
  // VLk = Lk (1 − δ/L) with L = Σ|f_{k+1} − f_k| + δ:
  // ∇VLk = −Lk (L ∇δ − δ ∇L)/L² = −Lk ((L − δ) ∇δ − δ ∇(L − δ))/L².
  const double L = vlk.closed_length;
  const double delta = vlk.cord;
  const double scale = -vlk.closed_linking / (L * L);
  // Curve part: each segment pulls its two ends along its unit direction.
  for (std::size_t k = 0; k + 1 < finger.size(); ++k) {
    const Vector3d e = finger[k + 1] - finger[k];
    const double len = e.norm();
    if (len > 0.0) {
      const Vector3d u = e / len;
      grad[k] += scale * delta * u;  // −δ·∂(L−δ)/∂f_k = +δ u
      grad[k + 1] -= scale * delta * u;
    }
  }
  // Cord part.
  if (delta > 0.0) {
    const Vector3d u = (finger.back() - finger.front()) / delta;
    grad.front() -= scale * (L - delta) * u;
    grad.back() += scale * (L - delta) * u;
  }
}

}  // namespace claspplan::servo
