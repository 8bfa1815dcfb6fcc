#include "tsrrt/planner.hpp"

#include <algorithm>
#include <cstdio>
#include <limits>
#include <numeric>
#include <optional>
#include <random>
#include <set>

#include "core/random_draws.hpp"
#include "tsrrt/elapsed.hpp"
#include "tsrrt/task_tree.hpp"

namespace claspplan::tsrrt {

namespace {

// The i-th term (from 1) of Luby, Sinclair and Zuckerman's sequence 1, 1, 2, 1, 1, 2, 4, 1, ...:
// restart intervals in these proportions lose at most a logarithmic factor against the best
// interval for a search whose run time is unknown (Inf. Process. Lett. 47, 1993).
int luby(int i) {
  for (int k = 1;; ++k) {
    if (i == (1 << k) - 1) return 1 << (k - 1);
    if (i < (1 << k) - 1) return luby(i - (1 << (k - 1)) + 1);
  }
}

// How one TS-CONNECT-GOAL attempt ended.
enum class Ending {
  kAccepted,
  kRejected,
  kObject,
  kEnvironment,
  kUnseen,
  kSelf,
  kJointLimits,
  kStall,
  kStepCap,
  kTimeLimit,
};

int& counter(ConnectOutcomes& o, Ending e) {
  switch (e) {
    case Ending::kAccepted:
      return o.accepted;
    case Ending::kRejected:
      return o.rejected;
    case Ending::kObject:
      return o.contact_object;
    case Ending::kEnvironment:
      return o.contact_environment;
    case Ending::kUnseen:
      return o.contact_unseen;
    case Ending::kSelf:
      return o.self_collision;
    case Ending::kJointLimits:
      return o.joint_limits;
    case Ending::kStall:
      return o.stall;
    case Ending::kStepCap:
      return o.step_cap;
    case Ending::kTimeLimit:
      break;
  }
  return o.time_limit;
}

Ending collision_ending(MotionCheck c) {
  switch (c) {
    case MotionCheck::kEnvironment:
      return Ending::kEnvironment;
    case MotionCheck::kUnseen:
      return Ending::kUnseen;
    case MotionCheck::kSelf:
      return Ending::kSelf;
    default:
      return Ending::kObject;
  }
}

std::string format_seconds(double s) {
  char text[32];
  std::snprintf(text, sizeof text, "%g", s);
  return text;
}

// "212 connect attempts; most ended in contact with the object (151); 12 detours".
std::string describe(const ConnectOutcomes& o) {
  if (o.attempts == 0) return "no connect attempts";
  std::string text =
      std::to_string(o.attempts) + (o.attempts == 1 ? " connect attempt" : " connect attempts");
  // The failed endings in order of precedence on ties.
  const std::pair<int, const char*> endings[] = {
      {o.contact_object, "ended in contact with the object"},
      {o.contact_environment, "ended in contact with the environment"},
      {o.contact_unseen, "ran into space no sensor saw"},
      {o.self_collision, "ended in self-collision"},
      {o.joint_limits, "ended at the joint limits"},
      {o.stall, "stopped making progress"},
      {o.rejected, "reached the goal but were rejected (insecure clasp)"},
      {o.step_cap, "ran out of steps"},
      {o.time_limit, "were cut short by the time limit"},
  };
  const auto* main = &endings[0];
  for (const auto& e : endings)
    if (e.first > main->first) main = &e;
  if (main->first > 0) {
    text += o.attempts == 1 ? "; it " : "; most ";
    text += main->second + std::string(" (") + std::to_string(main->first) + ")";
  }
  if (o.unseen_space_leads() && main->second != endings[2].second)
    text += "; " + std::to_string(o.contact_unseen) + " ran into space no sensor saw";
  if (o.rejected > 0 && main->second != endings[6].second) {
    text += "; " + std::to_string(o.rejected) + " reached the goal but were rejected";
  }
  text += "; " + std::to_string(o.detours) + (o.detours == 1 ? " detour" : " detours");
  if (o.restarts > 0)
    text += "; " + std::to_string(o.restarts) + (o.restarts == 1 ? " restart" : " restarts");
  if (o.sampled > 0) {
    text += "; " + std::to_string(o.sampled) + " approaches from sampled configurations (" +
            std::to_string(o.sampled_clasps) + " reached a clasp)";
  }
  return text;
}

// An attempt's progress toward its goal: one that gains neither approach nor linking for
// stall_steps steps is stuck, at the joint limits when the controller held joints in most of them.
class Progress {
 public:
  Progress(const TaskPoint& x, const TaskPoint& goal)
      : distance_((x.position - goal.position).norm()), linking_(x.linking) {}

