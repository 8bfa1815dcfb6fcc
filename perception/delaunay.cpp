// The only file that includes CGAL (it compiles slowly): the 3-D Delaunay triangulation.
#include <algorithm>
#include <stdexcept>
#include <utility>

#include <CGAL/Delaunay_triangulation_3.h>
#include <CGAL/Delaunay_triangulation_cell_base_3.h>
#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/Triangulation_cell_base_with_info_3.h>
#include <CGAL/Triangulation_data_structure_3.h>
#include <CGAL/Triangulation_vertex_base_with_info_3.h>

#include "perception/cloud_filters.hpp"
#include "perception/complex.hpp"
#include "perception/input_error.hpp"

namespace claspplan::perception {

namespace {
using Kernel = CGAL::Exact_predicates_inexact_constructions_kernel;  // exact predicates
using Vb = CGAL::Triangulation_vertex_base_with_info_3<int, Kernel>;
// A cell's info: the (pre-sort) index of each of its four facets.
using Cb =
    CGAL::Triangulation_cell_base_with_info_3<std::array<int, 4>, Kernel,
                                              CGAL::Delaunay_triangulation_cell_base_3<Kernel>>;
using Tds = CGAL::Triangulation_data_structure_3<Vb, Cb>;
using Delaunay = CGAL::Delaunay_triangulation_3<Kernel, Tds>;
}  // namespace

DelaunayGraph delaunay_3d(const PointCloud& points) {
  for (size_t i = 0; i < points.size(); ++i)
    if (!points[i].allFinite())
      throw InputError("point " + std::to_string(i) + " has a NaN or infinite coordinate");
  const size_t distinct = unique_points(points).size();
  if (distinct < 4)
    throw InputError("fewer than 4 distinct points (" + std::to_string(distinct) +
                     "): a 3-D triangulation needs at least 4");
  std::vector<std::pair<Kernel::Point_3, int>> input;
  input.reserve(points.size());
  for (size_t i = 0; i < points.size(); ++i)
    input.emplace_back(Kernel::Point_3(points[i].x(), points[i].y(), points[i].z()),
                       static_cast<int>(i));
  Delaunay dt(input.begin(), input.end());  // spatially sorted insertion
  if (dt.dimension() < 3)
    throw InputError(dt.dimension() == 2
                         ? "all points are coplanar: K_d needs points that span 3-D"
                         : "all points are collinear: K_d needs points that span 3-D");
  DelaunayGraph g;
  g.points = points;
  for (auto e = dt.finite_edges_begin(); e != dt.finite_edges_end(); ++e) {
    int a = e->first->vertex(e->second)->info();
    int b = e->first->vertex(e->third)->info();
    if (a > b) std::swap(a, b);
    g.edges.push_back({a, b});
  }
  std::sort(g.edges.begin(), g.edges.end());
  // Edge lookup: per vertex, its edges in CSR form (neighbours sorted).
  const int n = static_cast<int>(points.size());
  std::vector<int> start(n + 1, 0);
  for (const auto& e : g.edges) ++start[e[0] + 1];
  for (int i = 0; i < n; ++i) start[i + 1] += start[i];
  auto edge_id = [&](int a, int b) {
    if (a > b) std::swap(a, b);
    for (int k = start[a]; k < start[a + 1]; ++k)
      if (g.edges[k][1] == b) return k;
    throw std::logic_error("Delaunay facet edge missing");
  };
  g.edge_length.reserve(g.edges.size());
  for (const auto& e : g.edges) g.edge_length.push_back((points[e[0]] - points[e[1]]).norm());
  std::vector<std::pair<std::array<int, 3>, int>> facets;  // edge ids, enumeration index
  facets.reserve(2 * dt.number_of_finite_cells() + 16);
  for (auto f = dt.finite_facets_begin(); f != dt.finite_facets_end(); ++f) {
    const int i = f->second;
    const int a = f->first->vertex((i + 1) & 3)->info();
    const int b = f->first->vertex((i + 2) & 3)->info();
    const int c = f->first->vertex((i + 3) & 3)->info();
    std::array<int, 3> t{edge_id(a, b), edge_id(b, c), edge_id(a, c)};
    std::sort(t.begin(), t.end());
    const int k = static_cast<int>(facets.size());
    facets.emplace_back(t, k);
    f->first->info()[i] = k;  // both cells that share the facet
    f->first->neighbor(i)->info()[dt.mirror_index(f->first, i)] = k;
  }
  // CGAL's facet order depends on memory addresses: a canonical order keeps results identical.
  std::sort(facets.begin(), facets.end());
  std::vector<int> id(facets.size());
  g.triangles.reserve(facets.size());
  for (const auto& [t, k] : facets) {
    id[k] = static_cast<int>(g.triangles.size());
    g.triangles.push_back(t);
  }
  g.tetrahedra.reserve(dt.number_of_finite_cells());
  for (auto c = dt.finite_cells_begin(); c != dt.finite_cells_end(); ++c) {
    std::array<int, 4> faces;
    for (int i = 0; i < 4; ++i) faces[i] = id[c->info()[i]];
    std::sort(faces.begin(), faces.end());
    g.tetrahedra.push_back(faces);
  }
  std::sort(g.tetrahedra.begin(), g.tetrahedra.end());
  return g;
}

}  // namespace claspplan::perception
