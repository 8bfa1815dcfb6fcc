// The shortest H1 basis: hand-made complexes with known answers, and the fast path (limited
// roots, bounded Dijkstra, levels) against the all-roots greedy on many random complexes.
#include "perception/homology.hpp"

#include <algorithm>
#include <cmath>
#include <random>

#include <gtest/gtest.h>

#include "perception/cloud_filters.hpp"
#include "perception/complex.hpp"

namespace claspplan::perception {
namespace {

// A complex from explicit edges and triangles (triangles given by vertex triples).
SimplicialComplex make_complex(const PointCloud& pts, const std::vector<std::array<int, 2>>& edges,
                               const std::vector<std::array<int, 3>>& tris) {
  SimplicialComplex k;
  k.points = pts;
  k.d = 1.0;
  for (auto e : edges) {
    if (e[0] > e[1]) std::swap(e[0], e[1]);
    k.edges.push_back(e);
    k.edge_length.push_back((pts[e[0]] - pts[e[1]]).norm());
  }
  auto id = [&](int a, int b) {
    if (a > b) std::swap(a, b);
    for (size_t i = 0; i < k.edges.size(); ++i)
      if (k.edges[i][0] == a && k.edges[i][1] == b) return static_cast<int>(i);
    ADD_FAILURE() << "missing edge";
    return 0;
  };
  for (const auto& t : tris)
    k.triangles.push_back({id(t[0], t[1]), id(t[1], t[2]), id(t[0], t[2])});
  return k;
}

TEST(Homology, SmallComplexes) {
  // A square with one diagonal: one triangle filled -> one loop? No: the filled triangle kills the
  // cycle through the diagonal; the other triangle is empty: beta1 = 1, the loop has length
  // 2+sqrt2.
  const PointCloud sq = {{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0}};
  const auto k = make_complex(sq, {{0, 1}, {1, 2}, {2, 3}, {3, 0}, {0, 2}}, {{0, 1, 2}});
  EXPECT_EQ(betti_1(k), 1);
  const HomologyBasis b = shortest_homology_basis(k);
  ASSERT_EQ(b.cycles.size(), 1u);
  EXPECT_NEAR(b.cycles[0].length, 2 + std::sqrt(2.0), 1e-12);
  EXPECT_EQ(b.cycles[0].vertices.size(), 3u);
  // Both triangles filled: a disc.
  EXPECT_EQ(
      betti_1(make_complex(sq, {{0, 1}, {1, 2}, {2, 3}, {3, 0}, {0, 2}}, {{0, 1, 2}, {0, 2, 3}})),
      0);
  // Two disjoint empty triangles and an isolated point: beta1 = 2, one loop per component.
  PointCloud two = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {5, 0, 0}, {7, 0, 0}, {5, 2, 0}, {9, 9, 9}};
  const auto k2 = make_complex(two, {{0, 1}, {1, 2}, {0, 2}, {3, 4}, {4, 5}, {3, 5}}, {});
  const HomologyBasis b2 = shortest_homology_basis(k2);
  ASSERT_EQ(b2.beta1, 2);
  EXPECT_NEAR(b2.cycles[0].length, 2 + std::sqrt(2.0), 1e-12);
  EXPECT_NEAR(b2.cycles[1].length, 4 + 2 * std::sqrt(2.0), 1e-12);
  // A hollow tetrahedron (a sphere): beta1 = 0.
  const PointCloud tet = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {0, 0, 1}};
  EXPECT_EQ(betti_1(make_complex(tet, {{0, 1}, {0, 2}, {0, 3}, {1, 2}, {1, 3}, {2, 3}},
                                 {{0, 1, 2}, {0, 1, 3}, {0, 2, 3}, {1, 2, 3}})),
            0);
}

