// The object's collision geometry (collision_world.cpp, object_geometry.cpp): its FCL models,
// its triangle tree for exact round shapes and its bounding box. Internal to robots.
#pragma once

#include <memory>
#include <mutex>
#include <vector>

#include <Eigen/Core>
#include <fcl/geometry/bvh/BVH_model.h>
#include <fcl/math/bv/OBBRSS.h>

#include "robots/collision_world.hpp"
#include "robots/triangle_tree.hpp"

namespace claspplan::robots {

using Geometry = std::shared_ptr<fcl::CollisionGeometryd>;
using Mesh = fcl::BVHModel<fcl::OBBRSSd>;

// An axis-aligned box.
struct Box3 {
  Eigen::Vector3d lo, hi;
  bool overlaps(const Box3& o) const {
    return (lo.array() <= o.hi.array()).all() && (o.lo.array() <= hi.array()).all();
  }
  // Euclidean distance between two boxes (0 when they overlap).
  double distance(const Box3& o) const {
    const Eigen::Vector3d gap = (o.lo - hi).cwiseMax(lo - o.hi).cwiseMax(Eigen::Vector3d::Zero());
    return gap.norm();
  }
};

// The object's collision geometry, never modified once built (shared by worlds and threads).
struct ObjectGeometry {
  // OBBRSS, for distances. With the tree, only collisions are usual (the secure-clasp check): the
  // mesh is built at the first distance query, once for all threads.
  std::shared_ptr<Mesh> mesh;
  std::vector<fcl::Vector3d> mesh_vertices;
  std::vector<fcl::Triangle> mesh_triangles;
  std::once_flag mesh_built;
  std::shared_ptr<const TriangleTree> tree;  // exact spheres and capsules, when built for them
  // What collision queries test: `mesh`, or with the tree the same mesh in OBBs, whose bound of
  // a primitive FCL computes in closed form (OBBRSS fits one to its corners each query).
  Geometry collide;
  int triangles = 0;
  Box3 local_box;

  const Mesh& distance_mesh() const;
};

/// An FCL bounding-volume hierarchy over the triangles.
template <class Model>
std::shared_ptr<Model> build_bvh(const std::vector<fcl::Vector3d>& vertices,
                                 const std::vector<fcl::Triangle>& triangles) {
  auto model = std::make_shared<Model>();
  model->beginModel(static_cast<int>(triangles.size()), static_cast<int>(vertices.size()));
  model->addSubModel(vertices, triangles);
  model->endModel();
  model->computeLocalAABB();
  return model;
}

}  // namespace claspplan::robots
