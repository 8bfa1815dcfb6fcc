// Clasp planning for a robot (paper Sec. IV-D, V-A): the TS-RRT bound to the clasp controller and
// the collision world, finger closing until contact, path pruning, and the secure-clasp check.
#pragma once

#include <chrono>
#include <cstdint>
#include <functional>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include <Eigen/Core>
#include <Eigen/Geometry>

#include "robots/collision_world.hpp"
#include "servo/clasp_controller.hpp"
#include "tsrrt/escape_search.hpp"
#include "tsrrt/planner.hpp"
#include "tsrrt/problem.hpp"

namespace claspplan::tsrrt {

/// The TS-RRT's view of a clasp problem: TS-PROJECTION and TS-CONTROL from the clasp controller,
/// COLLISION-FREE from the collision world (interpolated at `resolution`; what a blocked motion
/// touches first tells the object, the environment and self-collision apart), TS-TOLERANCE on
/// virtual linking and, if `position_tolerance` > 0, also on the hand's distance to the goal.
/// The goals are the controller's clasp targets, in order (goal i is targets()[i]).
class ClaspProblem final : public PlanningProblem {
 public:
  /// `acceptance` (optional) decides on goal nodes, see PlanningProblem::accept().
  ClaspProblem(servo::ClaspController& controller, robots::CollisionWorld& world,
               double goal_linking, double position_tolerance, double resolution,
               std::function<bool(const Eigen::VectorXd&)> acceptance = {});
  TaskPoint project(const Eigen::VectorXd& q) override;
  Eigen::VectorXd control(const Eigen::VectorXd& q0, const TaskPoint& x0,
                          const TaskPoint& x1) override;
  /// The controller holds a joint that a step would push past its limit (it does not move in
  /// that step). An arm joint serves the arm tasks and the pose bias and so always moves unless
  /// held: the last step was limited when an arm joint within `kLimitMargin` of a limit did not
  /// move.
  bool control_limited() const override { return limited_; }
  MotionCheck check_motion(const Eigen::VectorXd& q0, const Eigen::VectorXd& q1) override;
  bool reached(const TaskPoint& x, const TaskPoint& goal) const override;
  bool accept(const Eigen::VectorXd& q) override { return !acceptance_ || acceptance_(q); }
  /// Arm joints uniform within their limits, the hand open (its pre-shape), collision-free: up
  /// to 20 draws.
  bool sample_configuration(const std::function<std::uint64_t()>& bits,
                            Eigen::VectorXd& q) override;
  /// Detour points of clasp target p with unit tangent t (see clasp_approaches()), at
  /// approach_distance() from p.
  std::vector<TaskPoint> approaches(int goal) override;
  /// The detour points' distance from their target: the open hand's reach from its centre
  /// (half the diagonal of its finger curves' bounding box) plus 2 cm, within [0.08, 0.12] m.
  double approach_distance() const { return approach_distance_; }

  static constexpr double kLimitMargin = 0.05;  ///< rad (m): one controller step at most

