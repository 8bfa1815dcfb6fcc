#include "tsrrt/clasp_scene.hpp"

#include <algorithm>
#include <cstdio>
#include <limits>
#include <numeric>
#include <stdexcept>

#include "core/input_error.hpp"
#include "perception/cloud_filters.hpp"
#include "perception/depth_surface.hpp"
#include "robots/triangle_tree.hpp"
#include "tsrrt/clasp_setup.hpp"
#include "tsrrt/elapsed.hpp"

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
    const bool room_a = a->verdict == perception::LoopVerdict::kNoRoom,
               room_b = b->verdict == perception::LoopVerdict::kNoRoom;
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

TriangleMesh object_collision_mesh(const perception::ObjectModel& object,
                                   const perception::Loop& loop,
                                   const Eigen::AlignedBox3d& workspace, const std::string& name) {
  TriangleMesh mesh;
  if (!object.views.empty()) {
    perception::DepthSurfaceOptions so;
    so.workspace = workspace;
    so.support_plane = object.support_plane;
    mesh = perception::depth_surface_mesh(object.views, so);
  } else {
    mesh.vertices = object.complex.points;
    for (int i = 0; i < static_cast<int>(object.complex.triangles.size()); ++i) {
      const auto v = object.complex.triangle_vertices(i);
      mesh.triangles.emplace_back(v[0], v[1], v[2]);
    }
  }
  if (mesh.triangles.empty()) {
    throw InputError((name.empty() ? "" : name + ": ") +
                     "the object has no surface to collide with (no depth surface "
                     "and no K_d triangles: raise perception.d or the point count)");
  }
  loop_tube(loop.points, kLoopTubeRadius, mesh);
  return mesh;
}

std::vector<Eigen::Vector3d> unmeshed_points(const std::vector<perception::DepthView>& views,
                                             const Eigen::AlignedBox3d& region,
                                             const TriangleMesh& collision_mesh,
                                             const std::optional<Eigen::Vector4d>& support) {
  const robots::TriangleTree mesh(collision_mesh.vertices, collision_mesh.triangles);
  const perception::SupportHeight height(support);
  const double margin = perception::DepthSurfaceOptions().plane_margin;
  std::vector<Eigen::Vector3d> out, points;
  for (const perception::DepthView& view : views) {
    points.resize(static_cast<std::size_t>(view.image.valid_count()));
    const std::size_t kept = perception::back_project(view, region, points.data()).kept;
    for (std::size_t i = 0; i < kept; ++i)
      if (height(points[i]) > margin &&
          !mesh.touches_capsule(points[i], points[i], kMeasurementSlack))
        out.push_back(points[i]);
  }
  return out;
}

void loop_tube(const servo::Points& loop, double radius, TriangleMesh& mesh) {
  std::vector<Eigen::Vector3d>& vertices = mesh.vertices;
  std::vector<Eigen::Vector3i>& triangles = mesh.triangles;
  constexpr int kSides = 6;
  const int n = static_cast<int>(loop.size());
  const int first = static_cast<int>(vertices.size());
  // Rings of vertices around each loop point, in the plane normal to the mean of its two
  // segments; the ring's frame is carried along the loop (parallel transport), so neighbouring
  // rings line up and the band between them does not twist.
  Eigen::Vector3d u = Eigen::Vector3d::Zero();
  for (int i = 0; i < n; ++i) {
    const Eigen::Vector3d tangent = (loop[(i + 1) % n] - loop[(i + n - 1) % n]).normalized();
    u = (i == 0) ? tangent.unitOrthogonal() : (u - tangent * tangent.dot(u));
    if (u.norm() < 1e-9) u = tangent.unitOrthogonal();  // a hairpin turn
    u.normalize();
    const Eigen::Vector3d v = tangent.cross(u);
    for (int k = 0; k < kSides; ++k) {
      const double a = 2.0 * 3.14159265358979323846 * k / kSides;
      vertices.push_back(loop[i] + radius * (std::cos(a) * u + std::sin(a) * v));
    }
  }
  for (int i = 0; i < n; ++i) {
    const int a = first + i * kSides, b = first + ((i + 1) % n) * kSides;
    for (int k = 0; k < kSides; ++k) {
      const int k1 = (k + 1) % kSides;
      triangles.emplace_back(a + k, a + k1, b + k1);
      triangles.emplace_back(a + k, b + k1, b + k);
    }
  }
}