TEST(Homology, LoopsAreClosedSimplePathsOfTheComplex) {
  // A ring of 12 points around a filled-in centre-less annulus: one loop, the inner circle.
  PointCloud pts;
  std::vector<std::array<int, 2>> edges;
  std::vector<std::array<int, 3>> tris;
  const int n = 12;
  for (int i = 0; i < n; ++i) {
    const double a = 2 * M_PI * i / n;
    pts.emplace_back(std::cos(a), std::sin(a), 0);          // inner
    pts.emplace_back(2 * std::cos(a), 2 * std::sin(a), 0);  // outer
  }
  for (int i = 0; i < n; ++i) {
    const int a = 2 * i, b = 2 * i + 1, c = 2 * ((i + 1) % n), d = 2 * ((i + 1) % n) + 1;
    edges.push_back({a, b});
    edges.push_back({a, c});
    edges.push_back({b, d});
    edges.push_back({b, c});
    tris.push_back({a, b, c});
    tris.push_back({b, c, d});
  }
  const auto k = make_complex(pts, edges, tris);
  const HomologyBasis basis = shortest_homology_basis(k);
  ASSERT_EQ(basis.beta1, 1);
  const BasisCycle& c = basis.cycles[0];
  EXPECT_NEAR(c.length, n * 2 * std::sin(M_PI / n), 1e-12);  // the inner 12-gon
  ASSERT_EQ(c.vertices.size(), c.edges.size());
  for (size_t i = 0; i < c.edges.size(); ++i) {
    const auto& e = k.edges[c.edges[i]];
    const int a = c.vertices[i], b = c.vertices[(i + 1) % c.vertices.size()];
    EXPECT_TRUE((e[0] == a && e[1] == b) || (e[0] == b && e[1] == a));
  }
  std::vector<int> v = c.vertices;
  std::sort(v.begin(), v.end());
  EXPECT_EQ(std::unique(v.begin(), v.end()), v.end());  // simple
}

// Random point sets (in a cube, on a noisy torus, on two linked rings) with d from 1.2 to 3 times
// their spacing: many loops of all sizes. The fast path must give the all-roots basis lengths.
TEST(Homology, FastPathEqualsAllRootsOnRandomComplexes) {
  std::mt19937_64 rng(2024);
  std::uniform_real_distribution<double> uni(0.0, 1.0);
  std::normal_distribution<double> gauss(0.0, 1.0);
  int compared = 0, loops = 0;
  for (int trial = 0; trial < 90; ++trial) {
    const int n = 60 + static_cast<int>(uni(rng) * 200);
    PointCloud pts;
    const int kind = trial % 3;
    for (int i = 0; i < n; ++i) {
      if (kind == 0) {
        pts.emplace_back(uni(rng), uni(rng), uni(rng));
      } else {
        const double u = 2 * M_PI * uni(rng), v = 2 * M_PI * uni(rng);
        const double R = 1.0, r = 0.35;
        Eigen::Vector3d p((R + r * std::cos(v)) * std::cos(u), (R + r * std::cos(v)) * std::sin(u),
                          r * std::sin(v));
        if (kind == 2 && i % 2) p = Eigen::Vector3d(p.x() + 1.0, p.z(), p.y());  // a linked ring
        pts.push_back(p + 0.02 * Eigen::Vector3d(gauss(rng), gauss(rng), gauss(rng)));
      }
    }
    const DelaunayGraph dg = delaunay_3d(pts);
    const double d = (1.2 + 1.8 * uni(rng)) * mean_spacing(pts);
    const SimplicialComplex k = build_complex(dg, d);
    HomologyOptions all;
    all.fast = false;
    const HomologyBasis fast = shortest_homology_basis(k);
    const HomologyBasis ref = shortest_homology_basis(k, all);
    ASSERT_EQ(fast.beta1, ref.beta1);
    ASSERT_EQ(fast.beta1, betti_1(k));
    ASSERT_EQ(fast.cycles.size(), ref.cycles.size());
    for (size_t i = 0; i < ref.cycles.size(); ++i)
      ASSERT_NEAR(fast.cycles[i].length, ref.cycles[i].length, 1e-9)
          << "trial " << trial << " loop " << i << " of " << ref.beta1;
    if (ref.beta1 > 0) ++compared;
    loops += ref.beta1;
    EXPECT_LE(fast.roots, ref.roots);
  }
  EXPECT_GT(compared, 60);
  EXPECT_GT(loops, 500);
}

