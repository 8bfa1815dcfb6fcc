#include "examples/run_scenario.hpp"

#include <chrono>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <limits>

#include "examples/command.hpp"
#include "examples/result_pictures.hpp"
#include "perception/depth_surface.hpp"
#include "robots/collision_world.hpp"
#include "robots/hand_size.hpp"
#include "servo/controller_run.hpp"
#include "tsrrt/clasp_planning.hpp"

namespace claspplan::cli {
namespace {

using Clock = std::chrono::steady_clock;
using nlohmann::json;

// The loop's material in the collision model (m): see tsrrt::loop_tube().
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

std::string no_loop_reason(const perception::ObjectModel& object) {
  if (object.loops.empty() && object.unstable_loops > 0)
    return "no stable loop: all " + std::to_string(object.unstable_loops) +
           " loops of K_d fill in by d' = " + std::to_string(object.persistence_d) +
           " m (gaps or holes narrower than a finger's)";
  if (object.loops.empty()) return "the object has no loops (beta1 = 0)";
  std::string why = "no claspable loop: ";
  for (std::size_t i = 0; i < object.loops.size() && i < 3; ++i) {
    why += (i ? "; " : "") + object.loops[i].reason;
  }
  return why;
}

// The planner's default sample box: object and hand start, with 0.3 m of room around them, so
// that the tree can find its way around obstacles next to the object.
void fit_sample_box(tsrrt::PlannerParameters& p, const perception::ObjectModel& object,
                    const Eigen::Vector3d& hand_start) {
  Eigen::AlignedBox3d box = perception::bounds(object.cloud);
  box.extend(hand_start);
  p.sample_min = box.min() - Eigen::Vector3d::Constant(0.3);
  p.sample_max = box.max() + Eigen::Vector3d::Constant(0.3);
}

// The object's collision model everywhere (planning, closing, verification): the surface the
// depth cameras saw (K_d is for topology: its long triangles web across holes), else K_d's
// triangles for clouds and whole-surface samples; and a thin tube along the clasped loop, so the
// loop itself is always material.
RenderMesh collision_mesh(const perception::ObjectModel& object, const perception::Loop& loop,
                          const perception::PerceptionOptions& options,
                          const std::string& scenario_path) {
  RenderMesh mesh;
  if (!object.views.empty()) {
    perception::DepthSurfaceOptions so;
    so.workspace = options.workspace;
    so.support_plane = object.support_plane;
    const perception::TriangleMesh seen = perception::depth_surface_mesh(object.views, so);
    mesh.vertices = seen.vertices;
    for (const auto& t : seen.triangles) mesh.triangles.emplace_back(t[0], t[1], t[2]);
  } else {
    mesh.vertices = object.complex.points;
    for (int i = 0; i < static_cast<int>(object.complex.triangles.size()); ++i) {
      const auto v = object.complex.triangle_vertices(i);
      mesh.triangles.emplace_back(v[0], v[1], v[2]);
    }
  }
  if (mesh.triangles.empty()) {
    throw std::invalid_argument(scenario_path +
                                ": the object has no surface to collide with (no depth surface "
                                "and no K_d triangles: raise perception.d or the point count)");
  }
  tsrrt::loop_tube(loop.points, kLoopTubeRadius, mesh.vertices, mesh.triangles);
  return mesh;
}

json scene_json(const SceneGeometry& scene) {
  json boxes = json::array();
  for (const auto& b : scene.boxes) {
    json rows = json::array();
    for (int r = 0; r < 3; ++r) rows.push_back(to_json(Eigen::Vector3d(b.pose.linear().row(r))));
    boxes.push_back({{"size", to_json(b.size)},
                     {"position", to_json(Eigen::Vector3d(b.pose.translation()))},
                     {"rotation", rows}});
  }
  json triangles = json::array();
  for (const auto& t : scene.object.triangles) triangles.push_back({t[0], t[1], t[2]});
  return {
      {"environment", {{"boxes", boxes}}},
      {"object_mesh", {{"vertices", to_json(scene.object.vertices)}, {"triangles", triangles}}}};
}

// What the controller-only or the planned phase produced.
struct Motion {
  std::vector<Eigen::VectorXd> path;  // start to final pose; empty when none was found
  bool success = false;
  json summary;  // the command's --json object so far
};

Motion run_controller_only(const Scenario& s, servo::ClaspController& controller,
                           robots::CollisionWorld& world, const Eigen::VectorXd& q_start,
                           double goal_linking, json& result, json& timing) {
  const auto t = Clock::now();
  servo::ControllerRunOptions ro = s.controller_run;
  ro.goal_linking = goal_linking;
  const servo::ControllerRun run = servo::run_controller(controller, world, q_start, ro);
  timing["controller"] = since(t);
  const int steps = static_cast<int>(run.waypoints.size()) - 1;
  result["steps"] = steps;
  result["collided"] = run.collided;
  result["target"] = run.target;
  result["linking_history"] = run.linking_history;
  return {run.waypoints,
          run.success,
          {{"success", run.success},
           {"reason", run.reason},
           {"steps", steps},
           {"collided", run.collided},
           {"seconds", timing["controller"]}}};
}

// TS-RRT with every goal node closed and verified at once (paper Sec. IV-D, V-A); with
// verify_in_search an insecure clasp is rejected and the search goes on.
Motion plan_clasp(Scenario& s, const SceneGeometry& scene, servo::ClaspController& controller,
                  robots::CollisionWorld& world, const Eigen::VectorXd& q_start,
                  double goal_linking, const perception::ObjectModel& object,
                  const RunOptions& options, const std::function<void(const std::string&)>& say,
                  json& result, json& timing) {
  const robots::RobotModel& model = scene.model;
  tsrrt::PlannerParameters pp = s.planning.planner;
  if (!s.planning.sample_box_given) {
    fit_sample_box(pp, object, controller.project(q_start).position);
  }
  if (pp.time_limit > 0.0) {
    s.planning.secure.deadline = Clock::now() + std::chrono::duration_cast<Clock::duration>(
                                                    std::chrono::duration<double>(pp.time_limit));
  }
  Eigen::VectorXd q_closed;
  tsrrt::SecureClaspReport check;
  int candidates = 0, screened = 0;
  double closing_seconds = 0.0, verification_seconds = 0.0;
  const auto close_and_verify = [&](const Eigen::VectorXd& q_goal) {
    ++candidates;
    auto t = Clock::now();
    q_closed = tsrrt::close_fingers(model, world, q_goal, s.planning.closing);
    closing_seconds += since(t);
    // A closable pose whose closed hand stays below the goal is no clasp: refused at once.
    const double closed_linking = controller.project(q_closed).linking;
    if (closed_linking < goal_linking && s.planning.verify_in_search) {
      ++screened;
      say("  clasp candidate " + std::to_string(candidates) + ": the closed hand reaches virtual " +
          "linking " + std::to_string(closed_linking) + " only; refused");
      return false;
    }
    say("  clasp candidate " + std::to_string(candidates) + ": fingers closed; verifying (" +
        std::to_string(s.planning.secure.sequences) + " x " +
        std::to_string(s.planning.secure.motions) + " random motions of the object) ...");
    t = Clock::now();
    // Screening first: the first motions of the first sequences, as the full check runs them
    // (same seeds), so an escape there is an escape of the full check: the verdict is the same,
    // found sooner.
    tsrrt::SecureClaspOptions screen = s.planning.secure;
    screen.sequences = std::min(screen.sequences, 2);
    screen.motions = std::min(screen.motions, 100);
    check = tsrrt::check_secure_clasp(model, scene.object.vertices, scene.object.triangles,
                                      q_closed, scene.loop, screen);
    const bool screened_out = !check.secure;
    if (!screened_out) {
      check = tsrrt::check_secure_clasp(model, scene.object.vertices, scene.object.triangles,
                                        q_closed, scene.loop, s.planning.secure);
    }
    verification_seconds += since(t);
    if (!check.secure) {
      say("  rejected: the object got free in " + std::to_string(check.escaped_sequences) + " of " +
          std::to_string(check.sequences) + " sequences" +
          (screened_out ? " of the screening (the first motions of the full check)" : ""));
    }
    return check.secure || !s.planning.verify_in_search;
  };
  const double tolerance = s.planning.closable_linking > 0
                               ? std::min(s.planning.closable_linking, goal_linking)
                               : goal_linking;
  tsrrt::ClaspProblem problem(controller, world, tolerance, s.planning.position_tolerance,
                              s.planning.collision_resolution, close_and_verify);
  std::vector<tsrrt::TaskPoint> goals;
  for (const auto& g : controller.targets()) goals.push_back({g.point, 1.0});  // Alg. 1, line 9
  say("planning (TS-RRT, " + std::to_string(goals.size()) + " clasp goals) ...");
  auto t = Clock::now();
  const tsrrt::PlanResult plan = tsrrt::build_ts_rrt(problem, q_start, goals, pp);
  const double seconds = since(t);
  timing["planning"] = seconds - closing_seconds - verification_seconds;
  timing["closing"] = closing_seconds;
  timing["verification"] = verification_seconds;
  result["cycles"] = plan.cycles;
  result["nodes"] = plan.nodes;
  result["control_steps"] = plan.control_steps;
  result["clasp_candidates"] = candidates;
  result["clasp_candidates_screened"] = screened;
  const tsrrt::ConnectOutcomes& o = plan.outcomes;
  const json outcomes = {{"attempts", o.attempts},
                         {"accepted", o.accepted},
                         {"rejected", o.rejected},
                         {"contact_object", o.contact_object},
                         {"contact_environment", o.contact_environment},
                         {"self_collision", o.self_collision},
                         {"joint_limits", o.joint_limits},
                         {"stall", o.stall},
                         {"step_cap", o.step_cap},
                         {"time_limit", o.time_limit},
                         {"detours", o.detours},
                         {"extend_collisions", o.extend_collisions}};
  result["connect_outcomes"] = outcomes;
  if (candidates > screened) result["verification"] = verification_json(check);

  Motion m;
  m.summary = {{"cycles", plan.cycles},
               {"nodes", plan.nodes},
               {"seconds", seconds},
               {"clasp_candidates", candidates},
               {"success", plan.success}};
  m.summary["connect_outcomes"] = outcomes;
  if (!plan.success) {
    m.summary["verified"] = false;
    m.summary["reason"] = plan.reason;
    if (options.pictures)
      write_tree_picture(scene, q_start, plan, {}, options.out_dir + "/tree.png");
    return m;
  }
  say("  clasp found after " + std::to_string(plan.cycles) + " cycles, " +
      std::to_string(plan.nodes) + " nodes; pruning the path ...");
  result["target"] = plan.goal_index;
  result["unpruned_waypoints"] = static_cast<int>(plan.path.size());
  t = Clock::now();
  m.path = tsrrt::prune_path(problem, plan.path, s.planning.prune_attempts, s.seed);
  timing["pruning"] = since(t);
  if (q_closed != m.path.back()) m.path.push_back(q_closed);
  m.success = check.secure;
  m.summary["verified"] = check.secure;
  m.summary["reason"] = check.secure ? "verified clasp"
                                     : "the clasp failed verification: the object got free in " +
                                           std::to_string(check.escaped_sequences) + " of " +
                                           std::to_string(check.sequences) + " sequences";
  if (options.pictures)
    write_tree_picture(scene, q_start, plan, m.path, options.out_dir + "/tree.png");
  return m;
}

}  // namespace

RunOutcome run_scenario(const Scenario& scenario, const RunOptions& options) {
  const auto t_start = Clock::now();
  const std::function<void(const std::string&)> say = [&](const std::string& m) {
    if (!options.quiet) progress(m);
  };
  Scenario s = scenario;
  if (options.seed) {
    s.seed = *options.seed;
    s.perception.seed = s.planning.planner.seed = s.planning.secure.seed = *options.seed;
  }
  if (options.max_cycles) {
    s.planning.planner.max_cycles = *options.max_cycles;
    s.planning.planner.time_limit = 0.0;
  }
  if (options.time_limit) s.planning.planner.time_limit = *options.time_limit;
  const robots::RobotModel model = robots::load_robot(s.robot);
  const Eigen::VectorXd q_start = model.complete_q(s.start);
  // Loops are chosen for this hand: holes its fingers pass, bars its closed hand encloses.
  const robots::HandSize hand = robots::hand_size(model);
  s.perception.finger_thickness = hand.finger_thickness;
  s.perception.closed_aperture = hand.closed_aperture;
  json timing;
  json result = {{"scenario", s.path},
                 {"robot", s.robot},
                 {"seed", s.seed},
                 {"mode", options.controller_only ? "controller" : "planner"}};
  json& joint_names = result["joint_names"] = json::array();
  for (const auto& j : model.joints) joint_names.push_back(j.name);
  const auto finish = [&](int exit_code, json summary) {
    timing["total"] = since(t_start);
    result["reason"] = summary["reason"];
    write_json(options.out_dir + "/result.json", result);
    write_json(options.out_dir + "/timing.json", timing);
    summary["out"] = options.out_dir;
    return RunOutcome{exit_code, summary};
  };

  // Perception. The inputs are read (and validated) before any progress line, so that a bad file
  // gives a single error line; synthetic depth images are kept as depth files.
  auto t = Clock::now();
  const perception::PerceptionInputs inputs = scenario_inputs(s);
  std::filesystem::create_directories(options.out_dir);
  for (std::size_t i = 0; i < s.object.cameras.size(); ++i) {
    const std::string stem = options.out_dir + "/depth_" + std::to_string(i);
    perception::write_depth_png(inputs.depth_views[i].image, inputs.depth_views[i].camera,
                                stem + ".png");
    perception::write_camera_yaml(inputs.depth_views[i].camera, stem + ".yaml");
  }
  say("perceiving the object ...");
  s.perception.progress = options.quiet ? nullptr : say;
  const perception::ObjectModel object = perception::build_object_model(inputs, s.perception);
  timing["perception"] = since(t);
  result["hand"] = {{"finger_thickness", hand.finger_thickness},
                    {"closed_aperture", hand.closed_aperture}};
  json& loops_json = result["loops"] = json::array();
  for (const auto& l : object.loops)
    loops_json.push_back({{"rank", l.rank}, {"verdict", l.verdict}, {"reason", l.reason}});
  const perception::Loop* loop = choose_loop(object, s.loop_hint);
  if (!loop) {
    result["success"] = false;
    return finish(kNoAnswer,
                  {{"success", false}, {"verified", false}, {"reason", no_loop_reason(object)}});
  }
  std::vector<servo::ClaspTarget> targets;
  json& targets_json = result["targets"] = json::array();
  for (const auto& g : perception::clasp_targets(*loop, s.targets, hand.closed_aperture)) {
    targets.push_back({g.p, g.tangent});
    targets_json.push_back({{"p", to_json(g.p)}, {"tangent", to_json(g.tangent)}});
  }
  result["loop"] = to_json(loop->points);
  result["loop_choice"] = {{"rank", loop->rank},
                           {"reason", loop->reason},
                           {"hole_width", loop->hole_width},
                           {"bar_thickness", loop->bar_thickness},
                           {"fit", loop->fit}};

  // The scene: the robot, the object's collision mesh and the static environment.
  const SceneGeometry scene{model, collision_mesh(object, *loop, s.perception, s.path), s.boxes,
                            loop->points};
  result.update(scene_json(scene));
  robots::CollisionWorld world(model);
  world.set_object(scene.object.vertices, scene.object.triangles);
  for (const auto& b : s.boxes) world.add_box(b.pose, b.size);
  robots::CollisionReport contact;
  if (world.in_collision(q_start, &contact)) {
    throw std::invalid_argument(s.path + ": the start configuration is in collision (" +
                                contact.first + " with " + contact.second + ")");
  }

  servo::ClaspController controller(model, loop->points, targets, s.controller);
  const double goal_linking =
      s.planning.goal_linking > 0.0 ? s.planning.goal_linking : model.vlink_goal;
  if (options.controller_only)
    say("running the controller alone toward the nearest clasp target ...");
  Motion m = options.controller_only
                 ? run_controller_only(s, controller, world, q_start, goal_linking, result, timing)
                 : plan_clasp(s, scene, controller, world, q_start, goal_linking, object, options,
                              say, result, timing);
  if (m.path.empty()) {
    result["success"] = false;
    result["verified"] = false;
    return finish(kNoAnswer, m.summary);
  }

  // The final pose: virtual linking (eq. 4) and the open curves' Gauss integrals (Fig. 6).
  const servo::TaskState final_state = controller.project(m.path.back());
  json& waypoints = result["waypoints"] = json::array();
  for (const auto& q : m.path) waypoints.push_back(to_json(q));
  result["final_q"] = to_json(m.path.back());
  result["success"] = m.success;
  if (!options.controller_only) result["verified"] = m.success;
  result["virtual_linking"] = final_state.linking;
  result["finger_virtual_linking"] = final_state.finger_linking;
  result["finger_open_linking"] = tsrrt::open_finger_linking(model, m.path.back(), loop->points);
  m.summary["virtual_linking"] = final_state.linking;
  m.summary["finger_virtual_linking"] = final_state.finger_linking;

  if (options.pictures) {
    t = Clock::now();
    write_clasp_views(scene, m.path.back(), options.out_dir);
    write_path_poses(scene, m.path, options.out_dir + "/poses.png");
    timing["pictures"] = since(t);
  }
  return finish(m.success ? kOk : kNoAnswer, m.summary);
}

json verification_json(const tsrrt::SecureClaspReport& v) {
  return {{"secure", v.secure},
          {"start_in_collision", v.start_in_collision},
          {"timed_out", v.timed_out},
          {"sequences", v.sequences},
          {"escaped_sequences", v.escaped_sequences},
          {"min_open_linking", v.min_open_linking},
          {"max_open_linking", v.max_open_linking},
          {"min_virtual_linking", v.min_virtual_linking},
          {"max_virtual_linking", v.max_virtual_linking}};
}

void print_run_summary(const json& s, bool controller_only) {
  const std::string reason = s.value("reason", std::string());
  if (controller_only) {
    std::printf("%s: %s after %d steps, virtual linking %.3f\n",
                s.value("success", false) ? "clasped" : "not clasped", reason.c_str(),
                s.value("steps", 0), s.value("virtual_linking", 0.0));
  } else if (s.value("verified", false)) {
    std::printf(
        "verified clasp: %d cycles after pre-expansion, %d nodes, %.2f s planning "
        "(the clasp checks included), virtual linking %.3f\n",
        s.value("cycles", 0), s.value("nodes", 0), s.value("seconds", 0.0),
        s.value("virtual_linking", 0.0));
  } else {
    std::printf("no verified clasp: %s\n", reason.c_str());
  }
  std::printf("result: %s/result.json, timing.json and pictures (*.png)\n",
              s.value("out", std::string()).c_str());
}

}  // namespace claspplan::cli