  /// After a step to x (`held`: the controller held a joint at its limit): how the attempt ends
  /// when it is stuck, else nothing.
  std::optional<Ending> update(const TaskPoint& x, const TaskPoint& goal, bool held,
                               const PlannerParameters& p) {
    const double distance = (x.position - goal.position).norm();
    const bool progress =
        distance < distance_ - p.stall_position || x.linking > linking_ + p.stall_linking;
    distance_ = std::min(distance_, distance);
    linking_ = std::max(linking_, x.linking);
    stalled_ = progress ? 0 : stalled_ + 1;
    limited_ = progress ? 0 : limited_ + (held ? 1 : 0);
    if (stalled_ < p.stall_steps) return std::nullopt;
    return 2 * limited_ >= stalled_ ? Ending::kJointLimits : Ending::kStall;
  }

 private:
  double distance_, linking_;
  int stalled_ = 0, limited_ = 0;
};

class TsRrt {
 public:
  TsRrt(PlanningProblem& problem, const std::vector<TaskPoint>& goals, const PlannerParameters& p)
      : problem_(problem),
        goals_(goals),
        p_(p),
        tree_(p.linking_scale),
        rng_(p.seed),
        tried_(goals.size()),
        approaches_(goals.size()),
        asked_(goals.size(), 0),
        next_approach_(goals.size(), 0),
        start_(Clock::now()) {}

  PlanResult run(const Eigen::VectorXd& q_init) {
    grow(q_init);
    for (result_.cycles = 1; result_.cycles <= p_.max_cycles; ++result_.cycles) {
      if (out_of_time()) break;
      // The current tree lives restart_cycles times the next term of Luby's sequence.
      if (p_.restart_cycles > 0 &&
          result_.cycles >
              restarted_at_ + p_.restart_cycles * luby(result_.outcomes.restarts + 1)) {
        restarted_at_ = result_.cycles - 1;
        ++result_.outcomes.restarts;
        grow(q_init);
        if (out_of_time()) break;
      }
      if (!branches_.empty()) {
        join();
        if (result_.success) break;
      }
      if (uniform01(rng_()) < p_.random_probability) {
        extend(random_sample());
        continue;
      }
      // (No draw in the first cycles: a search that ends there is the paper's, unchanged.)
      if (result_.cycles - restarted_at_ > p_.sample_after && p_.sample_probability > 0.0 &&
          uniform01(rng_()) < p_.sample_probability) {
        // As many approaches as a cycle has connect attempts.
        for (std::size_t g = 0; g < goals_.size() && !result_.success && !out_of_time(); ++g) {
          sample_approach();
          if (!branches_.empty()) join();
        }
        if (result_.success) break;
        continue;
      }
      for (std::size_t g = 0; g < goals_.size() && !result_.success && !out_of_time(); ++g) {
        connect(static_cast<int>(g));
      }
      if (result_.success) break;
    }
    if (!result_.success) {
      result_.cycles = std::min(result_.cycles, p_.max_cycles);
      result_.reason =
          (result_.stopped ? std::string("search stopped by the caller")
           : result_.timed_out
               ? "no clasp found within the time limit (" + format_seconds(p_.time_limit) + " s)"
               : "no clasp found within " + std::to_string(p_.max_cycles) + " cycles") +
          ": " + describe(result_.outcomes);
    }
    result_.nodes = tree_.size();
    for (int i = 0; i < tree_.size(); ++i) {
      result_.tree_points.push_back(tree_[i].x);
      result_.tree_parents.push_back(tree_[i].parent);
    }
    return result_;
  }

 private:
  // A new tree: the root q_init and the pre-expansion (Alg. 1, lines 1-4).
  void grow(const Eigen::VectorXd& q_init) {
    tree_.clear();
    for (auto& nodes : tried_) nodes.clear();
    tree_.add(q_init, problem_.project(q_init), -1);
    for (int i = 0; i < p_.pre_expansions && !out_of_time(); ++i) extend(random_sample());
  }

