// The only file that includes CGAL (it compiles slowly): the 3-D Delaunay triangulation.
#include <algorithm>
#include <array>
#include <cstdint>
#include <optional>
#include <stdexcept>
#include <utility>

#include <CGAL/Delaunay_triangulation_3.h>
#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/Triangulation_data_structure_3.h>
#include <CGAL/Triangulation_vertex_base_with_info_3.h>

#include "core/input_error.hpp"
#include "core/parallel.hpp"
#include "perception/complex.hpp"
#include "perception/counting_sort.hpp"

namespace claspplan::perception {

namespace {
using Kernel = CGAL::Exact_predicates_inexact_constructions_kernel;  // exact predicates
using Vb = CGAL::Triangulation_vertex_base_with_info_3<int, Kernel>;
using Tds = CGAL::Triangulation_data_structure_3<Vb>;
using Delaunay = CGAL::Delaunay_triangulation_3<Kernel, Tds>;

// Distinct simplices keyed by their lowest vertex: per vertex (CSR), the other vertices packed in
// 21 bits each, sorted.
class Simplices {
 public:
  static std::uint64_t pack(int b, int c = 0) {
    return (std::uint64_t(b) << 21) | std::uint64_t(c);
  }
  /// The edges (`faces` false) or triangles of the sorted cells, from each vertex's incident cells
  /// (`incident`: CSR over vertices, each entry a cell and the vertex's place in it): the
  /// vertices after it in a cell give its edges and faces. Each vertex's few dozen candidates are
  /// sorted in place, so no list of every cell's faces is ever stored.
  Simplices(const std::vector<std::array<int, 4>>& cells, const std::vector<int>& incident_start,
            const std::vector<std::pair<int, int>>& incident, bool faces) {
    const int n = static_cast<int>(incident_start.size()) - 1;
    start_.assign(n + 1, 0);
    rest_.reserve(faces ? 3 * cells.size() : 2 * cells.size());
    std::vector<std::uint64_t> found;
    for (int a = 0; a < n; ++a) {
      found.clear();
      for (int k = incident_start[a]; k < incident_start[a + 1]; ++k) {
        const auto& [cell, place] = incident[k];
        const std::array<int, 4>& c = cells[cell];
        for (int i = place + 1; i < 4; ++i) {
          if (!faces) {
            found.push_back(pack(c[i]));
            continue;
          }
          for (int j = i + 1; j < 4; ++j) found.push_back(pack(c[i], c[j]));
        }
      }
      std::sort(found.begin(), found.end());
      found.erase(std::unique(found.begin(), found.end()), found.end());
      rest_.insert(rest_.end(), found.begin(), found.end());
      start_[a + 1] = static_cast<int>(rest_.size());
    }
  }
  int size() const { return static_cast<int>(rest_.size()); }
  int first(int v) const { return start_[v]; }
  int end(int v) const { return start_[v + 1]; }
  std::uint64_t rest(int i) const { return rest_[i]; }
  /// Index of the simplex (v, rest), in lexicographic vertex order.
  int find(int v, std::uint64_t rest) const {
    const auto b = rest_.begin() + start_[v], e = rest_.begin() + start_[v + 1];
    const auto it = std::lower_bound(b, e, rest);
    if (it == e || *it != rest) throw std::logic_error("Delaunay face missing");
    return static_cast<int>(it - rest_.begin());
  }