// The loops that persist from K_d to K_d': the fast path, the all-roots search and one thread give
// the same lengths (the fast path and the thread count the same loops); none of them bounds in
// K_d'; and there are never more than the K_d basis loops that do not bound there.
TEST(Homology, PersistentBasisOnRandomComplexes) {
  std::mt19937_64 rng(2025);
  std::uniform_real_distribution<double> uni(0.0, 1.0);
  std::normal_distribution<double> gauss(0.0, 1.0);
  int with_loops = 0, fewer = 0;
  for (int trial = 0; trial < 60; ++trial) {
    const int n = 150 + static_cast<int>(uni(rng) * 250);
    PointCloud pts;
    for (int i = 0; i < n; ++i) {
      const double u = 2 * M_PI * uni(rng), v = 2 * M_PI * uni(rng);
      Eigen::Vector3d p((1.0 + 0.35 * std::cos(v)) * std::cos(u),
                        (1.0 + 0.35 * std::cos(v)) * std::sin(u), 0.35 * std::sin(v));
      if (trial % 2 && i % 2) p = Eigen::Vector3d(p.x() + 1.0, p.z(), p.y());  // a linked ring
      pts.push_back(p + 0.01 * Eigen::Vector3d(gauss(rng), gauss(rng), gauss(rng)));
    }
    const DelaunayGraph dg = delaunay_3d(pts);
    const double d = (2.0 + 1.5 * uni(rng)) * mean_spacing(pts);
    const SimplicialComplex k = build_complex(dg, d),
                            larger = build_complex(dg, d * (1.2 + uni(rng)));
    HomologyOptions all, one;
    all.fast = false;
    one.threads = 1;
    const HomologyBasis fast = persistent_homology_basis(k, larger);
    const HomologyBasis ref = persistent_homology_basis(k, larger, all);
    const HomologyBasis single = persistent_homology_basis(k, larger, one);
    ASSERT_EQ(fast.beta1, betti_1(k));
    ASSERT_EQ(fast.cycles.size(), ref.cycles.size()) << "trial " << trial;
    ASSERT_EQ(fast.cycles.size(), single.cycles.size());
    std::vector<std::vector<int>> cycles;
    for (size_t i = 0; i < ref.cycles.size(); ++i) {
      ASSERT_NEAR(fast.cycles[i].length, ref.cycles[i].length, 1e-9) << "trial " << trial;
      ASSERT_EQ(fast.cycles[i].vertices, single.cycles[i].vertices) << "trial " << trial;
      cycles.push_back(fast.cycles[i].vertices);
    }
    for (bool bounds : bounds_in(larger, cycles)) EXPECT_FALSE(bounds) << "trial " << trial;
    const HomologyBasis basis = shortest_homology_basis(k);
    std::vector<std::vector<int>> basis_cycles;
    for (const auto& c : basis.cycles) basis_cycles.push_back(c.vertices);
    const std::vector<bool> fill = bounds_in(larger, basis_cycles);
    const size_t stay = static_cast<size_t>(std::count(fill.begin(), fill.end(), false));
    EXPECT_LE(fast.cycles.size(), stay) << "trial " << trial;
    EXPECT_EQ(fast.cycles.empty(), stay == 0) << "trial " << trial;
    with_loops += !fast.cycles.empty();
    fewer += fast.cycles.size() < static_cast<size_t>(fast.beta1);
  }
  EXPECT_GT(with_loops, 30);
  EXPECT_GT(fewer, 20);  // loops did fill in
}

// A component large enough that the re-gauging grows its four trees on several threads: the same
// loops as on one thread.
TEST(Homology, PersistentBasisOfALargeComponentOnAnyThreadCount) {
  std::mt19937_64 rng(7);
  std::uniform_real_distribution<double> uni(0.0, 1.0);
  PointCloud pts;
  for (int i = 0; i < 3000; ++i) {
    const double u = 2 * M_PI * uni(rng), v = 2 * M_PI * uni(rng);
    pts.emplace_back((1.0 + 0.35 * std::cos(v)) * std::cos(u),
                     (1.0 + 0.35 * std::cos(v)) * std::sin(u), 0.35 * std::sin(v));
  }
  const DelaunayGraph dg = delaunay_3d(pts);
  const double d = 3.0 * mean_spacing(pts);
  const SimplicialComplex k = build_complex(dg, d), larger = build_complex(dg, 0.3);
  HomologyOptions one, two;
  one.threads = 1;
  two.threads = 2;
  const HomologyBasis a = persistent_homology_basis(k, larger, one);
  const HomologyBasis b = persistent_homology_basis(k, larger, two);
  ASSERT_EQ(a.cycles.size(), 2u);  // the torus's two loops
  ASSERT_EQ(b.cycles.size(), a.cycles.size());
  for (size_t i = 0; i < a.cycles.size(); ++i)
    EXPECT_EQ(a.cycles[i].vertices, b.cycles[i].vertices);
  EXPECT_EQ(a.support_edges, b.support_edges);
}