 private:
  servo::ClaspController& controller_;
  robots::CollisionWorld& world_;
  double goal_linking_, position_tolerance_, resolution_;
  std::function<bool(const Eigen::VectorXd&)> acceptance_;
  Eigen::VectorXd last_q_;  // the last control() result: continuing from it keeps the alignment
  bool limited_ = false;
  double approach_distance_ = 0.1;
};

/// The frame clasp target `target` of `loop` is approached in: with c the loop's centroid, r the
/// unit component of (p − c) orthogonal to the tangent t (outward from the hole) and n = t × r.
struct ApproachFrame {
  Eigen::Vector3d r, n, t;
  /// The unit direction from the target toward the approach at angle θ, given as
  /// (cos θ, sin θ): cos θ r + sin θ n.
  Eigen::Vector3d direction(const Eigen::Vector2d& angle) const {
    return angle.x() * r + angle.y() * n;
  }
};
ApproachFrame approach_frame(const servo::Points& loop, const servo::ClaspTarget& target);

/// The approach angles θ, each as (cos θ, sin θ): 0, +90°, −90°, +45°, −45°, in that order.
std::vector<Eigen::Vector2d> approach_angles();

/// Where to approach clasp target `target` of `loop` from: the points p + distance·direction(θ)
/// of its approach_frame() for θ in approach_angles(): from outside the loop and from both sides
/// of its plane, never from inside the hole.
std::vector<Eigen::Vector3d> clasp_approaches(const servo::Points& loop,
                                              const servo::ClaspTarget& target, double distance);

struct FingerClosingOptions {
  double step = 0.01;  ///< rad per closing step of a finger's joints
  /// A link stops where it comes within this of the object (m); the final pose is free.
  double clearance = 0.002;
  int max_steps = 400;
};

/// Closes each finger (the thumb included) along its joints' closing directions until its links
/// are within the clearance of the object or its joints reach their limits; every step stays
/// collision-free. A link that comes within the clearance (or touches the robot) stops the joints
/// that move it, and the joints beyond it go on closing: the finger curls around what it meets.
/// Returns the closed configuration (the path's last pose).
Eigen::VectorXd close_fingers(const robots::RobotModel& model, robots::CollisionWorld& world,
                              const Eigen::VectorXd& q, const FingerClosingOptions& options);

struct ApproachOptions {
  double step = 0.004;     ///< m per step along the approach direction
  double distance = 0.05;  ///< the longest advance (m); 0: none
};

/// The open hand moved straight along its approach direction (v_fwd) by the arm alone, the tool's
/// orientation kept, until the next step would touch anything (object, environment, itself),
/// leave the joint limits or lose the line, or `distance` is covered: the approach to contact
/// that precedes a grasp, so that the fingers close around the bar from deep rather than hook it
/// with their tips. Returns the poses after q, each collision-free (empty: no step was free).
std::vector<Eigen::VectorXd> approach_until_contact(const robots::RobotModel& model,
                                                    robots::CollisionWorld& world,
                                                    const Eigen::VectorXd& q,
                                                    const ApproachOptions& options);

struct SecureClaspOptions {
  int sequences = 10;               ///< paper Sec. V-A: 10 sequences ...
  int motions = 500;                ///< ... of 500 random translations and rotations
  double translation_step = 0.004;  ///< m per step of a motion
  double rotation_step = 0.03;      ///< rad per step of a motion
  int steps_per_motion = 25;        ///< a motion's longest run before it is cut short
  /// The object is free once no finger loop links its loop any more and its loop is farther than
  /// this from every finger curve (m).
  double free_distance = 0.05;
  /// When > 0, only the object's triangles within this of the closed hand (the box around its
  /// links' shapes) are tested, and the loop's tube whole: less geometry only makes escaping
  /// easier. Off by default: at 5 cm the purse's handle, left as its thin tube away from the hand,
  /// slipped out of clasps the whole object holds, and at 8–12 cm it saved no time (measured).
  double near_hand = 0.0;
  /// Fingers' spheres and capsules tested by their exact distance to the object's triangles
  /// (robots::CollisionWorld::set_exact_round_shapes), not by FCL's GJK.
  bool exact_round_shapes = true;
  std::uint64_t seed = 1;
  /// Sequences run in parallel, on all cores when 0; the result does not depend on this.
  int threads = 0;
  /// Give up (not secure, timed_out) once this passes; none by default.
  std::optional<std::chrono::steady_clock::time_point> deadline;
  /// After the random motions pass: the escape stages (escape_search.hpp), an RRT-Connect escape
  /// search and the energy-bounded gravity and approach pulls. Random motions accept hooks.
  bool escape_stages = true;
  /// Their budgets and goal; their seed, deadline, translation_step and rotation_step are this
  /// check's (the fields above), whatever `escape` holds.
  EscapeSearchOptions escape;
};

struct SecureClaspReport {
  bool secure = false;
  /// The hand already touches the object at q: the check cannot run (and is not passed).
  bool start_in_collision = false;
  bool timed_out = false;  ///< the deadline passed before the check finished (not passed)
  int sequences = 0;
  int escaped_sequences = 0;
  int escape_motion = -1;  ///< the first escaping motion's index in its sequence, or -1
  /// Where the object got free: its motion relative to the closed hand in the first escaping
  /// sequence (in sequence order), at the end of its escaping motion.
  std::optional<Eigen::Isometry3d> escape;
  /// The stage that freed the object ("random_motions", "escape_search", "gravity", "approach"),
  /// whose pose `escape` is; empty when none did.
  std::string escape_stage;
  /// Every stage in order: random_motions, then (with escape_stages) escape_search, gravity,
  /// approach; the stages after one that freed the object or timed out did not run. Empty when
  /// the check could not run (start_in_collision).
  std::vector<VerificationStage> stages;
  /// At the final pose (paper Fig. 6): |Lk| of each open finger curve with the loop, and VLk.
  std::vector<double> open_linking;
  std::vector<double> virtual_linking;
  double min_open_linking = 0, max_open_linking = 0;
  double min_virtual_linking = 0, max_virtual_linking = 0;
};

/// |Lk| of each open finger curve of the hand at q with the loop: the Gauss integral the paper's
/// Fig. 6 plots.
std::vector<double> open_finger_linking(const robots::RobotModel& model, const Eigen::VectorXd& q,
                                        const servo::Points& loop);

/// A closed tube of `radius` along a loop (hexagonal cross-section), as triangles. The loop is
/// material of the object, so adding it to the collision mesh keeps the loop from slipping
/// through gaps of a sparsely sampled surface (a thin handle seen by few depth views).
void loop_tube(const servo::Points& loop, double radius, std::vector<Eigen::Vector3d>& vertices,
               std::vector<Eigen::Vector3i>& triangles);

/// The secure-clasp check of paper Sec. V-A on a closed hand at q: the object (its collision mesh,
/// world frame, and its loop) is moved relative to the hand by random translations and rotations
/// about the loop point nearest the hand, each pursued in small steps until it would collide.
/// The clasp is secure when, in every sequence, the object never gets free (see free_distance).
/// Only robot–object contacts stop a motion: the static environment is ignored, as is the
/// object's own weight. Sequences advance together in rounds (25, 100, 400, ... motions) and the
/// check stops after the first round in which one escapes: `escaped_sequences` counts the escapes
/// up to then, `escape_motion` is the escaping motion of the first such sequence (by index).
/// When they pass and options.escape_stages is on, the escape stages run in order (see
/// SecureClaspOptions::escape) until one frees the object: secure only if every stage holds.
SecureClaspReport check_secure_clasp(const robots::RobotModel& model,
                                     const std::vector<Eigen::Vector3d>& object_vertices,
                                     const std::vector<Eigen::Vector3i>& object_triangles,
                                     const Eigen::VectorXd& q, const servo::Points& loop,
                                     const SecureClaspOptions& options);

/// check_secure_clasp() on one object for many closed hands (a search's clasp candidates): the
/// object's collision geometry is built at the first check and kept (unless options.near_hand
/// crops it for each hand).
class SecureClaspChecker {
 public:
  SecureClaspChecker(const robots::RobotModel& model, std::vector<Eigen::Vector3d> object_vertices,
                     std::vector<Eigen::Vector3i> object_triangles,
                     const SecureClaspOptions& options);
  /// The check at q; `screened_out` (optional) tells whether an escape showed in its first two
  /// rounds (the first 100 motions of every sequence): an insecure clasp found early.
  SecureClaspReport check(const Eigen::VectorXd& q, const servo::Points& loop,
                          bool* screened_out = nullptr);

