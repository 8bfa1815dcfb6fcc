// The whole clasp job as one call, in memory: object input -> perception (K_d, loops ranked for
// the hand) -> the loop to clasp and its targets -> the collision model -> TS-RRT with every goal
// node closed and verified (or the clasp controller alone) -> pruning -> the final task state.
// No files and no command-line types: `claspplan run` (examples/run_scenario.cpp) is a thin layer
// that turns a scenario into a ClaspRequest and the ClaspResult into its files.
//
// Shape: a free function plan_clasp(request) -> result, not a SimpleSetup-like class. OMPL's
// SimpleSetup keeps its parts (space information, problem definition, planner) because they exist
// before solve() and a user configures them; here every part (controller, collision world, TS-RRT
// problem) is bound to the loop that perception chooses in the middle of the call, so none exists
// before it and none would be configurable. What a caller may need afterwards is data in the
// result (object model, chosen loop, targets, collision mesh, environment, motion, tree), from
// which make_collision_world() rebuilds the world the plan was checked against. Like Pinocchio's
// model/data split, the request is constant input (the robot shared, never copied) and the
// result all that was computed, so one robot serves many concurrent calls.
#pragma once

#include <cstdint>
#include <functional>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include <Eigen/Geometry>

#include "core/input_error.hpp"
#include "core/mesh.hpp"
#include "perception/next_view.hpp"
#include "perception/pipeline.hpp"
#include "robots/collision_world.hpp"
#include "robots/hand_size.hpp"
#include "robots/robot_model.hpp"
#include "servo/clasp_controller.hpp"
#include "servo/controller_run.hpp"
#include "tsrrt/clasp_scene.hpp"
#include "tsrrt/planner.hpp"

namespace claspplan::tsrrt {

/// A static box of the environment (a table, a floor, a wall), world frame, centred at the pose.
struct EnvironmentBox {
  Eigen::Isometry3d pose = Eigen::Isometry3d::Identity();
  Eigen::Vector3d size = Eigen::Vector3d::Zero();
};

enum class ClaspMode {
  kPlan,  ///< TS-RRT, fingers closed and the clasp verified at every goal node
  /// The clasp controller alone toward the nearest clasp target, no search; when the fingers
  /// touch the object inside the tree's goal region, they are closed and the clasp verified.
  kControllerOnly,
};

struct ClaspResult;

/// A search in place of TS-RRT: from result.start, fills result.motion.waypoints (start to the
/// closed hand), status (kSuccess when it found one), verified, reason, verification, statistics,
/// and timings.closing and timings.verification (plan_clasp times the whole search).
using ClaspSearch = std::function<void(const ClaspScene&, ClaspResult&)>;

struct ClaspRequest {
  /// The robot (arm and hand); required. Shared, so that many requests use one model.
  std::shared_ptr<const robots::RobotModel> robot;
  /// The start configuration: all joints, or a prefix (arm, then hand) completed from the
  /// robot's home (RobotModel::complete_q()).
  Eigen::VectorXd start;
  /// The object: depth views with their cameras, clouds, or meshes (world frame).
  perception::PerceptionInputs object;
  std::vector<EnvironmentBox> environment;
  /// Clasp the claspable loop with a point nearest this one; none: the best ranked.
  std::optional<Eigen::Vector3d> loop_hint;
  /// The hand's virtual-linking goal (mean |VLk|, eq. 4), what the controller drives toward in
  /// both modes; none: the robot's own (RobotModel::vlink_goal).
  std::optional<double> goal_linking;

  /// The stages' options. The hand's sizes (finger thickness, closed aperture) come from the
  /// robot (robots::hand_size()): loops are chosen for this hand; set in `perception`, they are
  /// an error.
  /// perception.targets is the number of clasp targets on the chosen loop.
  perception::PerceptionOptions perception;
  servo::ControllerParameters controller;
  servo::ControllerRunOptions controller_run;  ///< kControllerOnly
  ClaspPlanningOptions planning;               ///< kPlan
  ClaspSearch search;  ///< kPlan: replaces TS-RRT when set (the benchmark's baselines)

  ClaspMode mode = ClaspMode::kPlan;
  /// When given, replaces the seed of every stage (perception, planner, pruning, verification);
  /// else each stage's own seed is used (the pruning uses the planner's).
  std::optional<std::uint64_t> seed;
  /// Bound the search by TS-RRT cycles: the planner's cycle limit, and no time limit unless
  /// time_limit is given too. Results then do not depend on the machine's speed or load.
  std::optional<int> max_cycles;
  std::optional<double> time_limit;  ///< seconds: replaces the planner's time limit
  /// Polled on the calling thread between perception's steps (true: claspplan::Stopped is
  /// thrown, core/stopped.hpp), during the search (true ends it: PlannerParameters::stop) and
  /// between the rounds and stages of each secure-clasp check (true: not passed).
  std::function<bool()> stop;