  bool out_of_time() {
    if (p_.time_limit > 0.0 && since(start_) >= p_.time_limit) {
      result_.timed_out = true;
    }
    if (!result_.timed_out && p_.stop && p_.stop()) result_.timed_out = result_.stopped = true;
    return result_.timed_out;
  }

  TaskPoint random_sample() {
    TaskPoint x;
    for (int k = 0; k < 3; ++k) {
      x.position[k] = p_.sample_min[k] + uniform01(rng_()) * (p_.sample_max[k] - p_.sample_min[k]);
    }
    x.linking = uniform01(rng_());
    return x;
  }

  // Alg. 2: controlled steps from the nearest node toward x; each kept when collision-free.
  void extend(const TaskPoint& x) { extend_from(tree_.nearest(x), x, p_.extend_steps, 0.0); }

  // Up to `steps` controlled steps from node `near` toward x, until a collision or within `reach`
  // metres of x. Returns the last node.
  int extend_from(int near, const TaskPoint& x, int steps, double reach) {
    for (int s = 0; s < steps && !out_of_time(); ++s) {
      if (reach > 0.0 && (tree_[near].x.position - x.position).norm() <= reach) break;
      const Eigen::VectorXd q_new = problem_.control(tree_[near].q, tree_[near].x, x);
      ++result_.control_steps;
      if (problem_.check_motion(tree_[near].q, q_new) != MotionCheck::kFree) {
        ++result_.outcomes.extend_collisions;
        break;
      }
      near = tree_.add(q_new, problem_.project(q_new), near);
    }
    return near;
  }

  // Alg. 3 from the nearest node not yet used for goal g. An attempt that fails (in contact with
  // the object, the environment or the robot itself, stuck, or at a goal node the clasp check
  // rejects) is followed by a detour: from nearby, the controller would bring the next attempt
  // the same way (a loop just above the floor is approached from the side, not from above).
  void connect(int g) {
    const int near = tree_.nearest(goals_[g], [&](int i) { return tried_[g].count(i) == 0; });
    if (near < 0) return;
    std::vector<int> nodes;
    const Ending ending = attempt(g, near, nodes);
    if (ending != Ending::kAccepted && ending != Ending::kTimeLimit) detour(g, nodes);
  }

  // Another approach direction after a failed attempt along `nodes`: back off along the attempt,
  // extend toward goal g's next approach point, and connect to g from there.
  void detour(int g, const std::vector<int>& nodes) {
    if (out_of_time()) return;
    if (!asked_[g]) approaches_[g] = problem_.approaches(g), asked_[g] = 1;
    if (approaches_[g].empty()) return;
    const TaskPoint& via = approaches_[g][next_approach_[g]++ % approaches_[g].size()];
    ++result_.outcomes.detours;
    const int back = std::max(0, static_cast<int>(nodes.size()) - 1 - p_.backoff_steps);
    const int from = nodes[back];
    const int end = extend_from(from, via, p_.detour_steps, p_.detour_reach);
    if (end == from || tried_[g].count(end) != 0) return;  // it would repeat the attempt
    std::vector<int> again;
    attempt(g, end, again);
  }

  // One TS-CONNECT-GOAL attempt: the controller iterated toward goal g from node `near` until a
  // collision, the goal, the step cap, or no progress. `nodes` gets the attempt's start node and
  // the nodes it added, in order.
  Ending attempt(int g, int near, std::vector<int>& nodes) {
    const Ending ending = run_attempt(g, near, nodes);
    ++result_.outcomes.attempts;
    ++counter(result_.outcomes, ending);
    return ending;
  }

  Ending run_attempt(int g, int near, std::vector<int>& nodes) {
    tried_[g].insert(near);
    nodes.push_back(near);
    const Ending ending =
        steer(tree_[near].q, tree_[near].x, goals_[g], [&](const auto& q, const auto& x) {
          near = tree_.add(q, x, near);
          nodes.push_back(near);
          tried_[g].insert(near);  // continuing from it toward g would repeat this attempt
        });
    // A rejected goal node stays: continuing from it toward g would only hover there.
    if (ending == Ending::kRejected) ++result_.rejected_goals;
    if (ending == Ending::kAccepted) succeed(g, near);
    return ending;
  }

  // The search ends with goal g reached through tree node `node`.
  void succeed(int g, int node) {
    result_.success = true;
    result_.goal_index = g;
    result_.path = tree_.path_to(node);
    for (int i = node; i >= 0; i = tree_[i].parent) result_.solution_nodes.push_back(i);
    std::reverse(result_.solution_nodes.begin(), result_.solution_nodes.end());
  }

