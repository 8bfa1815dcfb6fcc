// Escape searches of the object relative to the closed hand: the stages of the secure-clasp check
// that run after the paper's random motions (Sec. V-A). Random motions accept hooks (a thumb
// hooked into a container's neck): a way out that needs a planned path is rarely found by them.
// - escape_search: a bidirectional RRT (RRT-Connect, Kuffner & LaValle, ICRA 2000) for a rigid
//   motion of the object in SE(3) from its start to a pose far from the hand;
// - gravity / approach: the same search where the object's potential under a pull may rise by a
//   small slack only (energy-bounded caging: Mahler, Pokorny et al., "Energy-Bounded Caging:
//   Formal Definition and 2-D Energy Lower Bound Algorithm Based on Weighted Alpha Shapes",
//   ICRA 2016): an object that can only leave by being lifted is held under gravity.
// The searches are deterministic for a seed and bounded by iteration counts, so their verdict does
// not depend on the machine's speed; a deadline only turns a search into a timeout.
#pragma once

#include <chrono>
#include <cstdint>
#include <functional>
#include <optional>
#include <string>
#include <vector>

#include <Eigen/Geometry>

#include "robots/robot_model.hpp"
#include "servo/linking.hpp"

namespace claspplan::tsrrt {

struct EscapeSearchOptions {
  /// The object is out once every point of its loop is this far from every finger curve (m).
  double escape_distance = 0.30;
  /// How much the object's potential may rise along an escape of an energy-bounded stage (m of
  /// its vertices' centroid against the pull).
  double energy_slack = 0.005;
  /// Edges checked at this spacing, as the random motions step (m of the pivot; rad).
  double translation_step = 0.004;
  double rotation_step = 0.03;
  /// Translations sampled in a box of +-this around the start (m).
  double sample_box = 0.4;
  /// RRT-Connect iterations per search (one sample, an extension, a connection each).
  int iterations = 2000;
  /// The longest edge one extension adds (m of the pivot plus rotation weighted by the loop's
  /// reach from the pivot).
  double extend_distance = 0.06;
  /// Goal poses drawn to root the goal tree, and how many of them are kept.
  int goal_attempts = 64;
  int goal_roots = 6;
  /// Straight pulls before an energy-bounded search: attempts per pull direction (the first
  /// without perturbation), and the tries of a perturbed step before an attempt gives up.
  int pull_attempts = 4;
  int pull_retries = 4;
  std::uint64_t seed = 1;
  /// Give up (timed_out) once this passes, or once `cancelled` (called from the search's thread,
  /// whichever that is) returns true.
  std::optional<std::chrono::steady_clock::time_point> deadline;
  std::function<bool()> cancelled;
};

/// The object and the closed hand as a search sees them. The object moves rigidly by T (world
/// frame, from its start), written as a rotation about `pivot` and the pivot's translation.
struct EscapeProblem {
  std::vector<std::vector<Eigen::Vector3d>> curves;     ///< the closed hand's finger curves
  servo::Points loop;                                   ///< the clasped loop (start pose)
  Eigen::Vector3d pivot = Eigen::Vector3d::Zero();      ///< the loop point nearest the hand
  Eigen::Vector3d centroid = Eigen::Vector3d::Zero();   ///< of the object's mesh vertices
  Eigen::Vector3d approach = Eigen::Vector3d::UnitZ();  ///< the hand's v_fwd, world frame
  /// Does the object at T touch the robot?
  std::function<bool(const Eigen::Isometry3d&)> collides;
};

/// The problem of a closed hand at q; `vertices` give the centroid, `collides` the contacts.
EscapeProblem escape_problem(const robots::RobotModel& model, const Eigen::VectorXd& q,
                             const servo::Points& loop,
                             const std::vector<Eigen::Vector3d>& vertices,
                             std::function<bool(const Eigen::Isometry3d&)> collides);

struct EscapeResult {
  bool escaped = false;
  bool timed_out = false;
  int iterations = 0;  ///< RRT-Connect iterations run
  /// Where the object is out: its motion from its start (a goal pose the found path reaches).
  std::optional<Eigen::Isometry3d> escape;
};

/// RRT-Connect from the start (identity) to the goal poses. With `pull` (unit, world frame) a
/// pose is valid only if -pull . (centroid moved - centroid) <= energy_slack.
EscapeResult search_escape(const EscapeProblem& problem, const EscapeSearchOptions& options,
                           const std::optional<Eigen::Vector3d>& pull = std::nullopt);

/// The object translated along `pull` in small steps, slightly perturbed when blocked, until it is
/// out or stuck (energy-bounded as search_escape): the cheap catch of plain slides.
EscapeResult straight_pull(const EscapeProblem& problem, const EscapeSearchOptions& options,
                           const Eigen::Vector3d& pull);

/// One stage of the secure-clasp check (SecureClaspReport::stages).
struct VerificationStage {
  std::string name;  ///< "random_motions", "escape_search", "gravity", "approach"
  bool ran = false;
  bool passed = false;  ///< the object held (false when it got free or the stage timed out)
  bool timed_out = false;
  int iterations = 0;                       ///< random motions run, or RRT-Connect iterations
  double seconds = 0;                       ///< wall time: not part of any deterministic output
  std::optional<Eigen::Isometry3d> escape;  ///< where the object got free, as the report's
};

/// The stages after the random motions, in order.
enum class EscapeStage { kEscapeSearch, kGravity, kApproach };
const char* stage_name(EscapeStage stage);

/// Runs one stage: escape_search is search_escape() unbounded; gravity pulls along (0, 0, -1) and
/// approach along the hand's approach direction, each a straight_pull() then an energy-bounded
/// search_escape(). Each stage draws from its own stream of options.seed.
VerificationStage run_escape_stage(EscapeStage stage, const EscapeProblem& problem,
                                   const EscapeSearchOptions& options);

}  // namespace claspplan::tsrrt
