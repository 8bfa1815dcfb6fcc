// Plan a clasp from depth images with the library alone: no scenario file, no command line. The
// demo's depth files (the paper's bag on a table, three depth cameras) stand in for a camera's.
// Built in this tree and, by the package test, against an installed claspplan.
//
//   claspplan_api_example DEPTH_FOLDER    (view_<i>.png with its camera file view_<i>.yaml)
//
// Exit 0 on a verified clasp, 1 when there is none, 2 on an error (bad input).
#include <cstdio>
#include <exception>
#include <filesystem>
#include <memory>
#include <string>
#include <vector>

#include <claspplan/perception/pipeline.hpp>
#include <claspplan/robots/robot_model.hpp>
#include <claspplan/tsrrt/clasp_setup.hpp>

using namespace claspplan;

int main(int argc, char** argv) try {
  if (argc != 2) {
    std::fprintf(stderr, "usage: %s DEPTH_FOLDER (e.g. examples/depth/bag_2)\n", argv[0]);
    return 2;
  }
  // 1. Depth images with their cameras (world frame: the robot's base_link).
  std::vector<std::string> images, cameras;
  for (int i = 0; std::filesystem::exists(std::filesystem::path(argv[1]) /
                                          ("view_" + std::to_string(i) + ".png"));
       ++i) {
    const std::string stem =
        (std::filesystem::path(argv[1]) / ("view_" + std::to_string(i))).string();
    images.push_back(stem + ".png");
    cameras.push_back(stem + ".yaml");
  }
  if (images.empty()) throw InputError(std::string(argv[1]) + ": no view_0.png");

  // 2. The request: robot and start, object, environment, options.
  tsrrt::ClaspRequest request;
  request.robot = std::make_shared<const robots::RobotModel>(robots::load_robot("kr5_sdh"));
  request.start = (Eigen::VectorXd(6) << 0, -1.9, 1.5707963, 0, 1.9, 0).finished();
  request.object = perception::load_inputs(images, cameras);
  tsrrt::EnvironmentBox floor, table;  // the floor's top at z = 0, a 20 cm table
  floor.pose.translation() = Eigen::Vector3d(0.5, 0, -0.025);
  floor.size = Eigen::Vector3d(2.5, 2.5, 0.05);
  table.pose.translation() = Eigen::Vector3d(0.55, 0, 0.1);
  table.size = Eigen::Vector3d(0.6, 0.6, 0.2);
  request.environment = {floor, table};
  request.loop_hint = Eigen::Vector3d(0.55, 0, 0.56);  // clasp the strap (the paper's loop)
  request.perception.targets = 23;
  // Keep the points above the table, around the object.
  request.perception.workspace =
      Eigen::AlignedBox3d(Eigen::Vector3d(0.46, -0.21, 0.204), Eigen::Vector3d(0.64, 0.21, 0.675));
  request.planning.planner.pre_expansions = 20;
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
  const double seconds = result.timings.perception + result.timings.scene + result.timings.search +
                         result.timings.pruning;
  std::printf("%d cycles, %d nodes, %zu waypoints, %.2f s\n", result.statistics.cycles,
              result.statistics.nodes, result.motion.waypoints.size(), seconds);
  if (!result.motion.waypoints.empty()) {
    std::printf("virtual linking %.3f (per finger:", result.final_state.virtual_linking);
    for (double l : result.final_state.finger_virtual_linking) std::printf(" %.3f", l);
    std::printf(")\n");
  }
  return result.succeeded() && result.verified ? 0 : 1;
} catch (const InputError& e) {  // bad input
  std::fprintf(stderr, "error: %s\n", e.what());
  return 2;
} catch (const std::exception& e) {  // a failure that is not the input's fault
  std::fprintf(stderr, "internal error: %s\n", e.what());
  return 3;
}
