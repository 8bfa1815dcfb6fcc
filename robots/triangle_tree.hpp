// A static triangle mesh in a bounding-box tree, with exact "does this sphere or capsule touch
// it" queries: the closed-form alternative to FCL's GJK for the rounded shapes that make up the
// fingers (a capsule touches a triangle when their segment–triangle distance is at most its
// radius; a sphere is a capsule of length 0).
#pragma once

#include <vector>

#include <Eigen/Core>
#include <Eigen/Geometry>

namespace claspplan::robots {

/// Squared distance between segment [p0, p1] and triangle (a, b, c); 0 when they cross.
double segment_triangle_distance_sq(const Eigen::Vector3d& p0, const Eigen::Vector3d& p1,
                                    const Eigen::Vector3d& a, const Eigen::Vector3d& b,
                                    const Eigen::Vector3d& c);

class TriangleTree {
 public:
  TriangleTree() = default;
  /// Triangles with a repeated vertex are skipped; indices must be in range (not checked here).
  TriangleTree(const std::vector<Eigen::Vector3d>& vertices,
               const std::vector<Eigen::Vector3i>& triangles);

  bool empty() const { return nodes_.empty(); }
  /// Is some triangle within `radius` of segment [p0, p1] (mesh frame)?
  bool touches_capsule(const Eigen::Vector3d& p0, const Eigen::Vector3d& p1, double radius) const;

 private:
  struct Node {
    Eigen::AlignedBox3d box;
    int first = 0, count = 0;   // a leaf's triangles (count > 0), else
    int left = -1, right = -1;  // its children
  };
  struct Triangle {
    Eigen::Vector3d a, b, c;
    Eigen::Vector3d normal;  // unit, or zero for a sliver
    Eigen::Vector3d centre;  // of the bounding sphere: the centroid ...
    double reach = 0.0;      // ... and its distance to the farthest vertex
  };
  int build(int first, int count, std::vector<Eigen::Vector3d>& centres);

  std::vector<Node> nodes_;
  std::vector<Triangle> triangles_;
};

}  // namespace claspplan::robots