// The reduction skips each tetrahedron's last face (its boundary is the sum of the other three):
// the same loops, classes and persistence verdicts as without the tetrahedra, on thick complexes
// (d up to 4 times the spacing) where many faces are skipped.
TEST(Homology, TetrahedraSkipOnlyDependentColumns) {
  std::mt19937_64 rng(7);
  std::uniform_real_distribution<double> uni(0.0, 1.0);
  int with_tetrahedra = 0;
  for (int trial = 0; trial < 30; ++trial) {
    PointCloud pts;
    for (int i = 0; i < 150; ++i) {
      const double u = 2 * M_PI * uni(rng), v = 2 * M_PI * uni(rng), r = 0.35 * uni(rng);
      pts.emplace_back((1.0 + r * std::cos(v)) * std::cos(u), (1.0 + r * std::cos(v)) * std::sin(u),
                       r * std::sin(v));  // a solid torus: tetrahedra everywhere inside
    }
    const DelaunayGraph dg = delaunay_3d(pts);
    const double s = mean_spacing(pts);
    const SimplicialComplex k = build_complex(dg, (1.5 + 2.5 * uni(rng)) * s);
    SimplicialComplex bare = k;
    bare.tetrahedra.clear();
    with_tetrahedra += !k.tetrahedra.empty();
    const HomologyBasis a = shortest_homology_basis(k), b = shortest_homology_basis(bare);
    ASSERT_EQ(a.beta1, b.beta1) << "trial " << trial;
    ASSERT_EQ(a.cycles.size(), b.cycles.size());
    std::vector<std::vector<int>> cycles;
    for (size_t i = 0; i < a.cycles.size(); ++i) {
      ASSERT_EQ(a.cycles[i].vertices, b.cycles[i].vertices) << "trial " << trial;
      cycles.push_back(a.cycles[i].vertices);
    }
    const SimplicialComplex larger = build_complex(dg, 1.5 * k.d);
    SimplicialComplex larger_bare = larger;
    larger_bare.tetrahedra.clear();
    EXPECT_EQ(bounds_in(larger, cycles), bounds_in(larger_bare, cycles)) << "trial " << trial;
  }
  EXPECT_GT(with_tetrahedra, 20);
}

TEST(Homology, TooManyLoopsIsAnError) {
  PointCloud pts;
  std::mt19937_64 rng(5);
  std::uniform_real_distribution<double> uni(0.0, 1.0);
  for (int i = 0; i < 400; ++i) pts.emplace_back(uni(rng), uni(rng), uni(rng));
  const SimplicialComplex k = build_complex(delaunay_3d(pts), 1.5 * mean_spacing(pts));
  HomologyOptions o;
  o.max_beta1 = 5;
  ASSERT_GT(betti_1(k), 5);
  try {
    shortest_homology_basis(k, o);
    FAIL() << "no error";
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("too small"), std::string::npos) << e.what();
  }
}

TEST(Delaunay, RejectsDegenerateInput) {
  EXPECT_THROW(delaunay_3d({{0, 0, 0}, {1, 0, 0}, {0, 1, 0}}), std::invalid_argument);
  EXPECT_THROW(delaunay_3d({{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {1, 0, 0}, {0, 0, 0}}),
               std::invalid_argument);  // 3 distinct
  PointCloud flat;
  for (int i = 0; i < 50; ++i) flat.emplace_back(i % 7, i / 7, 0.0);
  try {
    delaunay_3d(flat);
    FAIL();
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("coplanar"), std::string::npos);
  }
  PointCloud line;
  for (int i = 0; i < 10; ++i) line.emplace_back(i, 2 * i, 3 * i);
  EXPECT_THROW(delaunay_3d(line), std::invalid_argument);
  const DelaunayGraph g = delaunay_3d({{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {0, 0, 1}});
  EXPECT_EQ(g.edges.size(), 6u);
  EXPECT_EQ(g.triangles.size(), 4u);
  // K_d keeps edges shorter than d and triangles whose three edges are.
  const SimplicialComplex k = build_complex(g, 1.2);
  EXPECT_EQ(k.edges.size(), 3u);  // the unit edges; the sqrt(2) ones are too long
  EXPECT_EQ(k.triangles.size(), 0u);
  EXPECT_EQ(build_complex(g, 1.5).triangles.size(), 4u);
  // The tetrahedron as its four facets; in K_d only when all six edges are.
  ASSERT_EQ(g.tetrahedra.size(), 1u);
  EXPECT_EQ(g.tetrahedra[0], (std::array<int, 4>{0, 1, 2, 3}));
  EXPECT_TRUE(k.tetrahedra.empty());
  EXPECT_EQ(build_complex(g, 1.5).tetrahedra.size(), 1u);
}

}  // namespace
}  // namespace claspplan::perception
