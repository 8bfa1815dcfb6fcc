#include "tsrrt/clasp_scene.hpp"

#include <algorithm>
#include <cstdio>
#include <limits>
#include <stdexcept>

#include "perception/depth_surface.hpp"
#include "perception/input_error.hpp"
#include "tsrrt/clasp_planning.hpp"

namespace claspplan::tsrrt {

int choose_loop(const perception::ObjectModel& object, const std::optional<Eigen::Vector3d>& hint) {
  int chosen = -1;
  double best = std::numeric_limits<double>::infinity();
  for (int i = 0; i < static_cast<int>(object.loops.size()); ++i) {
    const perception::Loop& loop = object.loops[i];
    if (!loop.claspable) continue;
    if (!hint) return i;  // ranked best first
    for (const auto& p : loop.points) {
      if ((p - *hint).norm() < best) best = (p - *hint).norm(), chosen = i;
    }
  }
  return chosen;
}

std::string no_loop_reason(const perception::ObjectModel& object) {
  char d[32];
  std::snprintf(d, sizeof d, "%.4f", object.persistence_d);
  const std::string filled_in =
      " of K_d fill in by d' = " + std::string(d) + " m (gaps or holes narrower than a finger's)";
  if (object.loops.empty() && object.unstable_loops > 0)
    return "no stable loop: all " + std::to_string(object.unstable_loops) + " loops" + filled_in;
  if (object.loops.empty()) return "the object has no loops (beta1 = 0)";
  // Loops refused for the hand's room first (they passed every other test), then the widest
  // holes: why the most promising loops were refused.
  std::vector<const perception::Loop*> widest;
  for (const auto& l : object.loops) widest.push_back(&l);
  std::stable_sort(widest.begin(), widest.end(), [](const auto* a, const auto* b) {
    const bool room_a = a->verdict == "no_room", room_b = b->verdict == "no_room";
    if (room_a != room_b) return room_a;
    return a->hole_width > b->hole_width;
  });
  // The same reason for several of them is said once, with their number.
  std::vector<std::pair<std::string, int>> reasons;
  for (std::size_t i = 0; i < widest.size() && i < 3; ++i) {
    auto same = std::find_if(reasons.begin(), reasons.end(),
                             [&](const auto& r) { return r.first == widest[i]->reason; });
    if (same == reasons.end())
      reasons.push_back({widest[i]->reason, 1});
    else
      ++same->second;
  }
  std::string why = "no claspable loop: ";
  for (std::size_t i = 0; i < reasons.size(); ++i) {
    why += (i ? "; " : "") + reasons[i].first;
    if (reasons[i].second > 1) why += " (" + std::to_string(reasons[i].second) + " loops)";
  }
  // A hole narrower than about d' (a small handle) is among these, not among the reasons above.
  if (object.unstable_loops > 0) {
    why += "; " + std::to_string(object.unstable_loops) + " more loop" +
           (object.unstable_loops > 1 ? "s" : "") + filled_in;
  }
  return why;
}

void object_collision_mesh(const perception::ObjectModel& object, const perception::Loop& loop,
                           const Eigen::AlignedBox3d& workspace, const std::string& name,
                           std::vector<Eigen::Vector3d>& vertices,
                           std::vector<Eigen::Vector3i>& triangles) {
  vertices.clear();
  triangles.clear();
  if (!object.views.empty()) {
    perception::DepthSurfaceOptions so;
    so.workspace = workspace;
    so.support_plane = object.support_plane;
    const perception::TriangleMesh seen = perception::depth_surface_mesh(object.views, so);
    vertices = seen.vertices;
    for (const auto& t : seen.triangles) triangles.emplace_back(t[0], t[1], t[2]);
  } else {
    vertices = object.complex.points;
    for (int i = 0; i < static_cast<int>(object.complex.triangles.size()); ++i) {
      const auto v = object.complex.triangle_vertices(i);
      triangles.emplace_back(v[0], v[1], v[2]);
    }
  }
  if (triangles.empty()) {
    throw InputError((name.empty() ? "" : name + ": ") +
                     "the object has no surface to collide with (no depth surface "
                     "and no K_d triangles: raise perception.d or the point count)");
  }
  loop_tube(loop.points, kLoopTubeRadius, vertices, triangles);
}

}  // namespace claspplan::tsrrt