  // The controller iterated from (q, x) toward `goal` (Alg. 3's inner loop), each collision-free
  // step handed to `keep(q, x)`, until a collision, the goal (accepted or rejected by the
  // problem), the step cap, no progress, or the time limit.
  template <class Keep>
  Ending steer(Eigen::VectorXd q, TaskPoint x, const TaskPoint& goal, Keep keep) {
    Progress progress(x, goal);
    for (int s = 0; s < p_.connect_steps; ++s) {
      if (out_of_time()) return Ending::kTimeLimit;
      Eigen::VectorXd q_new = problem_.control(q, x, goal);
      const bool held = problem_.control_limited();
      ++result_.control_steps;
      const MotionCheck check = problem_.check_motion(q, q_new);
      if (check != MotionCheck::kFree) return collision_ending(check);
      q = std::move(q_new);
      x = problem_.project(q);
      keep(q, x);
      if (problem_.reached(x, goal))
        return problem_.accept(q) ? Ending::kAccepted : Ending::kRejected;
      if (const std::optional<Ending> stuck = progress.update(x, goal, held, p_)) return *stuck;
    }
    return Ending::kStepCap;
  }

  // Goal sampling: one connect attempt from a random configuration toward the goal nearest to
  // its hand. An accepted clasp adds the attempt to the branches, its goal their root.
  void sample_approach() {
    Eigen::VectorXd q;
    if (!problem_.sample_configuration([this] { return rng_(); }, q)) return;
    ++result_.outcomes.sampled;
    const TaskPoint x = problem_.project(q);
    int g = 0;
    for (int i = 1; i < static_cast<int>(goals_.size()); ++i) {
      if ((goals_[i].position - x.position).squaredNorm() <
          (goals_[g].position - x.position).squaredNorm())
        g = i;
    }
    std::vector<Eigen::VectorXd> chain{q};
    const auto keep = [&](const Eigen::VectorXd& q_new, const TaskPoint&) {
      chain.push_back(q_new);
    };
    if (steer(q, x, goals_[g], keep) != Ending::kAccepted) return;
    ++result_.outcomes.sampled_clasps;
    for (auto it = chain.rbegin(); it != chain.rend(); ++it) {
      const int parent = it == chain.rbegin() ? -1 : static_cast<int>(branches_.size()) - 1;
      branches_.push_back({*it, parent, g});
    }
  }

  // One iteration of RRT-Connect in joint space between the tree and the branches: one tree takes
  // a step toward a random configuration, the other connects to the new node; the two alternate.
  void join() {
    Eigen::VectorXd q_rand;
    if (!problem_.sample_configuration([this] { return rng_(); }, q_rand)) return;
    join_from_tree_ = !join_from_tree_;
    if (join_from_tree_) {
      const int a = nearest_configuration(q_rand, false);
      const int a_new = joint_step(a, q_rand, false);
      if (a_new < 0) return;
      const int b = connect_configuration(tree_[a_new].q, true);
      if (b >= 0) finish(a_new, b);
    } else {
      const int b = nearest_configuration(q_rand, true);
      const int b_new = joint_step(b, q_rand, true);
      if (b_new < 0) return;
      const int a = connect_configuration(branches_[b_new].q, false);
      if (a >= 0) finish(a, b_new);
    }
  }

  const Eigen::VectorXd& configuration(int i, bool branch) const {
    return branch ? branches_[i].q : tree_[i].q;
  }

  // The node nearest to q in joint space, of the branches or of the tree.
  int nearest_configuration(const Eigen::VectorXd& q, bool branch) const {
    const int n = branch ? static_cast<int>(branches_.size()) : tree_.size();
    int best = 0;
    double best_d = std::numeric_limits<double>::infinity();
    for (int i = 0; i < n; ++i) {
      const double d = (configuration(i, branch) - q).squaredNorm();
      if (d < best_d) best_d = d, best = i;
    }
    return best;
  }