 private:
  const robots::RobotModel& model_;
  std::vector<Eigen::Vector3d> vertices_;
  std::vector<Eigen::Vector3i> triangles_;
  SecureClaspOptions options_;
  std::shared_ptr<const robots::ObjectGeometry> whole_;
};

/// The object's collision mesh as the secure-clasp check tests it: the triangles whose bounding
/// box meets the closed hand's box grown by `margin`, and those of the loop's tube (every vertex
/// within kLoopTubeRadius of a loop point), re-indexed. `margin` <= 0: all of them.
void crop_near_hand(const robots::RobotModel& model, const Eigen::VectorXd& q,
                    const servo::Points& loop, double margin,
                    const std::vector<Eigen::Vector3d>& vertices,
                    const std::vector<Eigen::Vector3i>& triangles,
                    std::vector<Eigen::Vector3d>& kept_vertices,
                    std::vector<Eigen::Vector3i>& kept_triangles);

/// Everything a planned clasp needs beyond the scene.
struct ClaspPlanningOptions {
  PlannerParameters planner;
  bool sample_box_given = false;  ///< else the box is fitted around object and hand
  /// The hand's virtual-linking goal (mean |VLk|, eq. 4): what the controller drives toward; 0:
  /// the hand's default goal.
  double goal_linking = 0.0;
  /// The tree's goal tolerance: a node at this mean |VLk| is a closable pose, where the fingers
  /// close until contact (paper Sec. V: 0.65 is the lowest threshold it uses for every hand). A
  /// closed hand that no longer links at it (closed_hand_links: one of three or more fingers may
  /// miss) is refused without the (costly) secure-clasp check. 0: the tree must reach
  /// goal_linking itself.
  double closable_linking = 0.65;
  double position_tolerance = 0.0;     ///< metres; 0: virtual linking only (as in the paper)
  double collision_resolution = 0.02;  ///< rad between checked configurations
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

}  // namespace claspplan::tsrrt
