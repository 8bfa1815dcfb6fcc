#include "robots/convex_hull.hpp"

#include <cstdio>
#include <map>

extern "C" {
#include <libqhull_r/qhull_ra.h>
}

#include "core/input_error.hpp"

namespace claspplan::robots {

TriangleMesh convex_hull(const std::vector<Eigen::Vector3d>& points, const std::string& what) {
  if (points.size() < 4) throw InputError(what + ": a convex hull needs at least 4 points");
  std::vector<coordT> coords;
  coords.reserve(3 * points.size());
  for (const auto& p : points) coords.insert(coords.end(), {p.x(), p.y(), p.z()});
  qhT qh_storage;
  qhT* qh = &qh_storage;
  // Qhull writes its messages to files: to none of ours.
  FILE* sink = std::fopen("/dev/null", "w");
  qh_zero(qh, sink);
  char options[] = "qhull Qt";  // triangulated facets
  const int failed = qh_new_qhull(qh, 3, static_cast<int>(points.size()), coords.data(), False,
                                  options, sink, sink);
  TriangleMesh hull;
  if (!failed) {
    std::map<int, int> index;  // Qhull's point id -> hull vertex
    facetT* facet;
    FORALLfacets {
      int t[3], k = 0;
      vertexT *vertex, **vertexp;
      FOREACHvertex_(facet->vertices) {
        const int id = qh_pointid(qh, vertex->point);
        auto [it, added] = index.emplace(id, static_cast<int>(hull.vertices.size()));
        if (added) hull.vertices.push_back(points[id]);
        if (k < 3) t[k] = it->second;
        ++k;
      }
      if (k != 3) continue;
      Eigen::Vector3i tri(t[0], t[1], t[2]);
      const Eigen::Vector3d n = (hull.vertices[t[1]] - hull.vertices[t[0]])
                                    .cross(hull.vertices[t[2]] - hull.vertices[t[0]]);
      const Eigen::Vector3d out(facet->normal[0], facet->normal[1], facet->normal[2]);
      if (n.dot(out) < 0) std::swap(tri[1], tri[2]);
      hull.triangles.push_back(tri);
    }
  }
  int curlong = 0, totlong = 0;
  qh_freeqhull(qh, !qh_ALL);
  qh_memfreeshort(qh, &curlong, &totlong);
  if (sink) std::fclose(sink);
  if (failed || hull.triangles.size() < 4)
    throw InputError(what + ": its points span no volume (no convex hull)");
  return hull;
}

}  // namespace claspplan::robots
