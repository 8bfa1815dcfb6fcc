// The 3-D Delaunay triangulation of the object's points and the simplicial complex K_d (paper
// Sec. IV-A): all points, every Delaunay edge shorter than d, every Delaunay triangle whose three
// edges are shorter than d.
#pragma once

#include <array>
#include <string>
#include <vector>

#include "core/mesh.hpp"

namespace claspplan::perception {

/// Edges and triangles (facets) of the 3-D Delaunay triangulation, over vertex indices into
/// `points`. Computed once; K_d for any d is a filter of it.
struct DelaunayGraph {
  PointCloud points;
  std::vector<std::array<int, 2>> edges;      ///< i < j
  std::vector<double> edge_length;            ///< per edge
  std::vector<std::array<int, 3>> triangles;  ///< edge ids, per Delaunay facet
  /// Each finite tetrahedron as its four facets (indices into `triangles`), sorted.
  std::vector<std::array<int, 4>> tetrahedra;
};

/// CGAL Delaunay_triangulation_3 with the exact-predicates kernel (Qhull does not scale: design
/// notes). Duplicate points are an error for the caller to avoid (use unique_points()).
/// Throws std::invalid_argument for fewer than 4 points, non-finite coordinates, or points that
/// do not span 3-D (all coplanar or collinear): K_d needs a 3-D triangulation.
DelaunayGraph delaunay_3d(const PointCloud& points);

/// K_d.
struct SimplicialComplex {
  PointCloud points;
  std::vector<std::array<int, 2>> edges;  ///< vertex indices, i < j
  std::vector<double> edge_length;
  std::vector<std::array<int, 3>> triangles;  ///< edge ids (indices into `edges`)
  /// The Delaunay tetrahedra whose six edges are shorter than d, as their four triangles (indices
  /// into `triangles`). K_d is the 2-skeleton; these only tell the homology which triangles'
  /// boundaries are sums of others (a tetrahedron's four faces bound nothing together).
  std::vector<std::array<int, 4>> tetrahedra;
  double d = 0.0;

  int vertex_count() const { return static_cast<int>(points.size()); }
  /// The three vertex indices of a triangle.
  std::array<int, 3> triangle_vertices(int t) const;
};

/// K_d from the Delaunay graph: edges with length < d, triangles whose three edges have length < d.
SimplicialComplex build_complex(const DelaunayGraph& delaunay, double d);

/// The automatic d: `factor` times the mean nearest-neighbour spacing of the points. The pipeline's
/// farthest-point samples are nearly uniform; below about 3x their spacing, sampling gaps become
/// many small noise loops (design notes; measured: 2x gives 130-180 loops on a torus, 2.5x still
/// 3-23), from 3x on whole-surface samples are clean and depth data from 3.5x. Walls thinner than d
/// fill in (a thin handle becomes solid: one loop, as in the paper's Fig. 3).
double automatic_d(const PointCloud& points, double factor = 3.5);

}  // namespace claspplan::perception
