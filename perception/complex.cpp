#include "perception/complex.hpp"

#include <cmath>
#include <stdexcept>

#include "core/input_error.hpp"
#include "perception/cloud_filters.hpp"

namespace claspplan::perception {

std::array<int, 3> SimplicialComplex::triangle_vertices(int t) const {
  const auto& e0 = edges[triangles[t][0]];
  const auto& e1 = edges[triangles[t][1]];
  const int c = (e1[0] != e0[0] && e1[0] != e0[1]) ? e1[0] : e1[1];
  return {e0[0], e0[1], c};
}

SimplicialComplex build_complex(const DelaunayGraph& delaunay, double d) {
  if (!(d > 0) || !std::isfinite(d))
    throw InputError("d must be a positive number of metres, got " + std::to_string(d));
  SimplicialComplex k;
  k.points = delaunay.points;
  k.d = d;
  std::vector<int> renumber(delaunay.edges.size(), -1);
  for (size_t e = 0; e < delaunay.edges.size(); ++e) {
    if (delaunay.edge_length[e] < d) {
      renumber[e] = static_cast<int>(k.edges.size());
      k.edges.push_back(delaunay.edges[e]);
      k.edge_length.push_back(delaunay.edge_length[e]);
    }
  }
  std::vector<int> triangle_of(delaunay.triangles.size(), -1);
  for (size_t t = 0; t < delaunay.triangles.size(); ++t) {
    const auto& e = delaunay.triangles[t];
    const int a = renumber[e[0]], b = renumber[e[1]], c = renumber[e[2]];
    if (a >= 0 && b >= 0 && c >= 0) {
      triangle_of[t] = static_cast<int>(k.triangles.size());
      k.triangles.push_back({a, b, c});
    }
  }
  for (const auto& f : delaunay.tetrahedra) {
    const std::array<int, 4> t{triangle_of[f[0]], triangle_of[f[1]], triangle_of[f[2]],
                               triangle_of[f[3]]};
    if (t[0] >= 0 && t[1] >= 0 && t[2] >= 0 && t[3] >= 0) k.tetrahedra.push_back(t);
  }
  return k;
}

double automatic_d(const PointCloud& points, double factor) {
  if (!(factor > 0)) throw InputError("the automatic-d factor must be > 0");
  return factor * mean_spacing(points);
}

}  // namespace claspplan::perception
