// The scene a clasp is planned in, from the object model: which loop to clasp (or why none can
// be), the object's collision model around it, and what a search does in it: close the fingers
// at an open pose and check the closed hand (close_and_check).
#pragma once

#include <optional>
#include <string>
#include <vector>

#include <Eigen/Core>

#include "perception/pipeline.hpp"
#include "robots/collision_world.hpp"
#include "robots/robot_model.hpp"
#include "servo/clasp_controller.hpp"
#include "tsrrt/approach.hpp"
#include "tsrrt/finger_closing.hpp"
#include "tsrrt/planner.hpp"
#include "tsrrt/secure_clasp.hpp"

namespace claspplan::tsrrt {

/// The claspable loop to clasp: the one with a point nearest `hint`, else the best ranked; -1
/// (an index into object.loops) when no loop is claspable.
int choose_loop(const perception::ObjectModel& object, const std::optional<Eigen::Vector3d>& hint);

/// One line on why an object has no claspable loop: no loops at all, only unstable ones, or the
/// first three loops' verdicts.
std::string no_loop_reason(const perception::ObjectModel& object);

/// A closed tube of `radius` along a loop (hexagonal cross-section), as triangles. The loop is
/// material of the object, so adding it to the collision mesh keeps the loop from slipping
/// through gaps of a sparsely sampled surface (a thin handle seen by few depth views). Appended
/// to `mesh`.
void loop_tube(const servo::Points& loop, double radius, TriangleMesh& mesh);

/// The loop's material in the collision model (m): see loop_tube().
constexpr double kLoopTubeRadius = 0.003;

/// The object's collision model everywhere (planning, closing, verification): the surface the
/// depth cameras saw (K_d is for topology: its long triangles web across holes), else K_d's
/// triangles for clouds and whole-surface samples; and a thin tube along the clasped loop, so the
/// loop itself is always material. `workspace` crops the depth surface (the perception's crop).
/// Throws std::invalid_argument when there is no surface at all; `name` prefixes the message.
TriangleMesh object_collision_mesh(const perception::ObjectModel& object,
                                   const perception::Loop& loop,
                                   const Eigen::AlignedBox3d& workspace, const std::string& name);

/// How far (m) a measured point may lie off the depth surface built from its neighbours: every
/// other pixel is a mesh vertex, the rest lie off it by their noise (DepthSurfaceOptions::min_jump,
/// about 3 sigma of a depth camera's 1 mm at arm's length).
constexpr double kMeasurementSlack = 0.004;

/// The views' measured points inside `region`, more than `support`'s plane margin above it, that
/// no triangle of `collision_mesh` comes within kMeasurementSlack of: material the depth surface
/// leaves out (a rod one or two pixels wide has no triangle of its own, nor has an edge seen
/// nearly edge-on). The robot may not enter their voxels, as it may not enter unseen space.
std::vector<Eigen::Vector3d> unmeshed_points(const std::vector<perception::DepthView>& views,
                                             const Eigen::AlignedBox3d& region,
                                             const TriangleMesh& collision_mesh,
                                             const std::optional<Eigen::Vector4d>& support);

/// Everything a planned clasp needs beyond the scene.
struct ClaspPlanningOptions {
  PlannerParameters planner;
  bool sample_box_given = false;  ///< else the box is fitted around object and hand
  /// The tree's goal tolerance: a node at this mean |VLk| is a closable pose, where the fingers
  /// close until contact (paper Sec. V: 0.65 is the lowest threshold it uses for every hand). A
  /// closed hand that no longer links at it (closed_hand_links: one of three or more fingers may
  /// miss) is refused without the (costly) secure-clasp check. 0: the tree must reach
  /// the hand's linking goal itself (ClaspRequest::goal_linking).
  double closable_linking = 0.65;
  double position_tolerance = 0.0;     ///< metres; 0: virtual linking only (as in the paper)
  double collision_resolution = 0.02;  ///< rad between checked configurations
  /// m: no robot point travels farther between checked configurations (0: collision_resolution
  /// alone, the default: `bench`'s check against the rendered truth at 1 mm found no path of the
  /// conditions suite stepping over anything at 0.02 rad).
  double collision_travel = 0.0;
  FingerClosingOptions closing;
  /// When the fingers closed where the tree stopped give no secure clasp, the open hand advances
  /// to contact along its approach direction and closes again (approach_until_contact).
  ApproachOptions approach;
  int prune_attempts = 100;
  SecureClaspOptions secure;
  /// Verify each goal node as it is found and go on searching when the clasp is not secure;
  /// false: the first goal node ends the search (paper Alg. 3) and is verified afterwards.
  bool verify_in_search = true;
};

struct ClaspTimings;  // clasp_setup.hpp

/// The scene plan_clasp() builds around the chosen loop, handed to a search that replaces
/// TS-RRT (ClaspRequest::search: the benchmark's baselines run in the same pipeline, with the
/// same perception, collision model, finger closing and secure-clasp check).
struct ClaspScene {
  const robots::RobotModel& robot;
  robots::CollisionWorld& world;       ///< robot, object and environment
  servo::ClaspController& controller;  ///< bound to the loop and its clasp targets
  SecureClaspChecker& checker;         ///< the secure-clasp check of this object
  const perception::Loop& loop;
  double goal_linking;                   ///< the hand's virtual-linking goal (mean |VLk|)
  const ClaspPlanningOptions& planning;  ///< closing, check, seed and limits
};

/// Why a clasp check did not pass, in one line: the stage that freed the object (random motions,
/// escape search, a pull), the time limit, or a hand that already touches the object.
std::string insecure_reason(const SecureClaspReport& check);

/// The tree's goal tolerance (mean |VLk|): closable_linking, at most the goal; the goal itself
/// when closable_linking is 0.
double closable_tolerance(const ClaspPlanningOptions& planning, double goal_linking);

/// Does a closed hand still link the loop, by its finger curves' |VLk|? When their mean (eq. 4)
/// reaches `threshold`, or, with three curves or more, when the mean of all but the lowest does:
/// one finger may miss a hole narrower than the hand, and the secure-clasp check decides (the
/// paper's goal tolerance ranges from a hand's goal down to 0.65 with the object's shape, Sec. V).
bool closed_hand_links(const std::vector<double>& finger_linking, double threshold);

/// The controller continued from q toward its nearest clasp target at full linking, each step
/// collision-free, until the hand's linking goal (scene.goal_linking) or 30 steps: the tree stops
/// at the lower closable tolerance, where the fingertips have often just crossed the bar. Returns
/// the poses after q (empty: already at the goal, or the first step was blocked).
std::vector<Eigen::VectorXd> deepen_to_linking_goal(const ClaspScene& scene, Eigen::VectorXd q);

/// A clasp candidate: the fingers closed at an open pose, and the secure-clasp check of the
/// closed hand unless it was refused before (closed_hand_links() false at the tree's tolerance).
struct ClaspCandidate {
  /// The motion on from the open pose when the fingers closed at its end (empty: closed where the
  /// tree stopped): the open hand's straight approach to contact, or the controller's steps on to
  /// the hand's linking goal (`deepened`). The motion is approach, then q_closed.
  std::vector<Eigen::VectorXd> approach;
  bool deepened = false;
  Eigen::VectorXd q_closed;
  double closed_linking = 0.0;  ///< mean |VLk| of the closed hand (eq. 4)
  bool refused = false;         ///< below the tree's tolerance: no check ran
  bool screened_out = false;    ///< the check's screening (its first motions) found an escape
  /// Where the fingers stopped against unseen space when they closed at the open pose
  /// (close_fingers' unseen_stops): what a camera would have to see for them to close further.
  std::vector<robots::EnvironmentHit> unseen_stops;
  SecureClaspReport check;
};

/// Closes the fingers at q_open (close_fingers with the scene's options); with `refuse_unlinked`,
/// refuses a closed hand that no longer links at the tree's tolerance (closed_hand_links,
/// closable_tolerance), else runs scene.checker. When that gives no secure clasp, the open hand
/// approaches to contact (approach_until_contact) and the same follows there, and failing that,
/// the controller goes on from the open pose to the hand's linking goal (up to 30 collision-free
/// steps: the tree stops at the lower closable tolerance) and the same follows there; the first
/// secure clasp is returned, else the first attempt. Adds the seconds to timings.closing and
/// timings.verification.
ClaspCandidate close_and_check(const ClaspScene& scene, const Eigen::VectorXd& q_open,
                               ClaspTimings& timings, bool refuse_unlinked = true);

}  // namespace claspplan::tsrrt
