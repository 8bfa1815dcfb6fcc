#include "tsrrt/clasp_setup.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <stdexcept>
#include <utility>

#include "core/input_error.hpp"
#include "core/mesh.hpp"
#include "robots/kinematics.hpp"
#include "tsrrt/clasp_problem.hpp"
#include "tsrrt/clasp_scene.hpp"
#include "tsrrt/elapsed.hpp"
#include "tsrrt/hand_room.hpp"

namespace claspplan::tsrrt {
namespace {

using Say = std::function<void(const std::string&)>;

// The planner's default sample box: object and hand start, with 0.3 m of room around them, so
// that the tree can find its way around obstacles next to the object.
void fit_sample_box(PlannerParameters& p, const perception::ObjectModel& object,
                    const Eigen::Vector3d& hand_start) {
  Eigen::AlignedBox3d box = bounds(object.cloud);
  box.extend(hand_start);
  p.sample_min = box.min() - Eigen::Vector3d::Constant(0.3);
  p.sample_max = box.max() + Eigen::Vector3d::Constant(0.3);
}

std::vector<Eigen::Vector3d> without_robot(const robots::RobotModel& model,
                                           const Eigen::VectorXd& start,
                                           std::vector<Eigen::Vector3d> voxels, double edge);

// A camera that would see where the robot met space no camera saw (next_view.hpp), at least 5 cm
// clear of the environment and of the robot at its start.
void suggest_view(const robots::RobotModel& model, ClaspResult& r,
                  const std::vector<Eigen::Vector3d>& unseen_contacts,
                  const std::string& what = "the space it ran into is unseen") {
  if (!r.object.sensed) return;
  constexpr double kClear = 0.05;
  perception::ViewOptions o;
  o.allowed = [&](const Eigen::Vector3d& p) {
    for (const EnvironmentBox& b : r.environment)
      if (((b.pose.inverse() * p).cwiseAbs() - 0.5 * b.size).maxCoeff() <= kClear) return false;
    return !without_robot(model, r.start, {p}, 2 * kClear / std::sqrt(3.0)).empty();
  };
  r.next_view =
      perception::view_into_unknown(*r.object.sensed, unseen_contacts, r.object.support_plane, o);
  if (r.next_view) r.reason += "; " + what + ": " + perception::view_text(*r.next_view);
}

// The clasp controller alone toward the nearest clasp target. A run that the object stops
// inside the tree's goal region (eq. 4 mean at least the goal tolerance, ClaspProblem::reached)
// ends as the planner's goal nodes do: the fingers closed to contact and the clasp verified. A
// hand whose thumb sweeps wider than the bar (the Allegro's) touches it before the hand's goal.
void run_controller_only(const ClaspRequest& request, const ClaspScene& scene, const Say& say,
                         ClaspResult& r) {
  const auto t = Clock::now();
  servo::ControllerRun run = servo::run_controller(scene.controller, scene.world, r.start,
                                                   scene.goal_linking, request.controller_run);
  r.timings.controller = since(t);
  r.statistics.control_steps = static_cast<int>(run.waypoints.size()) - 1;
  r.statistics.collided = run.collided;
  r.statistics.linking_history = std::move(run.linking_history);
  r.motion.target = run.target;
  r.motion.waypoints = std::move(run.waypoints);
  r.reason = run.reason;
  if (run.success) {
    r.status = ClaspStatus::kSuccess;
    return;
  }
  if (run.collided && run.collision.second == "unseen space")
    suggest_view(scene.robot, r, {scene.world.contact_point(run.environment_hit)});
  const double tolerance = closable_tolerance(scene.planning, scene.goal_linking);
  const bool touched_object =
      run.collided && run.collision.second == "object" && r.statistics.control_steps > 0;
  if (!touched_object || run.final_state.linking < tolerance) return;
  char line[200];
  std::snprintf(line, sizeof line,
                "  the fingers touched the object at virtual linking %.3f (goal region from %.2f): "
                "closing them to contact and verifying ...",
                run.final_state.linking, tolerance);
  say(line);
  const ClaspCandidate c = close_and_check(scene, r.motion.waypoints.back(), r.timings, true);
  r.statistics.clasp_candidates = 1;
  r.statistics.clasp_candidates_screened = c.refused ? 1 : 0;
  if (c.refused) {
    r.reason += "; the hand closed there reaches virtual linking " +
                std::to_string(c.closed_linking) + " only";
    return;
  }
  for (const auto& q : c.approach) r.motion.waypoints.push_back(q);
  r.motion.waypoints.push_back(c.q_closed);
  r.verification = c.check;
  r.verified = c.check.secure;
  if (c.check.secure) {
    r.status = ClaspStatus::kSuccess;
    r.reason = "verified clasp: the fingers touched the object in the goal region and closed";
  } else {
    r.reason += "; closed there: " + insecure_reason(c.check);
    if (!c.unseen_stops.empty()) {
      suggest_view(scene.robot, r, scene.world.contact_points(c.unseen_stops),
                   "the fingers stopped on unseen space");
    }
  }
}

// TS-RRT with every goal node closed and verified at once (paper Sec. IV-D, V-A); with
// verify_in_search an insecure clasp is rejected and the search goes on.
void run_search(const ClaspScene& scene, const Say& say, ClaspResult& r) {
  const ClaspPlanningOptions& planning = scene.planning;
  PlannerParameters pp = planning.planner;
  if (!planning.sample_box_given) {
    fit_sample_box(pp, r.object, scene.controller.project(r.start).position);
  }
  ClaspCandidate last;
  SecureClaspReport check;  // the last check made
  int candidates = 0, screened = 0;
  // Insecure closings whose fingers stopped against unseen space, and where (the first points).
  int rejected = 0, stopped_unseen = 0;
  std::vector<robots::EnvironmentHit> unseen_stops;
  const auto close_and_verify = [&](const Eigen::VectorXd& q_goal) {
    ++candidates;
    last = close_and_check(scene, q_goal, r.timings, planning.verify_in_search);
    if (last.refused) {
      ++screened;
      say("  clasp candidate " + std::to_string(candidates) +
          ": the closed hand reaches virtual linking " + std::to_string(last.closed_linking) +
          " only; refused");
      return false;
    }
    if (!last.approach.empty())
      say("  clasp candidate " + std::to_string(candidates) +
          (last.deepened ? ": closed again after the controller went on to the linking goal ("
                         : ": closed again after the open hand approached to contact (") +
          std::to_string(last.approach.size()) + " steps)");
    say("  clasp candidate " + std::to_string(candidates) + ": fingers closed; verified with " +
        std::to_string(planning.secure.sequences) + " x " +
        std::to_string(planning.secure.motions) + " random motions of the object");
    check = last.check;
    if (check.timed_out && check.escaped_sequences == 0) {
      say("  not verified: the time limit ended the check");
    } else if (check.start_in_collision) {
      say("  rejected: the closed hand touches the object");
    } else if (!check.secure) {
      say("  rejected: " + insecure_reason(check) +
          (last.screened_out ? " (in the screening: the full check's first motions)" : ""));
      ++rejected;
      if (!last.unseen_stops.empty()) {
        ++stopped_unseen;
        for (const robots::EnvironmentHit& hit : last.unseen_stops)
          if (unseen_stops.size() < ClaspProblem::kMaxContacts) unseen_stops.push_back(hit);
      }
    }
    return check.secure || !planning.verify_in_search;
  };
  // The tree stops at a closable pose; finger closing does the rest (paper Sec. V).
  const double tolerance = closable_tolerance(planning, scene.goal_linking);
  ClaspProblem problem(scene.controller, scene.world, tolerance, planning.position_tolerance,
                       planning.collision_resolution, close_and_verify);
  std::vector<TaskPoint> goals;
  for (const auto& g : scene.controller.targets()) goals.push_back({g.point, 1.0});  // Alg. 1, l. 9
  say("planning (TS-RRT, " + std::to_string(goals.size()) + " clasp goals) ...");
  PlanResult plan = build_ts_rrt(problem, r.start, goals, pp);

  ClaspStatistics& s = r.statistics;
  s.cycles = plan.cycles;
  s.nodes = plan.nodes;
  s.control_steps = plan.control_steps;
  s.clasp_candidates = candidates;
  s.clasp_candidates_screened = screened;
  s.connect_outcomes = plan.outcomes;
  s.tree_points = std::move(plan.tree_points);
  s.tree_parents = std::move(plan.tree_parents);
  s.solution_nodes = std::move(plan.solution_nodes);
  r.verification = check;
  if (!plan.success) {
    r.reason = plan.reason;
    // A camera for the unseen space nearest to a clasp: where the fingers stopped, when most
    // insecure clasps had such stops (the hand got round the bar); else where the search ran into
    // it, when it stopped a tenth of the attempts and more than any obstacle but the object.
    if (2 * stopped_unseen > rejected) {
      suggest_view(scene.robot, r, scene.world.contact_points(unseen_stops),
                   "in " + std::to_string(stopped_unseen) + " of the " + std::to_string(rejected) +
                       " insecure clasps the fingers stopped on unseen space");
    } else if (r.statistics.connect_outcomes.unseen_space_leads()) {
      suggest_view(scene.robot, r, problem.unseen_contacts());
    }
    return;
  }
  say("  clasp found after " + std::to_string(plan.cycles) + " cycles, " +
      std::to_string(plan.nodes) + " nodes; pruning the path ...");
  r.motion.target = plan.goal_index;
  s.unpruned_waypoints = static_cast<int>(plan.path.size());
  const auto t = Clock::now();
  r.motion.waypoints = prune_path(problem, std::move(plan.path), planning.prune_attempts, pp.seed);
  r.timings.pruning = since(t);
  for (const auto& q : last.approach) r.motion.waypoints.push_back(q);
  if (last.q_closed != r.motion.waypoints.back()) r.motion.waypoints.push_back(last.q_closed);
  r.verified = check.secure;
  if (check.secure) r.status = ClaspStatus::kSuccess;
  r.reason =
      check.secure ? "verified clasp" : "the clasp failed verification: " + insecure_reason(check);
}

// Distance to a collision shape from a point in the shape's frame (0 inside; a mesh: at most).
double shape_distance(const robots::CollisionShape& s, const Eigen::Vector3d& local) {
  using Type = robots::CollisionShape::Type;
  switch (s.type) {
    case Type::kBox:
      return (local.cwiseAbs() - 0.5 * s.size).cwiseMax(0.0).norm();
    case Type::kSphere:
      return std::max(0.0, local.norm() - s.radius);
    case Type::kCapsule: {
      const double z = std::clamp(local.z(), -0.5 * s.length, 0.5 * s.length);
      return std::max(0.0, (local - Eigen::Vector3d(0, 0, z)).norm() - s.radius);
    }
    case Type::kCylinder: {
      const double radial = std::max(0.0, local.head<2>().norm() - s.radius);
      const double axial = std::max(0.0, std::abs(local.z()) - 0.5 * s.length);
      return std::hypot(radial, axial);
    }
    case Type::kMesh:  // its box's: the mesh lies inside it
      return robots::shape_bounds(s).exteriorDistance(local);
  }
  return 0.0;
}

// The unseen voxels less those the robot itself fills at its start: a camera sees the robot there,
// not what lies behind it, and a real system masks the robot out of its depth images (a
// self-filter); nothing of the object can be where the robot stands.
std::vector<Eigen::Vector3d> without_robot(const robots::RobotModel& model,
                                           const Eigen::VectorXd& start,
                                           std::vector<Eigen::Vector3d> voxels, double edge) {
  robots::RobotData data(model);
  robots::forward_kinematics(model, start, data);
  const double reach = 0.5 * std::sqrt(3.0) * edge;  // a voxel within this may touch the shape
  std::vector<Eigen::Isometry3d> to_shape;           // each shape's frame from the world's
  for (const auto& s : model.shapes)
    to_shape.push_back((data.link_poses[s.link] * s.origin).inverse());
  const auto filled = [&](const Eigen::Vector3d& c) {
    for (std::size_t k = 0; k < model.shapes.size(); ++k)
      if (shape_distance(model.shapes[k], to_shape[k] * c) <= reach) return true;
    return false;
  };
  voxels.erase(std::remove_if(voxels.begin(), voxels.end(), filled), voxels.end());
  return voxels;
}

// The voxels the robot must not enter: the sensed map's unseen space (ClaspResult::unseen) and
// the measurements the collision mesh misses (ClaspResult::measured), and near the loop those of
// the same views cast on a finer grid in their place.
void blocked_space(const robots::RobotModel& model, const perception::Loop& loop,
                   const perception::SensedSpaceOptions& o, ClaspResult& r) {
  const perception::SensedSpace& coarse = *r.object.sensed;
  const std::vector<Eigen::Vector3d> unmeshed =
      unmeshed_points(r.object.views, coarse.region(), r.collision_mesh, r.object.support_plane);
  if (o.loop_resolution > 0.0) {
    Eigen::AlignedBox3d around;
    for (const Eigen::Vector3d& p : loop.points) around.extend(p);
    around = perception::object_region(around, o.loop_margin);
    perception::SensedSpace fine = coarse.refined(around, o.loop_resolution, o.loop_max_voxels);
    if (!fine.empty())
      r.sensed_near_loop = std::make_shared<const perception::SensedSpace>(std::move(fine));
  }
  // Each kind on the coarse grid outside the fine one's region, then on the fine grid.
  const auto add = [&](std::vector<ClaspResult::Voxels>& out, auto voxels_of) {
    std::vector<Eigen::Vector3d> outside = voxels_of(coarse);
    if (r.sensed_near_loop) {
      const Eigen::AlignedBox3d& box = r.sensed_near_loop->region();
      outside.erase(std::remove_if(outside.begin(), outside.end(),
                                   [&](const Eigen::Vector3d& c) { return box.contains(c); }),
                    outside.end());
    }
    out.push_back({without_robot(model, r.start, std::move(outside), coarse.resolution()),
                   coarse.resolution()});
    if (!r.sensed_near_loop) return;
    const perception::SensedSpace& fine = *r.sensed_near_loop;
    out.push_back(
        {without_robot(model, r.start, voxels_of(fine), fine.resolution()), fine.resolution()});
  };
  add(r.unseen, [&](const perception::SensedSpace& space) {
    return space.blocked_voxels(r.object.support_plane);
  });
  add(r.measured,
      [&](const perception::SensedSpace& space) { return space.voxels_holding(unmeshed); });
}

// One line of what the sensors saw and what the robot may not enter.
std::string sensed_summary(const ClaspResult& r) {
  const auto n = r.object.sensed->counts();
  const double all = static_cast<double>(n[0] + n[1] + n[2]) / 100.0;
  std::size_t blocked = 0;
  for (const auto* kind : {&r.measured, &r.unseen})
    for (const auto& v : *kind) blocked += v.centres.size();
  char line[200];
  std::snprintf(line, sizeof line,
                "sensed space near the object: %.0f%% free, %.0f%% occupied, %.0f%% unknown "
                "(%zu voxels the robot may not enter",
                n[1] / all, n[2] / all, n[0] / all, blocked);
  std::string text = line;
  if (r.sensed_near_loop) {
    std::snprintf(line, sizeof line, "; %.1f mm voxels, %.1f mm near the loop",
                  1e3 * r.object.sensed->resolution(), 1e3 * r.sensed_near_loop->resolution());
    text += line;
  }
  return text + ")";
}

// The loop to clasp and its targets. The clasp targets of a loop where the closed hand reaches
// into the environment at every approach are dropped; a claspable loop left without targets is
// refused ("no_room") and the next one tried, unless the request names the loop.
int choose_loop_with_room(const robots::RobotModel& model, const ClaspRequest& request,
                          robots::CollisionWorld& environment, const Say& say, ClaspResult& r) {
  for (int chosen = choose_loop(r.object, request.loop_hint); chosen >= 0;
       chosen = choose_loop(r.object, request.loop_hint)) {
    perception::Loop& loop = r.object.loops[chosen];
    std::vector<ClaspTarget> targets =
        perception::clasp_targets(loop, request.perception.targets, r.hand.closed_aperture);
    if (r.environment.empty()) {
      r.targets = std::move(targets);
      return chosen;
    }
    const std::vector<bool> room =
        clasp_room(model, r.hand.closed_q, environment, loop.points, targets);
    r.targets.clear();
    for (std::size_t i = 0; i < targets.size(); ++i)
      if (room[i]) r.targets.push_back(targets[i]);
    r.statistics.targets_without_room = static_cast<int>(targets.size() - r.targets.size());
    if (!r.targets.empty()) {
      if (r.statistics.targets_without_room > 0)
        say("clasp targets: " + std::to_string(r.statistics.targets_without_room) + " of " +
            std::to_string(targets.size()) +
            " dropped: the closed hand there reaches into the environment");
      return chosen;
    }
    say("loop rank " + std::to_string(loop.rank) +
        ": no room for the hand (the closed hand reaches into the environment at every clasp "
        "target)");
    loop.claspable = false;
    loop.verdict = perception::LoopVerdict::kNoRoom;
    loop.reason =
        "no room for this hand: the hand closed around the bar reaches into the "
        "environment at each of the loop's " +
        std::to_string(targets.size()) + " clasp targets, from all " +
        std::to_string(room_approach_angles().size()) + " approach directions";
    if (request.loop_hint) return -1;
  }
  return -1;
}

// The request's start, completed from the home pose. Its adaptive joints must sit where their
// leaders put them: a hand before any contact.
Eigen::VectorXd start_configuration(const robots::RobotModel& model, const Eigen::VectorXd& given) {
  const Eigen::VectorXd q =
      model.complete_q(std::vector<double>(given.data(), given.data() + given.size()));
  const Eigen::VectorXd coupled = model.couple(q);
  for (int j = 0; j < model.dof(); ++j) {
    if (std::abs(coupled[j] - q[j]) > 1e-9) {
      throw InputError("start: '" + model.joints[j].name +
                       "' is an adaptive joint: it starts where '" +
                       model.joints[model.joints[j].follows].name + "' puts it (" +
                       std::to_string(coupled[j]) + ")");
    }
  }
  return q;
}

}  // namespace

ClaspResult plan_clasp(const ClaspRequest& request) {
  const std::string prefix = request.name.empty() ? "" : request.name + ": ";
  if (!request.robot) throw InputError(prefix + "the request has no robot");
  if (request.goal_linking && !(*request.goal_linking > 0.0 && *request.goal_linking <= 1.0))
    throw InputError(prefix + "goal_linking must be in (0, 1]");
  if (request.perception.finger_thickness != 0.0 || request.perception.closed_aperture != 0.0)
    throw InputError(prefix +
                     "perception.finger_thickness and closed_aperture come from the robot "
                     "(robots::hand_size()): leave them 0");
  const robots::RobotModel& model = *request.robot;
  const Say say = [&](const std::string& m) {
    if (request.progress) request.progress(m);
  };
  // The stages' options with the request's overrides.
  perception::PerceptionOptions perception = request.perception;
  ClaspPlanningOptions planning = request.planning;
  if (request.seed) {
    perception.seed = planning.planner.seed = planning.secure.seed = *request.seed;
  }
  if (request.max_cycles) {
    planning.planner.max_cycles = *request.max_cycles;
    planning.planner.time_limit = 0.0;
  }
  if (request.time_limit) planning.planner.time_limit = *request.time_limit;
  if (request.stop) planning.planner.stop = planning.secure.stop = perception.stop = request.stop;

  ClaspResult r;
  r.start = start_configuration(model, request.start);
  // Loops are chosen for this hand: holes its fingers pass, bars its closed hand encloses.
  r.hand = robots::hand_size(model);
  perception.finger_thickness = r.hand.finger_thickness;
  perception.closed_aperture = r.hand.closed_aperture;
  if (request.progress) perception.progress = request.progress;

  r.environment = request.environment;
  for (const auto& b : r.environment) {
    if (!b.pose.matrix().allFinite() || !b.size.allFinite() || (b.size.array() <= 0).any())
      throw InputError(prefix + "an environment box has a non-finite pose or a size <= 0");
  }

  // The start against the environment and itself before perception (the object comes later).
  robots::CollisionWorld environment(model);
  for (const auto& b : r.environment) environment.add_box(b.pose, b.size);
  robots::CollisionReport contact;
  const auto start_touches = [&](robots::CollisionWorld& world) {
    if (world.in_collision(r.start, &contact))
      throw InputError(prefix + "the start configuration is in collision (" + contact.first +
                       " with " + contact.second + ")");
  };
  start_touches(environment);

  say("perceiving the object ...");
  auto t = Clock::now();
  r.object = perception::build_object_model(request.object, perception);
  r.timings.perception = since(t);
  t = Clock::now();
  r.loop = choose_loop_with_room(model, request, environment, say, r);
  if (r.loop < 0) {
    r.timings.scene = since(t);
    r.status = ClaspStatus::kNoClaspableLoop;
    r.reason = no_loop_reason(r.object);
    return r;
  }
  const perception::Loop& loop = r.object.loops[r.loop];

  // The scene: the robot, the object's collision mesh, the static environment and the space near
  // the object that no sensor saw (unknown is occupied there: sensed_space.hpp).
  r.collision_mesh = object_collision_mesh(r.object, loop, perception.workspace, request.name);
  if (r.object.sensed) {
    blocked_space(model, loop, perception.sensed, r);
    say(sensed_summary(r));
  }
  robots::CollisionWorld world = make_collision_world(model, r);
  world.set_motion_travel(planning.collision_travel);
  start_touches(world);

  r.timings.scene = since(t);

  servo::ClaspController controller(model, loop.points, r.targets, request.controller);
  const double goal_linking = request.goal_linking.value_or(model.vlink_goal);
  // The time limit bounds the search and every clasp check made in it.
  const auto t0 = Clock::now();
  if (planning.planner.time_limit > 0.0) {
    planning.secure.deadline = t0 + std::chrono::duration_cast<Clock::duration>(
                                        std::chrono::duration<double>(planning.planner.time_limit));
  }
  SecureClaspChecker checker(model, r.collision_mesh.vertices, r.collision_mesh.triangles,
                             planning.secure);
  const ClaspScene scene{model, world, controller, checker, loop, goal_linking, planning};
  if (request.mode == ClaspMode::kControllerOnly) {
    say("running the controller alone toward the nearest clasp target ...");
    run_controller_only(request, scene, say, r);
  } else {
    if (request.search) {
      request.search(scene, r);
    } else {
      run_search(scene, say, r);
    }
    r.timings.search = since(t0);
    r.timings.planning = r.timings.search - r.timings.closing - r.timings.verification;
  }
  if (r.motion.waypoints.empty()) return r;

  // The final pose: virtual linking (eq. 4) and the open curves' Gauss integrals (Fig. 6).
  r.motion.final_q = r.motion.waypoints.back();
  const servo::TaskState final_state = controller.project(r.motion.final_q);
  r.final_state.virtual_linking = final_state.linking;
  r.final_state.finger_virtual_linking = final_state.finger_linking;
  r.final_state.finger_open_linking = open_finger_linking(model, r.motion.final_q, loop.points);
  return r;
}

robots::CollisionWorld make_collision_world(const robots::RobotModel& robot,
                                            const ClaspResult& result) {
  robots::CollisionWorld world(robot);
  world.set_object(result.collision_mesh.vertices, result.collision_mesh.triangles);
  for (const auto& b : result.environment) world.add_box(b.pose, b.size);
  // The measured material first: a shape through it and the unknown behind met it first.
  for (const auto& v : result.measured)
    world.add_voxels(v.centres, v.edge, robots::CollisionWorld::VoxelKind::kMeasured);
  for (const auto& v : result.unseen) world.add_voxels(v.centres, v.edge);
  return world;
}

}  // namespace claspplan::tsrrt
