#include "examples/run_scenario.hpp"

#include <chrono>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <memory>
#include <utility>

#include "examples/command.hpp"
#include "examples/result_pictures.hpp"
#include "perception/drawing.hpp"
#include "tsrrt/clasp_setup.hpp"
#include "tsrrt/elapsed.hpp"

namespace claspplan::cli {
namespace {

using nlohmann::json;
using tsrrt::Clock;
using tsrrt::since;

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

json outcomes_json(const tsrrt::ConnectOutcomes& o) {
  return {{"attempts", o.attempts},
          {"accepted", o.accepted},
          {"rejected", o.rejected},
          {"contact_object", o.contact_object},
          {"contact_environment", o.contact_environment},
          {"contact_unseen", o.contact_unseen},
          {"self_collision", o.self_collision},
          {"joint_limits", o.joint_limits},
          {"stall", o.stall},
          {"step_cap", o.step_cap},
          {"time_limit", o.time_limit},
          {"detours", o.detours},
          {"extend_collisions", o.extend_collisions},
          {"restarts", o.restarts},
          {"sampled", o.sampled},
          {"sampled_clasps", o.sampled_clasps},
          {"joined", o.joined}};
}

// The controller-only phase's part of result.json, timing.json and the summary.
json controller_json(const tsrrt::ClaspResult& r, json& result, json& timing) {
  timing["controller"] = r.timings.controller;
  const tsrrt::ClaspStatistics& st = r.statistics;
  result["steps"] = st.control_steps;
  result["collided"] = st.collided;
  result["target"] = r.motion.target;
  result["linking_history"] = st.linking_history;
  json summary = {{"success", r.succeeded()},
                  {"reason", r.reason},
                  {"steps", st.control_steps},
                  {"collided", st.collided},
                  {"seconds", timing["controller"]}};
  // The fingers touched the object in the goal region and were closed there, as the planner
  // closes its goal nodes: the clasp was checked (tsrrt::run_controller_only).
  if (st.clasp_candidates > 0) {
    timing["closing"] = r.timings.closing;
    timing["verification"] = r.timings.verification;
    if (st.clasp_candidates > st.clasp_candidates_screened)
      result["verification"] = verification_json(r.verification);
    summary["verified"] = result["verified"] = r.verified;
  }
  return summary;
}

// The planned phase's part (TS-RRT, closing, verification, pruning), with the tree picture.
json planner_json(const tsrrt::ClaspResult& r, const SceneGeometry& scene,
                  const RunOptions& options, json& result, json& timing) {
  const tsrrt::ClaspStatistics& st = r.statistics;
  timing["planning"] = r.timings.planning;
  timing["closing"] = r.timings.closing;
  timing["verification"] = r.timings.verification;
  result["cycles"] = st.cycles;
  result["nodes"] = st.nodes;
  result["control_steps"] = st.control_steps;
  result["clasp_candidates"] = st.clasp_candidates;
  result["clasp_candidates_screened"] = st.clasp_candidates_screened;
  result["targets_without_room"] = st.targets_without_room;
  const json outcomes = outcomes_json(st.connect_outcomes);
  result["connect_outcomes"] = outcomes;
  if (st.clasp_candidates > st.clasp_candidates_screened)
    result["verification"] = verification_json(r.verification);
  const bool found = !r.motion.waypoints.empty();
  json summary = {{"cycles", st.cycles},
                  {"nodes", st.nodes},
                  {"seconds", r.timings.search},
                  {"clasp_candidates", st.clasp_candidates},
                  {"success", found}};
  summary["connect_outcomes"] = outcomes;
  summary["verified"] = r.verified;
  summary["reason"] = r.reason;
  if (found) {
    result["target"] = r.motion.target;
    result["unpruned_waypoints"] = st.unpruned_waypoints;
    timing["pruning"] = r.timings.pruning;
  }
  if (options.pictures)
    write_tree_picture(scene, r.start, st, r.motion.waypoints, options.out_dir + "/tree.png");
  return summary;
}

}  // namespace

tsrrt::ClaspRequest clasp_request(const Scenario& s, const RunOptions& options,
                                  std::shared_ptr<const robots::RobotModel> robot,
                                  perception::PerceptionInputs inputs) {
  tsrrt::ClaspRequest request;
  request.robot = std::move(robot);
  request.start =
      Eigen::Map<const Eigen::VectorXd>(s.start.data(), static_cast<Eigen::Index>(s.start.size()));
  request.object = std::move(inputs);
  request.environment = s.boxes;
  request.loop_hint = s.loop_hint;
  request.goal_linking = s.goal_linking;
  request.perception = s.perception;
  request.controller = s.controller;
  request.controller_run = s.controller_run;
  request.planning = s.planning;
  request.mode =
      options.controller_only ? tsrrt::ClaspMode::kControllerOnly : tsrrt::ClaspMode::kPlan;
  request.search = options.search;
  request.seed = options.seed;
  request.max_cycles = options.max_cycles;
  request.time_limit = options.time_limit;
  request.stop = options.stop;
  request.name = s.path;
  return request;
}

namespace {

// One run of the scenario as given; `added_views` (the cameras run_scenario added) go into its
// result.json and summary.
RunOutcome run_once(const Scenario& scenario, const RunOptions& options, const json& added_views) {
  const auto t_start = Clock::now();
  const std::function<void(const std::string&)> say = [&](const std::string& m) {
    if (!options.quiet) progress(m);
  };
  Scenario s = scenario;
  if (options.seed) s.seed = *options.seed;  // the depth noise's (the stages': the request's)
  const auto robot = std::make_shared<const robots::RobotModel>(robots::load_robot(s.robot));
  const robots::RobotModel& model = *robot;
  for (const auto& w : model.warnings) say("warning: " + w);
  model.complete_q(s.start);  // a bad start is reported before any file is read
  place_in_front_of_hand(s, model);
  json timing;
  json result = {{"scenario", s.path},
                 {"robot", s.robot},
                 {"seed", s.seed},
                 {"mode", options.controller_only ? "controller" : "planner"}};
  if (!added_views.empty()) result["added_views"] = added_views;
  json& joint_names = result["joint_names"] = json::array();
  for (const auto& j : model.joints) joint_names.push_back(j.name);
  std::optional<perception::ViewSuggestion> next_view;  // the camera the run names, if any
  const auto finish = [&](int exit_code, json summary) {
    timing["total"] = since(t_start);
    result["reason"] = summary["reason"];
    write_json(options.out_dir + "/result.json", result);
    write_json(options.out_dir + "/timing.json", timing);
    summary["out"] = options.out_dir;
    if (!added_views.empty()) summary["added_views"] = added_views;
    return RunOutcome{exit_code, summary, next_view};
  };

  // The inputs are read (and validated) before any progress line, so that a bad file gives a
  // single error line; synthetic depth images are kept as depth files.
  const auto t = Clock::now();
  perception::PerceptionInputs inputs = scenario_inputs(s);
  std::filesystem::create_directories(options.out_dir);
  for (std::size_t i = 0; i < s.object.cameras.size(); ++i) {
    const std::string stem = options.out_dir + "/depth_" + std::to_string(i);
    perception::write_depth_png(inputs.depth_views[i].image, inputs.depth_views[i].camera,
                                stem + ".png");
    perception::write_camera_yaml(inputs.depth_views[i].camera, stem + ".yaml");
  }
  const double input_seconds = since(t);
  tsrrt::ClaspRequest request = clasp_request(s, options, robot, std::move(inputs));
  if (!options.quiet) request.progress = say;
  const tsrrt::ClaspResult r = tsrrt::plan_clasp(request);
  next_view = r.next_view;

  timing["perception"] = input_seconds + r.timings.perception;
  timing["scene"] = r.timings.scene;
  result["hand"] = {{"finger_thickness", r.hand.finger_thickness},
                    {"closed_aperture", r.hand.closed_aperture}};
  json& loops_json = result["loops"] = json::array();
  for (const auto& l : r.object.loops)
    loops_json.push_back(
        {{"rank", l.rank}, {"verdict", perception::verdict_name(l.verdict)}, {"reason", l.reason}});
  const perception::Loop* loop = r.chosen_loop();
  if (options.pictures && r.object.sensed) {
    // Through the chosen loop, else the first refused for what the sensors saw, else the first;
    // through the unseen space a next best view would see, when there is one.
    const perception::Loop* shown = loop;
    for (const auto& l : r.object.loops)
      if (!shown && (l.verdict == perception::LoopVerdict::kUnseenFarSide ||
                     l.verdict == perception::LoopVerdict::kEnclosed))
        shown = &l;
    if (!shown && !r.object.loops.empty()) shown = &r.object.loops.front();
    const Eigen::Vector3d centre = r.next_view ? r.next_view->target
                                   : shown     ? shown->centre
                                               : r.object.sensed->region().center();
    perception::draw_sensed_space_png(
        *r.object.sensed, centre, shown ? shown->points : std::vector<Eigen::Vector3d>{},
        shown ? "loop rank " + std::to_string(shown->rank) + ": " + shown->reason : "no loop",
        options.out_dir + "/sensed.png", r.next_view ? &*r.next_view : nullptr,
        r.sensed_near_loop.get());
  }
  if (!loop) {
    result["success"] = false;
    return finish(kNoAnswer, {{"success", false}, {"verified", false}, {"reason", r.reason}});
  }
  json& targets_json = result["targets"] = json::array();
  for (const auto& g : r.targets)
    targets_json.push_back({{"p", to_json(g.point)}, {"tangent", to_json(g.tangent)}});
  result["loop"] = to_json(loop->points);
  result["loop_choice"] = {{"rank", loop->rank},
                           {"reason", loop->reason},
                           {"hole_width", loop->hole_width},
                           {"bar_thickness", loop->bar_thickness},
                           {"fit", loop->fit}};

  // The scene: the robot, the object's collision mesh and the static environment.
  const SceneGeometry scene{
      model, {r.collision_mesh.vertices, r.collision_mesh.triangles}, r.environment, loop->points};
  result.update(scene_json(scene));
  json summary = options.controller_only ? controller_json(r, result, timing)
                                         : planner_json(r, scene, options, result, timing);
  if (const auto& v = r.next_view) {  // a camera for the unseen space the robot ran into
    result["next_best_view"] = {{"position", {v->position.x(), v->position.y(), v->position.z()}},
                                {"target", {v->target.x(), v->target.y(), v->target.z()}},
                                {"visible_voxels", v->visible},
                                {"unknown_voxels", v->unknown}};
    summary["next_best_view"] = result["next_best_view"];
  }
  const std::vector<Eigen::VectorXd>& path = r.motion.waypoints;
  if (path.empty()) {
    result["success"] = false;
    result["verified"] = false;
    return finish(kNoAnswer, summary);
  }

  // The final pose: virtual linking (eq. 4) and the open curves' Gauss integrals (Fig. 6).
  json& waypoints = result["waypoints"] = json::array();
  for (const auto& q : path) waypoints.push_back(to_json(q));
  result["final_q"] = to_json(r.motion.final_q);
  result["success"] = r.succeeded();
  if (!options.controller_only) result["verified"] = r.verified;
  result["virtual_linking"] = r.final_state.virtual_linking;
  result["finger_virtual_linking"] = r.final_state.finger_virtual_linking;
  result["finger_open_linking"] = r.final_state.finger_open_linking;
  summary["virtual_linking"] = r.final_state.virtual_linking;
  summary["finger_virtual_linking"] = r.final_state.finger_virtual_linking;

  if (options.pictures) {
    const auto tp = Clock::now();
    write_clasp_views(scene, r.motion.final_q, options.out_dir);
    if (r.verification.escape)
      write_escape_view(scene, r.motion.final_q, *r.verification.escape,
                        options.out_dir + "/escape.png");
    write_path_poses(scene, path, options.out_dir + "/poses.png");
    timing["pictures"] = since(tp);
  }
  return finish(r.succeeded() ? kOk : kNoAnswer, summary);
}

}  // namespace

RunOutcome run_scenario(const Scenario& scenario, const RunOptions& options) {
  if (options.next_views < 0 || options.next_views > 10)
    throw InputError("--next-views: " + std::to_string(options.next_views) + " is not in 0..10");
  if (options.next_views > 0 && scenario.object.cameras.empty())
    throw InputError(scenario.path +
                     ": --next-views renders the camera a failed run names, so the scenario must "
                     "render its depth (object: cameras); with depth files or clouds, capture "
                     "from the camera the reason names and add that view");
  // A robot that moves its camera where the reason says and looks again: the view is rendered
  // and added to the others, and the run starts over (the same seed).
  Scenario s = scenario;
  json added = json::array();
  for (;;) {
    RunOutcome outcome = run_once(s, options, added);
    const std::optional<perception::ViewSuggestion>& view = outcome.next_view;
    if (outcome.exit_code != kNoAnswer || !view ||
        static_cast<int>(added.size()) >= options.next_views || (options.stop && options.stop()))
      return outcome;
    s.object.cameras.emplace_back(view->position, view->target);
    added.push_back({{"position", to_json(view->position)}, {"target", to_json(view->target)}});
    if (!options.quiet) {
      progress("adding " + perception::view_text(*view) + ", and running again (view " +
               std::to_string(added.size()) + " of at most " + std::to_string(options.next_views) +
               ")");
    }
  }
}

json verification_json(const tsrrt::SecureClaspReport& v) {
  json j = {{"secure", v.secure},
            {"start_in_collision", v.start_in_collision},
            {"timed_out", v.timed_out},
            {"sequences", v.sequences},
            {"escaped_sequences", v.escaped_sequences},
            {"min_open_linking", v.min_open_linking},
            {"max_open_linking", v.max_open_linking},
            {"min_virtual_linking", v.min_virtual_linking},
            {"max_virtual_linking", v.max_virtual_linking}};
  json stages = json::array();
  for (const auto& st : v.stages) {
    json one = {{"name", st.name},
                {"ran", st.ran},
                {"passed", st.passed},
                {"timed_out", st.timed_out},
                {"iterations", st.iterations}};
    if (st.escape) {
      const Eigen::Vector3d t = st.escape->translation();
      one["escape"] = {{"translation", {t.x(), t.y(), t.z()}},
                       {"rotation", Eigen::AngleAxisd(st.escape->linear()).angle()}};
    }
    stages.push_back(one);
  }
  j["stages"] = stages;
  if (!v.escape_stage.empty()) j["escape_stage"] = v.escape_stage;
  if (v.escape) {  // the first escaping sequence's motion of the object, relative to the hand
    const Eigen::Vector3d t = v.escape->translation();
    j["escape"] = {{"translation", {t.x(), t.y(), t.z()}},
                   {"rotation", Eigen::AngleAxisd(v.escape->linear()).angle()}};
  }
  return j;
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
