// The secure-clasp check (paper Sec. V-A) and the stages after it (escape_search.hpp): does the
// closed hand hold the object?
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
#include "robots/robot_model.hpp"
#include "servo/linking.hpp"
#include "tsrrt/escape_search.hpp"

namespace claspplan::tsrrt {

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
  /// Polled on the calling thread between rounds of motions and between stages: true gives up
  /// as the deadline does (Ctrl-C in Python).
  std::function<bool()> stop;
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

}  // namespace claspplan::tsrrt