 private:
  std::vector<int> start_;
  std::vector<std::uint64_t> rest_;
};
}  // namespace

DelaunayGraph delaunay_3d(const PointCloud& points) {
  for (size_t i = 0; i < points.size(); ++i)
    if (!points[i].allFinite())
      throw InputError("point " + std::to_string(i) + " has a NaN or infinite coordinate");
  const int n = static_cast<int>(points.size());
  if (n >= (1 << 21)) throw InputError("more than 2,097,151 points for the Delaunay triangulation");
  std::vector<std::pair<Kernel::Point_3, int>> input;
  input.reserve(points.size());
  for (size_t i = 0; i < points.size(); ++i)
    input.emplace_back(Kernel::Point_3(points[i].x(), points[i].y(), points[i].z()),
                       static_cast<int>(i));
  Delaunay dt(input.begin(), input.end());  // spatially sorted insertion; duplicates merged
  if (dt.number_of_vertices() < 4)
    throw InputError("fewer than 4 distinct points (" + std::to_string(dt.number_of_vertices()) +
                     "): a 3-D triangulation needs at least 4");
  if (dt.dimension() < 3)
    throw InputError(dt.dimension() == 2
                         ? "all points are coplanar: K_d needs points that span 3-D"
                         : "all points are collinear: K_d needs points that span 3-D");
  // Every finite cell as its four vertices, sorted. Edges, triangles and tetrahedra are numbered
  // in lexicographic vertex order, which is also the order of their sorted face ids (edge ab comes
  // before ac and ac before bc when a < b < c): a canonical order, independent of CGAL's memory
  // addresses, so that results are identical from run to run.
  std::vector<std::array<int, 4>> unsorted;
  unsorted.reserve(dt.number_of_finite_cells());
  for (auto c = dt.finite_cells_begin(); c != dt.finite_cells_end(); ++c) {
    std::array<int, 4> v;
    for (int i = 0; i < 4; ++i) v[i] = c->vertex(i)->info();
    std::sort(v.begin(), v.end());
    unsorted.push_back(v);
  }
  // Sorted: bucketed by lowest vertex (a counting sort), then each bucket's few cells compared.
  std::vector<int> at;
  std::vector<std::array<int, 4>> cells = detail::sorted_by_key(
      unsorted, n, [](const std::array<int, 4>& c) { return c[0]; }, &at);
  for (int v = 0; v < n; ++v)
    if (at[v + 1] - at[v] > 1) std::sort(cells.begin() + at[v], cells.begin() + at[v + 1]);
  unsorted = {};
  // Each vertex's incident cells, with its place in the cell's sorted vertices.
  std::vector<int> incident_start(n + 1, 0);
  for (const auto& c : cells)
    for (int v : c) ++incident_start[v + 1];
  for (int v = 0; v < n; ++v) incident_start[v + 1] += incident_start[v];
  std::vector<std::pair<int, int>> incident(4 * cells.size());
  {
    std::vector<int> fill(incident_start.begin(), incident_start.end() - 1);
    for (int k = 0; k < static_cast<int>(cells.size()); ++k)
      for (int i = 0; i < 4; ++i) incident[fill[cells[k][i]]++] = {k, i};
  }
  // The edges and the triangles side by side, then the tetrahedra beside the rest: each list is
  // built whole by one thread, so the result does not depend on how many run.
  std::optional<Simplices> edge_list, face_list;
  parallel_invoke([&] { edge_list.emplace(cells, incident_start, incident, false); },
                  [&] { face_list.emplace(cells, incident_start, incident, true); });
  const Simplices &edges = *edge_list, &faces = *face_list;
  incident = {};
  DelaunayGraph g;
  const auto tetrahedra = [&] {
    constexpr int kFaces[4][3] = {{0, 1, 2}, {0, 1, 3}, {0, 2, 3}, {1, 2, 3}};
    g.tetrahedra.reserve(cells.size());
    for (const auto& c : cells) {
      std::array<int, 4> t;
      for (int i = 0; i < 4; ++i) {
        const int* f = kFaces[i];
        t[i] = faces.find(c[f[0]], Simplices::pack(c[f[1]], c[f[2]]));  // ascending
      }
      g.tetrahedra.push_back(t);
    }
  };
  const auto edges_and_triangles = [&] {
    g.points = points;
    g.edges.reserve(edges.size());
    g.edge_length.reserve(edges.size());
    for (int a = 0; a < n; ++a)
      for (int i = edges.first(a); i < edges.end(a); ++i) {
        const int b = static_cast<int>(edges.rest(i) >> 21);
        g.edges.push_back({a, b});
        g.edge_length.push_back((points[a] - points[b]).norm());
      }
    // The triangles' edge ids, for two halves of the vertices side by side.
    auto edge_id = [&](int a, int b) { return edges.find(a, Simplices::pack(b)); };
    g.triangles.resize(faces.size());
    const auto triangles_of = [&](int from, int to) {
      for (int a = from; a < to; ++a)
        for (int i = faces.first(a); i < faces.end(a); ++i) {
          const int b = static_cast<int>(faces.rest(i) >> 21);
          const int c = static_cast<int>(faces.rest(i) & ((1u << 21) - 1));
          g.triangles[i] = {edge_id(a, b), edge_id(a, c), edge_id(b, c)};  // ascending
        }
    };
    int half = 0;
    while (half < n && faces.first(half) < faces.size() / 2) ++half;
    parallel_invoke([&] { triangles_of(0, half); }, [&] { triangles_of(half, n); });
  };
  parallel_invoke(edges_and_triangles, tetrahedra);
  return g;
}

}  // namespace claspplan::perception
