// BUILD-TS-RRT (paper Alg. 1) with TS-EXTEND (Alg. 2) and TS-CONNECT-GOAL (Alg. 3), extended by
// detours after failed attempts and by goal sampling (attempts from random configurations, joined
// to the tree in joint space); and the randomized path pruning applied to its solution.
#pragma once

#include <algorithm>
#include <cstdint>
#include <functional>
#include <string>
#include <vector>

#include <Eigen/Core>

#include "tsrrt/problem.hpp"

namespace claspplan::tsrrt {

struct PlannerParameters {
  double random_probability = 0.1;  ///< P: chance of a random TS-EXTEND instead of goal connects
  int pre_expansions = 50;          ///< n: random extensions before the main loop
  /// K. Effectively unbounded by default: the time limit bounds the search.
  int max_cycles = 100000;
  double time_limit = 10.0;  ///< wall-clock limit in seconds; 0 = none
  /// Polled with the time limit: true ends the search as the limit would (a caller's cancel: a
  /// GUI's button, Ctrl-C in Python). It is called at every controller step: keep it cheap.
  std::function<bool()> stop;
  /// Controller steps per TS-EXTEND, each kept as a node: with the controller's 2 cm position
  /// cap a one-step extension barely explores, so an extension runs up to ~20 cm.
  int extend_steps = 10;
  int connect_steps = 250;       ///< step cap of one TS-CONNECT-GOAL attempt
  int stall_steps = 25;          ///< a connect attempt ends after this many steps without progress
  double stall_position = 5e-4;  ///< metres of approach that count as progress
  double stall_linking = 2e-3;   ///< virtual linking gained that counts as progress
  /// A connect attempt that ends against the object (contact, stall or joint limits) is followed
  /// by a detour (PlanningProblem::approaches()): back off this many nodes along the attempt, ...
  int backoff_steps = 5;
  /// ... extend toward the detour point for up to this many controller steps (each a node; the
  /// extension stops within `detour_reach` metres of the point) and connect to the goal again.
  int detour_steps = 20;
  double detour_reach = 0.01;
  /// Goal sampling, an extension of Alg. 1: after the first `sample_after` cycles, a cycle with
  /// this probability runs its connect attempts (one per goal) from random collision-free
  /// configurations (PlanningProblem::sample_configuration()) instead of from the tree. A clasp
  /// one reaches is joined to the tree by a joint-space RRT-Connect, one iteration after each
  /// attempt and at the start of each cycle. It finds clasps whose approach the tree's nearest
  /// nodes never take (a handle reached past the body). 0: the paper's algorithm.
  double sample_probability = 0.5;
  int sample_after = 10;
  double joint_step = 0.1;  ///< rad: the longest joint move of one joint-space step
  /// Restarts, an extension of Alg. 1: a search without a clasp drops its tree and grows a new
  /// one from q_init (pre-expansion included), after restart_cycles times 1, 1, 2, 1, 1, 2, 4, ...
  /// cycles (Luby's sequence). A tree that failed near the loop offers its nodes there, pressed
  /// against the object, to every later attempt, while a clasp either comes in a tree's first
  /// cycles or late; a new tree starts from fresh random extensions. The accepted clasps of goal
  /// sampling are kept. 0: never (the paper's algorithm).
  int restart_cycles = 30;
  /// RANDOM-TS-SAMPLE: positions uniform in this box (world frame), linking uniform in [0, 1].
  Eigen::Vector3d sample_min = Eigen::Vector3d::Constant(-1.0);
  Eigen::Vector3d sample_max = Eigen::Vector3d::Constant(1.0);
  double linking_scale = 0.1;  ///< metres one unit of linking counts as, for nearest neighbours
  std::uint64_t seed = 1;
};

/// How the TS-CONNECT-GOAL attempts ended (each attempt exactly one way), and the rest of the
/// search's events.
struct ConnectOutcomes {
  int attempts = 0;             ///< connect attempts made; the endings below add up to it
  int accepted = 0;             ///< goal reached and accepted
  int rejected = 0;             ///< goal reached, but PlanningProblem::accept() refused it
  int contact_object = 0;       ///< the next step touched the object
  int contact_environment = 0;  ///< ... the static environment
  int contact_unseen = 0;       ///< ... space near the object that no sensor saw
  int self_collision = 0;       ///< ... the robot itself
  int joint_limits = 0;         ///< no progress while the controller held joints at their limits
  int stall = 0;                ///< no progress otherwise (stall_steps steps)
  int step_cap = 0;             ///< connect_steps steps without reaching the goal
  int time_limit = 0;           ///< cut short by the time limit
  int detours = 0;              ///< detours toward an approach point after a failed attempt
  int extend_collisions = 0;    ///< TS-EXTEND steps (random or detour) that ended in a collision
  int restarts = 0;             ///< new trees grown (PlannerParameters::restart_cycles)
  /// Goal sampling (not among the attempts above): approaches from sampled configurations, those
  /// that reached an accepted clasp, and whether one of those was joined to the tree.
  int sampled = 0;
  int sampled_clasps = 0;
  int joined = 0;

  /// Unseen space stopped at least a tenth of the attempts (fewer: a camera would change little)
  /// and more than any other failed ending but contact with the object (which a search for a
  /// clasp on it meets however much was seen; on a tie the environment comes first): a camera
  /// would help, and describe() names the count.
  bool unseen_space_leads() const {
    return 10 * contact_unseen >= attempts && contact_unseen > contact_environment &&
           contact_unseen >=
               std::max({self_collision, joint_limits, stall, rejected, step_cap, time_limit});
  }
  /// The sum of the endings (equals `attempts`).
  int endings() const {
    return accepted + rejected + contact_object + contact_environment + contact_unseen +
           self_collision + joint_limits + stall + step_cap + time_limit;
  }
};

struct PlanResult {
  bool success = false;
  /// Why the search ended without a goal (one line: the limit, the connect attempts, how most
  /// of them ended, the detours).
  std::string reason;
  std::vector<Eigen::VectorXd> path;  ///< start to goal configuration, when successful
  int goal_index = -1;                ///< which goal was reached
  int cycles = 0;                     ///< cycles of Alg. 1's loop after the pre-expansion
  int nodes = 0;                      ///< of the last tree
  int control_steps = 0;
  int rejected_goals = 0;  ///< nodes in goal tolerance that PlanningProblem::accept() refused
  ConnectOutcomes outcomes;
  bool timed_out = false;
  bool stopped = false;  ///< ended by PlannerParameters::stop
  /// The tree, for pictures: each node's task point and parent.
  std::vector<TaskPoint> tree_points;
  std::vector<int> tree_parents;
  std::vector<int> solution_nodes;  ///< tree indices of the path
};

/// Alg. 1. `goals` are the task-space goals x_goal = (p, 1.0) of the clasp targets.
PlanResult build_ts_rrt(PlanningProblem& problem, const Eigen::VectorXd& q_init,
                        const std::vector<TaskPoint>& goals, const PlannerParameters& p);

/// Randomized path pruning: `attempts` times, pick two waypoints at random and join them directly
/// when PlanningProblem::motion_free() allows that motion; then each shortcut kept that
/// PlanningProblem::shortcut_free() refuses is replaced by the steps it cut. The first and last
/// waypoints stay.
std::vector<Eigen::VectorXd> prune_path(PlanningProblem& problem, std::vector<Eigen::VectorXd> path,
                                        int attempts, std::uint64_t seed);

}  // namespace claspplan::tsrrt
