#include "tsrrt/planner.hpp"

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <random>
#include <set>

#include "tsrrt/task_tree.hpp"

namespace claspplan::tsrrt {

namespace {

using Clock = std::chrono::steady_clock;

// How one TS-CONNECT-GOAL attempt ended.
enum class Ending {
  kAccepted,
  kRejected,
  kObject,
  kEnvironment,
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
  if (o.rejected > 0 && main->second != endings[5].second) {
    text += "; " + std::to_string(o.rejected) + " reached the goal but were rejected";
  }
  text += "; " + std::to_string(o.detours) + (o.detours == 1 ? " detour" : " detours");
  return text;
}

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
    tree_.add(q_init, problem_.project(q_init), -1);
    for (int i = 0; i < p_.pre_expansions && !out_of_time(); ++i) extend(random_sample());
    for (result_.cycles = 1; result_.cycles <= p_.max_cycles; ++result_.cycles) {
      if (out_of_time()) break;
      if (uniform01(rng_()) < p_.random_probability) {
        extend(random_sample());
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
          (result_.timed_out
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
  bool out_of_time() {
    if (p_.time_limit > 0.0 &&
        std::chrono::duration<double>(Clock::now() - start_).count() >= p_.time_limit) {
      result_.timed_out = true;
    }
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
    const TaskPoint& goal = goals_[g];
    tried_[g].insert(near);
    nodes.push_back(near);
    double best_distance = (tree_[near].x.position - goal.position).norm();
    double best_linking = tree_[near].x.linking;
    int stalled = 0, limited = 0;
    for (int s = 0; s < p_.connect_steps; ++s) {
      if (out_of_time()) return Ending::kTimeLimit;
      const Eigen::VectorXd q_new = problem_.control(tree_[near].q, tree_[near].x, goal);
      const bool held = problem_.control_limited();
      ++result_.control_steps;
      const MotionCheck check = problem_.check_motion(tree_[near].q, q_new);
      if (check != MotionCheck::kFree) return collision_ending(check);
      const TaskPoint x_new = problem_.project(q_new);
      near = tree_.add(q_new, x_new, near);
      nodes.push_back(near);
      tried_[g].insert(near);  // continuing from it toward g would repeat this attempt
      if (problem_.reached(x_new, goal)) {
        if (!problem_.accept(q_new)) {
          ++result_.rejected_goals;
          return Ending::kRejected;  // continuing from here toward g would only hover there
        }
        result_.success = true;
        result_.goal_index = g;
        result_.path = tree_.path_to(near);
        for (int i = near; i >= 0; i = tree_[i].parent) result_.solution_nodes.push_back(i);
        std::reverse(result_.solution_nodes.begin(), result_.solution_nodes.end());
        return Ending::kAccepted;
      }
      const double distance = (x_new.position - goal.position).norm();
      const bool progress = distance < best_distance - p_.stall_position ||
                            x_new.linking > best_linking + p_.stall_linking;
      best_distance = std::min(best_distance, distance);
      best_linking = std::max(best_linking, x_new.linking);
      stalled = progress ? 0 : stalled + 1;
      limited = progress ? 0 : limited + (held ? 1 : 0);
      // Stuck: at the joint limits when the controller held joints in most of the stalled steps.
      if (stalled >= p_.stall_steps) {
        return 2 * limited >= stalled ? Ending::kJointLimits : Ending::kStall;
      }
    }
    return Ending::kStepCap;
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
  std::mt19937_64 rng(seed);
  for (int a = 0; a < attempts && path.size() > 2; ++a) {
    const auto n = path.size();
    std::size_t i = static_cast<std::size_t>(uniform01(rng()) * n);
    std::size_t j = static_cast<std::size_t>(uniform01(rng()) * n);
    if (i > j) std::swap(i, j);
    if (j < i + 2) continue;
    if (problem.motion_free(path[i], path[j])) {
      path.erase(path.begin() + static_cast<std::ptrdiff_t>(i) + 1,
                 path.begin() + static_cast<std::ptrdiff_t>(j));
    }
  }
  return path;
}

}  // namespace claspplan::tsrrt
