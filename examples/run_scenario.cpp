#include "examples/run_scenario.hpp"

#include <chrono>
#include <filesystem>
#include <fstream>
#include <limits>

#include "examples/command.hpp"
#include "examples/result_pictures.hpp"
#include "robots/collision_world.hpp"
#include "robots/kinematics.hpp"
#include "servo/controller_run.hpp"
#include "tsrrt/clasp_planning.hpp"

namespace claspplan::cli {
namespace {

using Clock = std::chrono::steady_clock;
using nlohmann::json;

// The loop's material in the secure-clasp check (m): see tsrrt::loop_tube().
constexpr double kLoopTubeRadius = 0.003;

double since(Clock::time_point t) {
  return std::chrono::duration<double>(Clock::now() - t).count();
}

json to_json(const Eigen::VectorXd& v) {
  return std::vector<double>(v.data(), v.data() + v.size());
}
json to_json(const Eigen::Vector3d& v) {
  return {v.x(), v.y(), v.z()};
}
json to_json(const std::vector<Eigen::Vector3d>& points) {
  json a = json::array();
  for (const auto& p : points) a.push_back(to_json(p));
  return a;
}

void write_json(const std::string& path, const json& j) {
  std::ofstream out(path);
  out << j.dump(2) << "\n";
  if (!out) throw std::runtime_error("cannot write " + path);
}

// The claspable loop to clasp: the one nearest the scenario's hint, else the best ranked.
const perception::Loop* choose_loop(const perception::ObjectModel& object,
                                    const std::optional<Eigen::Vector3d>& hint) {
  const perception::Loop* chosen = nullptr;
  double best = std::numeric_limits<double>::infinity();
  for (const auto& loop : object.loops) {
    if (!loop.claspable) continue;
    if (!hint) return &loop;  // ranked best first
    for (const auto& p : loop.points) {
      if ((p - *hint).norm() < best) best = (p - *hint).norm(), chosen = &loop;
    }
  }
  return chosen;
}

// The planner's sample box: object and hand start, with room around them.
void fit_sample_box(tsrrt::PlannerParameters& p, const perception::ObjectModel& object,
                    const Eigen::Vector3d& hand_start) {
  Eigen::AlignedBox3d box = perception::bounds(object.cloud);
  box.extend(hand_start);
  p.sample_min = box.min() - Eigen::Vector3d::Constant(0.15);
  p.sample_max = box.max() + Eigen::Vector3d::Constant(0.15);
}

}  // namespace

RunOutcome run_scenario(const Scenario& scenario, const RunOptions& options) {
  const auto t_start = Clock::now();
  const auto say = [&](const std::string& m) {
    if (!options.quiet) progress(m);
  };
  Scenario s = scenario;
  if (options.seed) {
    s.seed = *options.seed;
    s.perception.seed = s.planning.planner.seed = s.planning.secure.seed = *options.seed;
  }
  if (options.time_limit) s.planning.planner.time_limit = *options.time_limit;

  const robots::RobotModel model = robots::load_robot(s.robot);
  const Eigen::VectorXd q_start = model.complete_q(s.start);
  json timing;

  // Perception: the object's loops, the loop to clasp and its targets.
  say("perceiving the object ...");
  auto t = Clock::now();
  s.perception.progress = options.quiet ? nullptr : std::function<void(const std::string&)>(say);
  const perception::PerceptionInputs inputs = scenario_inputs(s);
  std::filesystem::create_directories(options.out_dir);
  // Synthetic depth images are kept, so they can be looked at and used as depth files.
  for (std::size_t i = 0; i < s.object.cameras.size(); ++i) {
    const std::string stem = options.out_dir + "/depth_" + std::to_string(i);
    perception::write_depth_png(inputs.depth_views[i].image, inputs.depth_views[i].camera,
                                stem + ".png");
    perception::write_camera_yaml(inputs.depth_views[i].camera, stem + ".yaml");
  }
  const perception::ObjectModel object = perception::build_object_model(inputs, s.perception);
  timing["perception"] = since(t);
  say("  " + std::to_string(object.cloud.size()) + " points, d = " + std::to_string(object.d) +
      " m, beta1 = " + std::to_string(object.beta1));

  json result = {{"scenario", s.path},
                 {"robot", s.robot},
                 {"seed", s.seed},
                 {"mode", options.controller_only ? "controller" : "planner"}};
  json joint_names = json::array();
  for (const auto& j : model.joints) joint_names.push_back(j.name);
  result["joint_names"] = joint_names;
  const auto finish = [&](RunOutcome outcome) {
    timing["total"] = since(t_start);
    result["reason"] = outcome.summary["reason"];
    write_json(options.out_dir + "/result.json", result);
    write_json(options.out_dir + "/timing.json", timing);
    outcome.summary["out"] = options.out_dir;
    return outcome;
  };

  const perception::Loop* loop = choose_loop(object, s.loop_hint);
  if (!loop) {
    std::string why =
        object.loops.empty() ? "the object has no loops (beta1 = 0)" : "no claspable loop: ";
    for (std::size_t i = 0; i < object.loops.size() && i < 3; ++i) {
      why += (i ? "; " : "") + object.loops[i].reason;
    }
    result["success"] = false;
    return finish({kNoAnswer, {{"success", false}, {"verified", false}, {"reason", why}}});
  }
  std::vector<servo::ClaspTarget> targets;
  for (const auto& g : perception::clasp_targets(loop->points, s.targets)) {
    targets.push_back({g.p, g.tangent});
  }
  result["loop"] = to_json(loop->points);
  json targets_json = json::array();
  for (const auto& g : targets) {
    targets_json.push_back({{"p", to_json(g.point)}, {"tangent", to_json(g.tangent)}});
  }
  result["targets"] = targets_json;

  // The collision world: the robot, the object's K_d triangles and the static environment.
  SceneGeometry scene{model, {}, s.boxes, loop->points};
  for (const auto& p : object.complex.points) scene.object.vertices.push_back(p);
  for (int i = 0; i < static_cast<int>(object.complex.triangles.size()); ++i) {
    const auto v = object.complex.triangle_vertices(i);
    scene.object.triangles.emplace_back(v[0], v[1], v[2]);
  }
  if (scene.object.triangles.empty()) {
    throw std::invalid_argument(s.path +
                                ": the object's complex K_d has no triangles to collide with "
                                "(raise perception.d or the point count)");
  }
  // The collision model everywhere (planning, closing, verification): K_d and the loop's tube.
  tsrrt::loop_tube(loop->points, kLoopTubeRadius, scene.object.vertices, scene.object.triangles);
  robots::CollisionWorld world(model);
  world.set_object(scene.object.vertices, scene.object.triangles);
  for (const auto& b : s.boxes) world.add_box(b.pose, b.size);
  robots::CollisionReport contact;
  if (world.in_collision(q_start, &contact)) {
    throw std::invalid_argument(s.path + ": the start configuration is in collision (" +
                                contact.first + " with " + contact.second + ")");
  }
  result["object_mesh"] = {{"vertices", to_json(scene.object.vertices)},
                           {"triangles", json::array()}};
  for (const auto& tri : scene.object.triangles) {
    result["object_mesh"]["triangles"].push_back({tri[0], tri[1], tri[2]});
  }

  servo::ClaspController controller(model, loop->points, targets, s.controller);
  const double goal_linking =
      s.planning.goal_linking > 0.0 ? s.planning.goal_linking : model.vlink_goal;
  std::vector<Eigen::VectorXd> path;
  json summary;
  bool success = false;

  if (options.controller_only) {
    say("running the controller alone toward the nearest clasp target ...");
    t = Clock::now();
    servo::ControllerRunOptions ro = s.controller_run;
    ro.goal_linking = goal_linking;
    const servo::ControllerRun run = servo::run_controller(controller, world, q_start, ro);
    timing["controller"] = since(t);
    path = run.waypoints;
    success = run.success;
    result["steps"] = static_cast<int>(run.waypoints.size()) - 1;
    result["collided"] = run.collided;
    result["target"] = run.target;
    result["linking_history"] = run.linking_history;
    summary = {{"success", success},
               {"reason", run.reason},
               {"steps", result["steps"]},
               {"collided", run.collided},
               {"seconds", timing["controller"]}};
  } else {
    tsrrt::PlannerParameters pp = s.planning.planner;
    if (!s.planning.sample_box_given)
      fit_sample_box(pp, object, controller.project(q_start).position);
    // A goal node is closed and checked at once; with verify_in_search an insecure clasp is
    // rejected and the search goes on, else the first goal ends it (the paper's order).
    Eigen::VectorXd q_closed;
    tsrrt::SecureClaspReport check;
    int candidates = 0;
    double closing_seconds = 0.0, verification_seconds = 0.0;
    const auto close_and_verify = [&](const Eigen::VectorXd& q_goal) {
      ++candidates;
      auto t0 = Clock::now();
      q_closed = tsrrt::close_fingers(model, world, q_goal, s.planning.closing);
      closing_seconds += since(t0);
      say("  clasp candidate " + std::to_string(candidates) + ": closing the fingers and " +
          "verifying (" + std::to_string(s.planning.secure.sequences) + " x " +
          std::to_string(s.planning.secure.motions) + " random motions of the object) ...");
      t0 = Clock::now();
      check = tsrrt::check_secure_clasp(model, scene.object.vertices, scene.object.triangles,
                                        q_closed, loop->points, s.planning.secure);
      verification_seconds += since(t0);
      if (!check.secure) {
        say("  rejected: the object got free in " + std::to_string(check.escaped_sequences) +
            " of " + std::to_string(check.sequences) + " sequences");
      }
      return check.secure || !s.planning.verify_in_search;
    };
    tsrrt::ClaspProblem problem(controller, world, goal_linking, s.planning.position_tolerance,
                                s.planning.collision_resolution, close_and_verify);
    std::vector<tsrrt::TaskPoint> goals;
    for (const auto& g : targets) goals.push_back({g.point, 1.0});  // x_goal = (p, 1.0), Alg. 1
    say("planning (TS-RRT, " + std::to_string(goals.size()) + " clasp goals) ...");
    t = Clock::now();
    const tsrrt::PlanResult plan = tsrrt::build_ts_rrt(problem, q_start, goals, pp);
    const double planning_seconds = since(t);
    timing["planning"] = planning_seconds - closing_seconds - verification_seconds;
    timing["closing"] = closing_seconds;
    timing["verification"] = verification_seconds;
    result["cycles"] = plan.cycles;
    result["nodes"] = plan.nodes;
    result["control_steps"] = plan.control_steps;
    result["clasp_candidates"] = candidates;
    summary = {{"cycles", plan.cycles},
               {"nodes", plan.nodes},
               {"seconds", planning_seconds},
               {"clasp_candidates", candidates}};
    if (candidates > 0) {
      result["verification"] = {{"secure", check.secure},
                                {"start_in_collision", check.start_in_collision},
                                {"sequences", check.sequences},
                                {"escaped_sequences", check.escaped_sequences},
                                {"min_open_linking", check.min_open_linking},
                                {"max_open_linking", check.max_open_linking},
                                {"min_virtual_linking", check.min_virtual_linking},
                                {"max_virtual_linking", check.max_virtual_linking}};
    }
    if (!plan.success) {
      result["success"] = false;
      result["verified"] = false;
      summary["success"] = summary["verified"] = false;
      summary["reason"] = plan.reason;
      if (options.pictures)
        write_tree_picture(scene, q_start, plan, {}, options.out_dir + "/tree.png");
      return finish({kNoAnswer, summary});
    }
    say("  clasp found after " + std::to_string(plan.cycles) + " cycles, " +
        std::to_string(plan.nodes) + " nodes; pruning the path ...");
    result["target"] = plan.goal_index;
    t = Clock::now();
    path = tsrrt::prune_path(problem, plan.path, s.planning.prune_attempts, s.seed);
    timing["pruning"] = since(t);
    result["unpruned_waypoints"] = static_cast<int>(plan.path.size());
    if (q_closed != path.back()) path.push_back(q_closed);
    success = check.secure;
    result["verified"] = check.secure;
    summary["success"] = true;
    summary["verified"] = check.secure;
    summary["reason"] = check.secure ? "verified clasp"
                                     : "the clasp failed verification: the object got free in " +
                                           std::to_string(check.escaped_sequences) + " of " +
                                           std::to_string(check.sequences) + " sequences";
    if (options.pictures)
      write_tree_picture(scene, q_start, plan, path, options.out_dir + "/tree.png");
  }

  // Linking at the final pose (paper eq. 4 and Fig. 6).
  const servo::TaskState final_state = controller.project(path.back());
  robots::RobotData data(model);
  robots::FingerCurvesData curves;
  robots::finger_curves(model, path.back(), data, curves, false);
  json open = json::array();
  for (const auto& c : curves.points) {
    open.push_back(std::abs(servo::gauss_linking(loop->points, true, c, false)));
  }
  json waypoints = json::array();
  for (const auto& q : path) waypoints.push_back(to_json(q));
  result["waypoints"] = waypoints;
  result["final_q"] = to_json(path.back());
  result["success"] = success;
  result["virtual_linking"] = final_state.linking;
  result["finger_virtual_linking"] = final_state.finger_linking;
  result["finger_open_linking"] = open;
  summary["virtual_linking"] = final_state.linking;
  if (!options.controller_only) summary["success"] = true;

  if (options.pictures) {
    t = Clock::now();
    write_clasp_views(scene, path.back(), options.out_dir);
    write_path_poses(scene, path, options.out_dir + "/poses.png");
    timing["pictures"] = since(t);
  }
  return finish({success ? kOk : kNoAnswer, summary});
}

}  // namespace claspplan::cli