  // A collision-free joint-space step of at most joint_step per joint from node `from` toward q:
  // the new node, or -1. A branch node's parent is the node it came from (toward its goal).
  int joint_step(int from, const Eigen::VectorXd& q, bool branch) {
    const Eigen::VectorXd& q0 = configuration(from, branch);
    const double longest = (q - q0).cwiseAbs().maxCoeff();
    const Eigen::VectorXd q1 =
        longest <= p_.joint_step ? q : Eigen::VectorXd(q0 + (q - q0) * (p_.joint_step / longest));
    if (problem_.check_motion(q0, q1) != MotionCheck::kFree) return -1;
    if (!branch) return tree_.add(q1, problem_.project(q1), from);
    branches_.push_back({q1, from, branches_[from].goal});
    return static_cast<int>(branches_.size()) - 1;
  }

  // Joint-space steps from the nearest node toward q until blocked (-1) or there (that node).
  int connect_configuration(const Eigen::VectorXd& q, bool branch) {
    int i = nearest_configuration(q, branch);
    while (configuration(i, branch) != q) {
      if (out_of_time()) return -1;
      i = joint_step(i, q, branch);
      if (i < 0) return -1;
    }
    return i;
  }

  // Tree node a and branch node b hold the same configuration: the path runs through the tree to
  // a, then along b's branch to its goal, whose clasp is accepted again (the problem keeps the
  // clasp it accepted last).
  void finish(int a, int b) {
    int root = b;
    while (branches_[root].parent >= 0) root = branches_[root].parent;
    if (!problem_.accept(branches_[root].q)) return;
    ++result_.outcomes.joined;
    succeed(branches_[root].goal, a);
    for (int i = branches_[b].parent; i >= 0; i = branches_[i].parent)
      result_.path.push_back(branches_[i].q);
  }

  PlanningProblem& problem_;
  const std::vector<TaskPoint>& goals_;
  const PlannerParameters& p_;
  TaskTree tree_;
  std::mt19937_64 rng_;
  std::vector<std::set<int>> tried_;                // nodes already extended toward each goal
  std::vector<std::vector<TaskPoint>> approaches_;  // each goal's detour points, once asked
  std::vector<char> asked_;
  std::vector<std::size_t> next_approach_;  // each goal's next detour point (cycling)
  // Goal sampling: the sampled attempts that reached an accepted clasp, as a joint-space forest
  // whose roots are their goal configurations (each node's parent is the next toward its root).
  struct BranchNode {
    Eigen::VectorXd q;
    int parent = -1;
    int goal = -1;
  };
  std::vector<BranchNode> branches_;
  bool join_from_tree_ = false;
  int restarted_at_ = 0;  // the cycle after which the current tree was grown
  Clock::time_point start_;
  PlanResult result_;
};

}  // namespace

PlanResult build_ts_rrt(PlanningProblem& problem, const Eigen::VectorXd& q_init,
                        const std::vector<TaskPoint>& goals, const PlannerParameters& p) {
  return TsRrt(problem, goals, p).run(q_init);
}

std::vector<Eigen::VectorXd> prune_path(PlanningProblem& problem, std::vector<Eigen::VectorXd> path,
                                        int attempts, std::uint64_t seed) {
  // Shortcuts are found with the search's check and only the kept ones get shortcut_free()'s
  // finer one: most tried shortcuts are later cut by longer ones.
  std::vector<std::size_t> kept(path.size());  // the waypoints kept, as indices into `path`
  std::iota(kept.begin(), kept.end(), std::size_t{0});
  std::mt19937_64 rng(seed);
  for (int a = 0; a < attempts && kept.size() > 2; ++a) {
    const auto n = kept.size();
    std::size_t i = static_cast<std::size_t>(uniform01(rng()) * n);
    std::size_t j = static_cast<std::size_t>(uniform01(rng()) * n);
    if (i > j) std::swap(i, j);
    if (j < i + 2) continue;
    if (problem.motion_free(path[kept[i]], path[kept[j]]))
      kept.erase(kept.begin() + static_cast<std::ptrdiff_t>(i) + 1,
                 kept.begin() + static_cast<std::ptrdiff_t>(j));
  }
  // A kept shortcut that fails the finer check gives its steps back.
  std::vector<Eigen::VectorXd> out{path.front()};
  for (std::size_t k = 1; k < kept.size(); ++k) {
    const std::size_t from = kept[k - 1], to = kept[k];
    if (to > from + 1 && !problem.shortcut_free(path[from], path[to]))
      out.insert(out.end(), path.begin() + static_cast<std::ptrdiff_t>(from) + 1,
                 path.begin() + static_cast<std::ptrdiff_t>(to));
    out.push_back(path[to]);
  }
  return out;
}

}  // namespace claspplan::tsrrt
