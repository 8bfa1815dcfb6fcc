#include "robots/object_geometry.hpp"

#include <stdexcept>
#include <string>

#include <fcl/math/bv/OBB.h>

namespace claspplan::robots {

const Mesh& ObjectGeometry::distance_mesh() const {
  auto& self = const_cast<ObjectGeometry&>(*this);
  std::call_once(self.mesh_built, [&self] {
    if (!self.mesh) self.mesh = build_bvh<Mesh>(self.mesh_vertices, self.mesh_triangles);
    self.mesh_vertices = {};
    self.mesh_triangles = {};
  });
  return *mesh;
}

std::shared_ptr<const ObjectGeometry> make_object_geometry(
    const std::vector<Eigen::Vector3d>& vertices, const std::vector<Eigen::Vector3i>& triangles,
    bool exact_round_shapes) {
  if (vertices.empty()) throw std::invalid_argument("collision object: no vertices");
  std::vector<fcl::Vector3d> v;
  v.reserve(vertices.size());
  Box3 b{vertices[0], vertices[0]};
  for (size_t i = 0; i < vertices.size(); ++i) {
    if (!vertices[i].allFinite())
      throw std::invalid_argument("collision object: vertex " + std::to_string(i) +
                                  " is not finite");
    v.push_back(vertices[i]);
    b.lo = b.lo.cwiseMin(vertices[i]);
    b.hi = b.hi.cwiseMax(vertices[i]);
  }
  const int n = static_cast<int>(vertices.size());
  std::vector<fcl::Triangle> t;
  t.reserve(triangles.size());
  for (size_t i = 0; i < triangles.size(); ++i) {
    const Eigen::Vector3i& tri = triangles[i];
    if ((tri.array() < 0).any() || (tri.array() >= n).any())
      throw std::invalid_argument("collision object: triangle " + std::to_string(i) +
                                  " has a vertex index out of range");
    if (tri[0] == tri[1] || tri[1] == tri[2] || tri[0] == tri[2]) continue;
    t.emplace_back(tri[0], tri[1], tri[2]);
  }
  if (t.empty()) throw std::invalid_argument("collision object: no usable triangle");
  auto g = std::make_shared<ObjectGeometry>();
  g->triangles = static_cast<int>(t.size());
  if (exact_round_shapes) {
    g->tree = std::make_shared<TriangleTree>(vertices, triangles);
    g->collide = build_bvh<fcl::BVHModel<fcl::OBBd>>(v, t);
    g->mesh_vertices = std::move(v);
    g->mesh_triangles = std::move(t);
  } else {
    g->mesh = build_bvh<Mesh>(v, t);
    g->collide = g->mesh;
  }
  g->local_box = b;
  return g;
}

}  // namespace claspplan::robots
