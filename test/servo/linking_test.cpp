// The linking core: Gauss linking integral (eq. 1), exact linking number, virtual linking (eq. 2)
// and their gradients.
#include "servo/linking.hpp"

#include <cmath>
#include <limits>
#include <random>

#include <gtest/gtest.h>

#include "test/support/curves.hpp"

namespace claspplan::test {
namespace {

using Eigen::Vector3d;
using servo::gauss_linking;
using servo::linking_number;

// Lk of two closed curves both ways: the Gauss sum and the crossing count, which must agree.
int checked_linking(const Curve& a, const Curve& b) {
  const double gauss = gauss_linking(a, true, b, true);
  const int crossings = linking_number(a, b);
  EXPECT_NEAR(gauss, crossings, 1e-9) << "Gauss sum and crossing count disagree";
  EXPECT_EQ(linking_number(b, a), crossings) << "Lk must be symmetric";
  return crossings;
}

const Curve kSquare = {{0, 0, 0}, {2, 0, 0}, {2, 2, 0}, {0, 2, 0}};
// Pierces the square's disc at (1, 1) going +z, then returns outside it at x = 3.
const Curve kPiercing = {{1, 1, -1}, {1, 1, 1}, {3, 1, 1}, {3, 1, -1}};

TEST(GaussLinking, RightHandRuleGivesPlusOne) {
  EXPECT_EQ(checked_linking(kSquare, kPiercing), 1);
  EXPECT_EQ(checked_linking(reversed(kSquare), kPiercing), -1);
  EXPECT_EQ(checked_linking(kSquare, reversed(kPiercing)), -1);
  EXPECT_EQ(checked_linking(reversed(kSquare), reversed(kPiercing)), 1);
}

TEST(GaussLinking, TorusLinksT2_2kLinkKTimes) {
  for (int k = 1; k <= 5; ++k) {
    const Curve a = torus_link_component(k, 0, 60 * k);
    const Curve b = torus_link_component(k, 1, 60 * k);
    EXPECT_EQ(std::abs(checked_linking(a, b)), k) << "T(2," << 2 * k << ")";
  }
}

TEST(GaussLinking, WhiteheadLinkHasLinkingZero) {
  // σ1² σ2⁻¹ σ1 σ2⁻¹: an alternating reduced 5-crossing diagram of two components, the
  // Whitehead link (nontrivial, yet Lk = 0).
  const std::vector<Curve> link = braid_closure(3, {1, 1, -2, 1, -2});
  ASSERT_EQ(link.size(), 2u);
  EXPECT_EQ(checked_linking(link[0], link[1]), 0);
  // The same construction does see linking: σ1² on two strands is the Hopf link.
  const std::vector<Curve> hopf = braid_closure(2, {1, 1});
  ASSERT_EQ(hopf.size(), 2u);
  EXPECT_EQ(std::abs(checked_linking(hopf[0], hopf[1])), 1);
}

TEST(GaussLinking, FarApartRingsHaveLinkingZero) {
  const Curve a = circle({0, 0, 0}, 1.0, Vector3d::UnitX(), Vector3d::UnitY(), 40);
  const Curve b = circle({5, 0, 0}, 1.0, Vector3d::UnitX(), Vector3d::UnitZ(), 40);
  EXPECT_EQ(checked_linking(a, b), 0);
  EXPECT_NEAR(gauss_linking(a, true, b, true), 0.0, 1e-12);
}

TEST(GaussLinking, InvariantUnderRigidMotionScalingAndSubdivision) {
  std::mt19937_64 rng(7);
  const Curve a = torus_link_component(3, 0, 90);
  const Curve b = torus_link_component(3, 1, 90);
  const Curve open_b(b.begin(), b.begin() + 40);
  const double lk = gauss_linking(a, true, b, true);
  const double open = gauss_linking(a, true, open_b, false);
  for (double scale : {1e-3, 0.37, 1.0, 25.0, 1e3}) {
    const Eigen::Isometry3d T = random_rigid_motion(rng);
    const Curve ta = transformed(a, T, scale), tb = transformed(b, T, scale);
    const Curve tob = transformed(open_b, T, scale);
    EXPECT_NEAR(gauss_linking(ta, true, tb, true), lk, 1e-9) << "scale " << scale;
    EXPECT_EQ(linking_number(ta, tb), std::lround(lk));
    // The open-curve integral is not a topological invariant, but it is a geometric one.
    EXPECT_NEAR(gauss_linking(ta, true, tob, false), open, 1e-9) << "scale " << scale;
  }
  const Curve sa = subdivided(a, true, 3), sb = subdivided(b, true, 2);
  EXPECT_NEAR(gauss_linking(sa, true, sb, true), lk, 1e-9);
  EXPECT_EQ(linking_number(sa, sb), std::lround(lk));
  EXPECT_NEAR(gauss_linking(sa, true, subdivided(open_b, false, 4), false), open, 1e-9);
}

// Gauss–Legendre nodes and weights on [0, 1].
void gauss_legendre(int n, std::vector<double>& x, std::vector<double>& w) {
  x.assign(n, 0.0);
  w.assign(n, 0.0);
  for (int i = 0; i < n; ++i) {
    double z = std::cos(kPi * (i + 0.75) / (n + 0.5)), dp = 0.0;
    for (int it = 0; it < 100; ++it) {
      double p0 = 1.0, p1 = 0.0;
      for (int k = 1; k <= n; ++k) {
        const double p2 = p1;
        p1 = p0;
        p0 = ((2.0 * k - 1.0) * z * p1 - (k - 1.0) * p2) / k;
      }
      dp = n * (z * p0 - p1) / (z * z - 1.0);
      const double dz = p0 / dp;
      z -= dz;
      if (std::abs(dz) < 1e-15) break;
    }
    x[i] = 0.5 * (1.0 - z);
    w[i] = 1.0 / ((1.0 - z * z) * dp * dp);
  }
}

// Eq. 1 by brute-force composite Gauss–Legendre quadrature over every segment pair.
double quadrature_linking(const Curve& a, bool a_closed, const Curve& b, bool b_closed) {
  std::vector<double> x, w;
  gauss_legendre(12, x, w);
  const int panels = 12;
  std::vector<std::pair<Vector3d, Vector3d>> qa, qb;  // (point, weighted tangent)
  auto nodes = [&](const Curve& c, bool closed, auto& out) {
    const std::size_t segments = closed ? c.size() : c.size() - 1;
    for (std::size_t i = 0; i < segments; ++i) {
      const Vector3d p = c[i], d = c[(i + 1) % c.size()] - c[i];
      for (int k = 0; k < panels; ++k) {
        for (std::size_t g = 0; g < x.size(); ++g) {
          const double s = (k + x[g]) / panels;
          out.emplace_back(p + s * d, d * (w[g] / panels));
        }
      }
    }
  };
  nodes(a, a_closed, qa);
  nodes(b, b_closed, qb);
  double sum = 0.0;
  for (const auto& [pa, ta] : qa) {
    for (const auto& [pb, tb] : qb) {
      const Vector3d r = pa - pb;
      sum += r.dot(ta.cross(tb)) / std::pow(r.norm(), 3);
    }
  }
  return sum / (4.0 * kPi);
}

double segment_distance(const Vector3d& p, const Vector3d& q, const Vector3d& r,
                        const Vector3d& s) {
  // Dense sampling is enough to keep random test curves apart.
  double best = std::numeric_limits<double>::infinity();
  for (int i = 0; i <= 50; ++i) {
    for (int j = 0; j <= 50; ++j) {
      best = std::min(best, ((p + (q - p) * (i / 50.0)) - (r + (s - r) * (j / 50.0))).norm());
    }
  }
  return best;
}

Curve random_polyline(std::mt19937_64& rng, int n, const Vector3d& offset) {
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  Curve c;
  for (int i = 0; i < n; ++i) c.push_back(offset + Vector3d(u(rng), u(rng), u(rng)));
  return c;
}

TEST(GaussLinking, OpenCurvesAgreeWithQuadratureOfEquation1) {
  std::mt19937_64 rng(42);
  int checked = 0;
  while (checked < 12) {
    const Curve a = random_polyline(rng, 5, Vector3d::Zero());
    const Curve b = random_polyline(rng, 4, Vector3d(0.4, 0.3, 0.8));
    double gap = std::numeric_limits<double>::infinity();
    for (std::size_t i = 0; i < a.size(); ++i)
      for (std::size_t j = 0; j + 1 < b.size(); ++j)
        gap = std::min(gap, segment_distance(a[i], a[(i + 1) % a.size()], b[j], b[j + 1]));
    if (gap < 0.3) continue;  // quadrature needs room; the closed form does not
    const bool a_closed = checked % 2 == 0;
    EXPECT_NEAR(gauss_linking(a, a_closed, b, false), quadrature_linking(a, a_closed, b, false),
                1e-6);
    ++checked;
  }
}

// A ring of radius 0.1 in the xy-plane and a 9-point finger arc of radius 0.04 around its strand
// at (0.1, 0, 0), opened by `span` radians (the demo's example).
Curve ring() {
  return circle({0, 0, 0}, 0.1, Vector3d::UnitX(), Vector3d::UnitY(), 64);
}
Curve finger_arc(double span, const Vector3d& shift = Vector3d::Zero()) {
  Curve c;
  for (int i = 0; i < 9; ++i) {
    const double t = kPi - span / 2.0 + span * i / 8.0;
    c.push_back(shift + Vector3d(0.1 + 0.04 * std::cos(t), 0.0, 0.04 * std::sin(t)));
  }
  return c;
}

TEST(VirtualLinking, ZeroWhileTheLoopDoesNotPassThroughTheVirtualLoop) {
  for (double deg : {40.0, 90.0, 150.0, 175.0}) {
    const servo::VirtualLinking v = servo::virtual_linking(ring(), finger_arc(deg * kPi / 180));
    EXPECT_EQ(v.closed_linking, 0) << deg;
    EXPECT_EQ(v.value, 0.0) << deg;
  }
  // A nearly closed hand far from the loop links nothing either.
  const servo::VirtualLinking far =
      servo::virtual_linking(ring(), finger_arc(6.0, Vector3d(0.0, 0.5, 0.0)));
  EXPECT_EQ(far.value, 0.0);
}

TEST(VirtualLinking, TendsToLkAsTheCordShrinks) {
  double previous_gap = 1.0;
  for (double gap_deg : {40.0, 10.0, 1.0, 0.01}) {
    const Curve finger = finger_arc((360.0 - gap_deg) * kPi / 180);
    const servo::VirtualLinking v = servo::virtual_linking(ring(), finger);
    ASSERT_EQ(std::abs(v.closed_linking), 1);
    const double gap = std::abs(v.value - v.closed_linking);
    EXPECT_NEAR(gap, v.cord / v.closed_length, 1e-12);
    EXPECT_LT(gap, previous_gap);
    previous_gap = gap;
  }
  EXPECT_LT(previous_gap, 1e-4);
}

TEST(VirtualLinking, GrowsAsTheFingerCurveClosesAroundTheLoop) {
  double previous = 0.0;
  for (double deg = 185.0; deg <= 355.0; deg += 10.0) {
    const double v = std::abs(servo::virtual_linking(ring(), finger_arc(deg * kPi / 180)).value);
    EXPECT_GT(v, previous) << "span " << deg;
    previous = v;
  }
  EXPECT_GT(previous, 0.9);
}

// Central differences of f with respect to every coordinate of every vertex of `c`.
template <class F>
std::vector<Vector3d> numeric_gradient(const Curve& c, F f, double h = 1e-6) {
  std::vector<Vector3d> g(c.size(), Vector3d::Zero());
  for (std::size_t i = 0; i < c.size(); ++i) {
    for (int k = 0; k < 3; ++k) {
      Curve plus = c, minus = c;
      plus[i][k] += h;
      minus[i][k] -= h;
      g[i][k] = (f(plus) - f(minus)) / (2.0 * h);
    }
  }
  return g;
}

void expect_gradients_match(const std::vector<Vector3d>& analytic,
                            const std::vector<Vector3d>& numeric) {
  ASSERT_EQ(analytic.size(), numeric.size());
  for (std::size_t i = 0; i < analytic.size(); ++i) {
    for (int k = 0; k < 3; ++k) {
      const double a = analytic[i][k], n = numeric[i][k];
      EXPECT_TRUE(std::abs(a - n) <= 1e-9 || std::abs(a - n) <= 1e-6 * std::abs(n))
          << "vertex " << i << " coordinate " << k << ": analytic " << a << " numeric " << n;
    }
  }
}

TEST(Gradients, OpenGaussIntegralMatchesCentralDifferences) {
  std::mt19937_64 rng(3);
  const Curve loop = ring();
  for (int trial = 0; trial < 6; ++trial) {
    std::normal_distribution<double> jitter(0.0, 0.004);
    Curve finger = finger_arc((150.0 + 35.0 * trial) * kPi / 180);
    for (auto& p : finger) p += Vector3d(jitter(rng), jitter(rng), jitter(rng));
    std::vector<Vector3d> grad;
    const double value = servo::gauss_linking_gradient(loop, true, finger, false, grad);
    EXPECT_DOUBLE_EQ(value, gauss_linking(loop, true, finger, false));
    expect_gradients_match(grad, numeric_gradient(finger, [&](const Curve& f) {
                             return gauss_linking(loop, true, f, false);
                           }));
  }
  // Random open pairs in general position, both curves open.
  for (int trial = 0; trial < 6; ++trial) {
    const Curve a = random_polyline(rng, 6, Vector3d::Zero());
    const Curve b = random_polyline(rng, 5, Vector3d(0.2, 0.1, 0.5));
    std::vector<Vector3d> grad;
    servo::gauss_linking_gradient(a, false, b, false, grad);
    expect_gradients_match(grad, numeric_gradient(b, [&](const Curve& f) {
                             return gauss_linking(a, false, f, false);
                           }));
  }
}

TEST(Gradients, VirtualLinkingMatchesCentralDifferences) {
  std::mt19937_64 rng(5);
  const Curve loop = ring();
  for (double deg : {200.0, 260.0, 330.0}) {
    std::normal_distribution<double> jitter(0.0, 0.003);
    Curve finger = finger_arc(deg * kPi / 180);
    for (auto& p : finger) p += Vector3d(jitter(rng), jitter(rng), jitter(rng));
    const servo::VirtualLinking v = servo::virtual_linking(loop, finger);
    ASSERT_NE(v.closed_linking, 0);
    std::vector<Vector3d> grad;
    servo::virtual_linking_gradient(v, finger, grad);
    expect_gradients_match(grad, numeric_gradient(finger, [&](const Curve& f) {
                             return servo::virtual_linking(loop, f).value;
                           }));
  }
  // Unlinked: the gradient is exactly zero.
  const servo::VirtualLinking unlinked = servo::virtual_linking(loop, finger_arc(1.0));
  std::vector<Vector3d> grad;
  servo::virtual_linking_gradient(unlinked, finger_arc(1.0), grad);
  for (const auto& g : grad) EXPECT_EQ(g.norm(), 0.0);
}

TEST(BadInput, CurvesAreValidated) {
  const double nan = std::numeric_limits<double>::quiet_NaN();
  const double inf = std::numeric_limits<double>::infinity();
  EXPECT_THROW(servo::validate_curve({{0, 0, 0}}, false, "c"), std::invalid_argument);
  EXPECT_THROW(servo::validate_curve({{0, 0, 0}, {1, 0, 0}}, true, "c"), std::invalid_argument);
  EXPECT_THROW(servo::validate_curve({{0, 0, 0}, {nan, 0, 0}}, false, "c"), std::invalid_argument);
  EXPECT_THROW(servo::validate_curve({{0, 0, 0}, {0, inf, 0}}, false, "c"), std::invalid_argument);
  EXPECT_THROW(servo::validate_curve({{0, 0, 0}, {1, 0, 0}, {1, 0, 0}}, false, "c"),
               std::invalid_argument);
  // The closing segment of a closed curve counts too.
  EXPECT_THROW(servo::validate_curve({{0, 0, 0}, {1, 0, 0}, {0, 0, 0}}, true, "c"),
               std::invalid_argument);
  EXPECT_NO_THROW(servo::validate_curve({{0, 0, 0}, {1, 0, 0}, {0, 1, 0}}, true, "c"));
  EXPECT_THROW(gauss_linking(kSquare, true, {{0, 0, 0}}, false), std::invalid_argument);
}

TEST(BadInput, IntersectingCurvesAreReportedNeverNaN) {
  // A vertex of B on an edge of A.
  const Curve touching = {{1, 0, 0}, {1, -1, 1}, {1, -1, -1}};
  EXPECT_THROW(gauss_linking(kSquare, true, touching, true), servo::CurvesIntersect);
  // Coplanar edges crossing in their interiors.
  const Curve crossing = {{1, -1, 0}, {1, 1, 0}, {3, 1, 0}, {3, -1, 0}};
  EXPECT_THROW(gauss_linking(kSquare, true, crossing, true), servo::CurvesIntersect);
  // A shared vertex.
  const Curve sharing = {{2, 2, 0}, {3, 3, 1}, {3, 3, -1}};
  EXPECT_THROW(gauss_linking(kSquare, true, sharing, true), servo::CurvesIntersect);
  // Nearly touching curves still give finite, integer-valued answers.
  for (double eps : {1e-3, 1e-6, 1e-8}) {
    const Curve near = {{1, 1, -1}, {1, 1, 1}, {2 + eps, 1, 1}, {2 + eps, 1, -1}};
    const double lk = gauss_linking(kSquare, true, near, true);
    EXPECT_TRUE(std::isfinite(lk));
    EXPECT_NEAR(lk, 1.0, 1e-6) << eps;
    EXPECT_EQ(linking_number(kSquare, near), 1);
  }
}

TEST(LinkingNumber, DegenerateTouchesAreCountedOnce) {
  // The piercing segment passes exactly through a vertex of the fan (A's first vertex is the
  // apex; its diagonal (0,0)→(2,2) is a shared fan edge).
  const Curve through_diagonal = {{1, 1, -1}, {1, 1, 1}, {-3, 1, 1}, {-3, 1, -1}};
  EXPECT_EQ(std::abs(linking_number(kSquare, through_diagonal)), 1);
  EXPECT_EQ(std::abs(linking_number(through_diagonal, kSquare)), 1);
  // A vertex of the loop exactly in the fan's plane, inside the triangle.
  const Curve vertex_in_plane = {
      {1.5, 0.5, -1}, {1.5, 0.5, 0}, {1.5, 0.5, 1}, {3, 0.5, 1}, {3, 0.5, -1}};
  EXPECT_EQ(std::abs(linking_number(kSquare, vertex_in_plane)), 1);
  // Touching the plane from one side and going back does not link.
  const Curve kiss = {{1.5, 0.5, -1}, {1.5, 0.5, 0}, {1.6, 0.5, -1}};
  EXPECT_EQ(linking_number(kSquare, kiss), 0);
}

}  // namespace
}  // namespace claspplan::test
