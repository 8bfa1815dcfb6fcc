// A box as a closed triangle mesh, for tests that need an object of known shape.
#pragma once

#include <Eigen/Geometry>

#include "core/mesh.hpp"

namespace claspplan::test {

/// A box of edge lengths `size` centred at `pose` (its 12 triangles, facing outwards).
inline TriangleMesh box_mesh(const Eigen::Isometry3d& pose, const Eigen::Vector3d& size) {
  TriangleMesh mesh;
  for (int c = 0; c < 8; ++c)
    mesh.vertices.push_back(pose * (0.5 * Eigen::Vector3d((c & 1) ? size.x() : -size.x(),
                                                          (c & 2) ? size.y() : -size.y(),
                                                          (c & 4) ? size.z() : -size.z())));
  const int faces[6][4] = {{0, 2, 3, 1}, {4, 5, 7, 6}, {0, 1, 5, 4},
                           {2, 6, 7, 3}, {0, 4, 6, 2}, {1, 3, 7, 5}};
  for (const auto& f : faces) {
    mesh.triangles.emplace_back(f[0], f[1], f[2]);
    mesh.triangles.emplace_back(f[0], f[2], f[3]);
  }
  return mesh;
}

}  // namespace claspplan::test
