// Plan a clasp from depth images with the library alone (tsrrt/clasp_setup.hpp): no scenario file,
// no command line. The purse's example depth files stand in for a real camera's.
//
//   claspplan_api_example [FOLDER]    (depth files go to FOLDER, else to a temporary folder)
//
// Exit 0 on a verified clasp, 1 when there is none, 2 on an error (bad input).
#include <cstdio>
#include <exception>
#include <filesystem>
#include <memory>
#include <string>
#include <vector>

#include "examples/objects.hpp"
#include "perception/pipeline.hpp"
#include "robots/robot_model.hpp"
#include "tsrrt/clasp_setup.hpp"

using namespace claspplan;

int main(int argc, char** argv) try {
  // 1. Depth images with their cameras: the purse on a table, seen by two depth cameras.
  const std::string dir =
      argc > 1 ? argv[1]
               : (std::filesystem::temp_directory_path() / "claspplan_api_example").string();
  std::vector<std::string> images, cameras;
  for (const auto& [png, yaml] : objects::write_purse_depth_example(dir)) {
    images.push_back(png);
    cameras.push_back(yaml);
  }
  perception::PerceptionInputs inputs = perception::load_inputs(images, cameras);
  // The cameras are calibrated in the table's frame (the purse at its origin); the table stands
  // 0.55 m in front of the robot, along the robot's x axis.
  for (auto& view : inputs.depth_views)
    view.camera.T_world_camera.pretranslate(Eigen::Vector3d(0.55, 0, 0));

  // 2. The request: robot and start, object, environment, options.
  tsrrt::ClaspRequest request;
  request.robot = std::make_shared<const robots::RobotModel>(robots::load_robot("kr5_sdh"));
  request.start = (Eigen::VectorXd(6) << 0, -1.5707963, 1.5707963, 0, 1.5707963, 0).finished();
  request.object = std::move(inputs);
  tsrrt::EnvironmentBox floor;  // the floor, its top at z = 0
  floor.pose.translation() = Eigen::Vector3d(0.5, 0, -0.025);
  floor.size = Eigen::Vector3d(2.0, 2.0, 0.05);
  request.environment.push_back(floor);
  request.targets = 9;
  // Keep the object's points: the robot's reach, above the floor.
  request.perception.workspace =
      Eigen::AlignedBox3d(Eigen::Vector3d(0.2, -0.4, 0.01), Eigen::Vector3d(0.95, 0.4, 0.7));
  request.planning.planner.pre_expansions = 200;
  request.seed = 1;
  request.max_cycles = 300;  // a bound by cycles, not seconds: the same plan on any machine
  request.progress = [](const std::string& line) { std::fprintf(stderr, "%s\n", line.c_str()); };

  // 3. Plan, close the fingers, prune, verify.
  const tsrrt::ClaspResult result = tsrrt::plan_clasp(request);

  // 4. The outcome.
  std::printf("verified: %s (%s)\n", result.verified ? "yes" : "no", result.reason.c_str());
  if (const perception::Loop* loop = result.chosen_loop())
    std::printf("loop: rank %d of %zu, %zu targets (%s)\n", loop->rank, result.object.loops.size(),
                result.targets.size(), loop->reason.c_str());
  const double seconds = result.timings.perception + result.timings.search + result.timings.pruning;
  std::printf("%d cycles, %d nodes, %zu waypoints, %.2f s\n", result.statistics.cycles,
              result.statistics.nodes, result.motion.waypoints.size(), seconds);
  if (!result.motion.waypoints.empty()) {
    std::printf("virtual linking %.3f (per finger:", result.final_state.virtual_linking);
    for (double l : result.final_state.finger_virtual_linking) std::printf(" %.3f", l);
    std::printf(")\n");
  }
  return result.status == tsrrt::ClaspStatus::kSuccess ? 0 : 1;
} catch (const std::exception& e) {  // InputError: bad input
  std::fprintf(stderr, "error: %s\n", e.what());
  return 2;
}
