// Procedural triangle meshes for the robots tests and benchmarks (closed, outward-facing).
#pragma once

#include <cmath>
#include <vector>

#include <Eigen/Core>

#include "core/mesh.hpp"

namespace claspplan::test {

using TriMesh = TriangleMesh;

/// A torus around the z axis through the origin: major radius R, tube radius r, nu × nv quads
/// (2·nu·nv triangles).
inline TriMesh torus_mesh(double R, double r, int nu, int nv) {
  TriMesh m;
  const double two_pi = 2.0 * M_PI;
  for (int i = 0; i < nu; ++i) {
    const double u = two_pi * i / nu;
    for (int j = 0; j < nv; ++j) {
      const double v = two_pi * j / nv;
      m.vertices.emplace_back((R + r * std::cos(v)) * std::cos(u),
                              (R + r * std::cos(v)) * std::sin(u), r * std::sin(v));
    }
  }
  auto id = [&](int i, int j) { return (i % nu) * nv + (j % nv); };
  for (int i = 0; i < nu; ++i) {
    for (int j = 0; j < nv; ++j) {
      m.triangles.emplace_back(id(i, j), id(i + 1, j), id(i + 1, j + 1));
      m.triangles.emplace_back(id(i, j), id(i + 1, j + 1), id(i, j + 1));
    }
  }
  return m;
}

/// A closed cylinder (bar) along the z axis, centred at the origin, n sides.
inline TriMesh bar_mesh(double radius, double length, int n) {
  TriMesh m;
  for (int k = 0; k < 2; ++k) {
    const double z = (k == 0 ? -0.5 : 0.5) * length;
    for (int i = 0; i < n; ++i) {
      const double a = 2.0 * M_PI * i / n;
      m.vertices.emplace_back(radius * std::cos(a), radius * std::sin(a), z);
    }
  }
  const int bottom = static_cast<int>(m.vertices.size());
  m.vertices.emplace_back(0, 0, -0.5 * length);
  m.vertices.emplace_back(0, 0, 0.5 * length);
  for (int i = 0; i < n; ++i) {
    const int j = (i + 1) % n;
    m.triangles.emplace_back(i, j, n + j);
    m.triangles.emplace_back(i, n + j, n + i);
    m.triangles.emplace_back(bottom, j, i);
    m.triangles.emplace_back(bottom + 1, n + i, n + j);
  }
  return m;
}

}  // namespace claspplan::test
