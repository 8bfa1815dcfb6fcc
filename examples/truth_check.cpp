#include "examples/truth_check.hpp"

#include "examples/result_file.hpp"
#include "robots/collision_world.hpp"

namespace claspplan::cli {

TruthContact check_path_against_truth(const Scenario& scenario, const std::string& result_json) {
  TruthContact out;
  const std::optional<TriangleMesh> scene = rendered_scene(scenario);
  if (!scene) return out;
  const ResultFile r = read_result_file(result_json, true);
  std::size_t n = r.waypoints.size();
  if (n < 2) return out;
  const int arm = r.model.arm_dof;
  if (r.waypoints[n - 1].head(arm) == r.waypoints[n - 2].head(arm)) --n;  // the closing

  robots::CollisionWorld world(r.model);
  world.set_object(scene->vertices, scene->triangles);
  world.set_self_collision(false);  // the planner's own business; this is about the world
  world.set_motion_travel(kTruthTravel);
  out.checked = true;
  for (std::size_t i = 0; i + 1 < n; ++i) {
    ++out.segments;
    robots::CollisionReport report;
    if (!world.motion_free(r.waypoints[i], r.waypoints[i + 1], kTruthResolution, &report)) {
      out.touches = true;
      out.segment = static_cast<int>(i);
      out.what = report.first + " and " + report.second;
      break;
    }
  }
  return out;
}

}  // namespace claspplan::cli