std::string insecure_reason(const SecureClaspReport& check) {
  if (check.timed_out) return "the time limit ended the check";
  if (check.start_in_collision) return "the closed hand touches the object";
  if (check.escape_stage.empty() || check.escape_stage == "random_motions")
    return "the object got free in " + std::to_string(check.escaped_sequences) + " of " +
           std::to_string(check.sequences) + " sequences of random motions";
  if (check.escape_stage == "escape_search")
    return "the escape search found a way out for the object (random motions held it)";
  return "the object got free under the " + check.escape_stage +
         " pull without rising against it (random motions held it)";
}

double closable_tolerance(const ClaspPlanningOptions& planning, double goal_linking) {
  return planning.closable_linking > 0 ? std::min(planning.closable_linking, goal_linking)
                                       : goal_linking;
}

bool closed_hand_links(const std::vector<double>& finger_linking, double threshold) {
  const std::size_t n = finger_linking.size();
  if (n == 0) return false;
  // Summed in curve order, as eq. 4's task feature does: the same mean to the last bit.
  const double sum = std::accumulate(finger_linking.begin(), finger_linking.end(), 0.0);
  if (sum / static_cast<double>(n) >= threshold) return true;
  const double lowest = *std::min_element(finger_linking.begin(), finger_linking.end());
  return n >= 3 && (sum - lowest) / static_cast<double>(n - 1) >= threshold;
}

namespace {

// close_and_check at one open pose.
ClaspCandidate close_and_check_at(const ClaspScene& scene, const Eigen::VectorXd& q_open,
                                  ClaspTimings& timings, bool refuse_unlinked) {
  ClaspCandidate c;
  auto t = Clock::now();
  c.q_closed =
      close_fingers(scene.robot, scene.world, q_open, scene.planning.closing, &c.unseen_stops);
  timings.closing += since(t);
  // A closed hand that falls below the goal region the tree stopped in is no clasp: refused at
  // once.
  const servo::TaskState closed = scene.controller.project(c.q_closed);
  c.closed_linking = closed.linking;
  c.refused =
      refuse_unlinked && !closed_hand_links(closed.finger_linking,
                                            closable_tolerance(scene.planning, scene.goal_linking));
  if (c.refused) return c;
  t = Clock::now();
  c.check = scene.checker.check(c.q_closed, scene.loop.points, &c.screened_out);
  timings.verification += since(t);
  return c;
}

}  // namespace

std::vector<Eigen::VectorXd> deepen_to_linking_goal(const ClaspScene& scene, Eigen::VectorXd q) {
  constexpr int kSteps = 30;
  std::vector<Eigen::VectorXd> path;
  servo::ClaspController& controller = scene.controller;
  controller.forget_direction();
  servo::TaskState x = controller.project(q);
  if (x.nearest_target < 0 || x.linking >= scene.goal_linking) return path;
  const Eigen::Vector3d target = controller.targets()[x.nearest_target].point;
  for (int s = 0; s < kSteps && x.linking < scene.goal_linking; ++s) {
    Eigen::VectorXd next = controller.step(q, target, 1.0);
    if (!scene.world.motion_free(q, next, scene.planning.collision_resolution)) break;
    q = std::move(next);
    path.push_back(q);
    x = controller.project(q);
  }
  controller.forget_direction();  // the search's next step starts elsewhere
  return path;
}

ClaspCandidate close_and_check(const ClaspScene& scene, const Eigen::VectorXd& q_open,
                               ClaspTimings& timings, bool refuse_unlinked) {
  ClaspCandidate first = close_and_check_at(scene, q_open, timings, refuse_unlinked);
  if (first.check.secure || first.check.timed_out) return first;
  // Deeper before closing again: straight along the approach to contact, else the controller on
  // to the hand's linking goal.
  for (int way = 0; way < 2; ++way) {
    const auto t = Clock::now();
    std::vector<Eigen::VectorXd> approach =
        way == 0 ? approach_until_contact(scene.robot, scene.world, q_open, scene.planning.approach)
                 : deepen_to_linking_goal(scene, q_open);
    timings.closing += since(t);
    if (approach.empty()) continue;
    ClaspCandidate deeper = close_and_check_at(scene, approach.back(), timings, refuse_unlinked);
    if (!deeper.check.secure) continue;
    deeper.approach = std::move(approach);
    deeper.deepened = way == 1;
    return deeper;
  }
  return first;
}

}  // namespace claspplan::tsrrt