  /// Optional progress lines (perception steps, clasp candidates, ...).
  std::function<void(const std::string&)> progress;
  /// Names the problem in error messages ("<name>: ..."), e.g. the scenario file; may be empty.
  std::string name;
};

enum class ClaspStatus {
  kSuccess,  ///< a verified clasp (kControllerOnly: the linking goal reached, or a verified clasp)
  kNoClaspableLoop,  ///< a valid problem without an answer: no loop this hand can clasp
  kNoClasp,          ///< ... no (verified) clasp within the budget, or the controller stopped
};

struct ClaspMotion {
  /// Start to final configuration (the closed hand last); empty when no motion was found.
  std::vector<Eigen::VectorXd> waypoints;
  Eigen::VectorXd final_q;  ///< waypoints.back(), when there are waypoints
  int target = -1;          ///< the clasp target reached or driven to (index into targets)
};

struct ClaspStatistics {
  // kPlan: the TS-RRT search.
  int cycles = 0;  ///< of Alg. 1's loop after the pre-expansion
  int nodes = 0;
  int control_steps = 0;  ///< controller steps of the search (kControllerOnly: of the run)
  /// Goal nodes closed (and verified unless screened); kControllerOnly: 1 when the fingers touched
  /// the object in the goal region and were closed there.
  int clasp_candidates = 0;
  int clasp_candidates_screened = 0;  ///< closed hands refused unverified (closed_hand_links)
  /// Clasp targets dropped before the search: the closed hand there reaches into the environment
  /// at every approach (clasp_room()).
  int targets_without_room = 0;
  ConnectOutcomes connect_outcomes;
  int unpruned_waypoints = 0;  ///< of the found path, before pruning
  /// The tree, for pictures: each node's task point and parent, and the solution's nodes.
  std::vector<TaskPoint> tree_points;
  std::vector<int> tree_parents;
  std::vector<int> solution_nodes;
  // kControllerOnly.
  bool collided = false;                ///< a step would have collided
  std::vector<double> linking_history;  ///< Π_vlink after every step (the start included)
};

/// The task state at the final configuration (paper eq. 4 and Fig. 6).
struct ClaspTaskState {
  double virtual_linking = 0.0;                ///< Π_vlink: mean |VLk| of the finger curves
  std::vector<double> finger_virtual_linking;  ///< |VLk| per finger curve
  std::vector<double> finger_open_linking;     ///< |Lk| of each open finger curve with the loop
};

/// Seconds per phase (wall clock; not part of any determinism guarantee).
struct ClaspTimings {
  double perception = 0.0;
  /// Between perception and the search: the loop's choice, the whole sensed region cast and its
  /// unseen voxels, the object's collision mesh and the collision world.
  double scene = 0.0;
  double controller = 0.0;    ///< kControllerOnly: the controller run
  double search = 0.0;        ///< kPlan: the whole TS-RRT search, closing and verification included
  double planning = 0.0;      ///< ... of it the tree search alone
  double closing = 0.0;       ///< ... the finger closing of the candidates
  double verification = 0.0;  ///< ... the secure-clasp checks of the candidates
  double pruning = 0.0;
};

struct ClaspResult {
  /// The outcome; a search (TS-RRT or a ClaspSearch) sets kSuccess when it ends at a clasp.
  ClaspStatus status = ClaspStatus::kNoClasp;
  bool verified = false;  ///< the final clasp passed the secure-clasp check
  std::string reason;     ///< one line: why it succeeded or not

  Eigen::VectorXd start;             ///< the completed start configuration
  robots::HandSize hand;             ///< the hand sizes the loops were chosen for
  perception::ObjectModel object;    ///< K_d, the ranked loops, ...
  int loop = -1;                     ///< the chosen loop (index into object.loops), -1: none
  std::vector<ClaspTarget> targets;  ///< on the chosen loop
  /// The object's collision model used everywhere (planning, closing, verification), world
  /// frame: its seen surface and the loop's tube.
  TriangleMesh collision_mesh;
  std::vector<EnvironmentBox> environment;
  /// The sensed map cast again on a finer grid near the chosen loop
  /// (perception::SensedSpaceOptions::loop_resolution), or null: in its region it stands for
  /// object.sensed.
  std::shared_ptr<const perception::SensedSpace> sensed_near_loop;
  /// Space near the object that no sensor saw (perception::SensedSpace::blocked_voxels(): unknown
  /// voxels, and the support's below its surface), as cubes the robot must not enter: the sensed
  /// map's outside sensed_near_loop's region, then sensed_near_loop's. Empty without a sensed map
  /// (a mesh, or a cloud without a sensor origin).
  struct Voxels {
    std::vector<Eigen::Vector3d> centres;
    double edge = 0.0;
  };
  std::vector<Voxels> unseen;
  /// Voxels holding measured points that collision_mesh leaves out (unmeshed_points(): a rod
  /// too thin for the depth surface), laid out as `unseen`: the robot must not enter them either,
  /// and meeting them is meeting the object, not unseen space.
  std::vector<Voxels> measured;

  /// kNoClasp after a search whose attempts most often ran into unseen space, or a controller
  /// run that unseen space stopped: a camera that would see most of the unknown space where the
  /// robot met it (also in `reason`).
  std::optional<perception::ViewSuggestion> next_view;

  ClaspMotion motion;
  ClaspTaskState final_state;  ///< when motion.waypoints is not empty
  /// The last verified candidate's check (clasp_candidates > clasp_candidates_screened).
  SecureClaspReport verification;
  ClaspStatistics statistics;
  ClaspTimings timings;

  bool succeeded() const { return status == ClaspStatus::kSuccess; }
  /// The chosen loop, or nullptr.
  const perception::Loop* chosen_loop() const { return loop >= 0 ? &object.loops[loop] : nullptr; }
};

/// Runs the whole job. Returns kNoClaspableLoop / kNoClasp (with a reason) for a valid problem
/// without an answer. Throws InputError for malformed input: no robot, a bad start
/// configuration (outside the limits, or in collision), invalid object input or options, an
/// object without a surface to collide with.
ClaspResult plan_clasp(const ClaspRequest& request);

/// The collision world a result's motion was checked in: the robot, the result's collision mesh,
/// environment and unseen voxels.
robots::CollisionWorld make_collision_world(const robots::RobotModel& robot,
                                            const ClaspResult& result);

}  // namespace claspplan::tsrrt
