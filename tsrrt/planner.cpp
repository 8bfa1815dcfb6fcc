#include "tsrrt/planner.hpp"

#include <algorithm>
#include <chrono>
#include <random>
#include <set>

#include "tsrrt/task_tree.hpp"

namespace claspplan::tsrrt {

double uniform01(std::uint64_t bits) {
  return static_cast<double>(bits >> 11) * 0x1.0p-53;
}

namespace {

using Clock = std::chrono::steady_clock;

class TsRrt {
 public:
  TsRrt(PlanningProblem& problem, const std::vector<TaskPoint>& goals, const PlannerParameters& p)
      : problem_(problem),
        goals_(goals),
        p_(p),
        tree_(p.linking_scale),
        rng_(p.seed),
        tried_(goals.size()),
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
      result_.reason = result_.timed_out
                           ? "no clasp found within the time limit"
                           : "no clasp found within " + std::to_string(p_.max_cycles) + " cycles";
      if (result_.rejected_goals > 0) {
        result_.reason += " (" + std::to_string(result_.rejected_goals) +
                          " reached the goal tolerance but were rejected)";
      }
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

  // Alg. 2: one controlled step from the nearest node toward x; kept when collision-free.
  void extend(const TaskPoint& x) {
    int near = tree_.nearest(x);
    for (int s = 0; s < p_.extend_steps && !out_of_time(); ++s) {
      const Eigen::VectorXd q_new = problem_.control(tree_[near].q, tree_[near].x, x);
      ++result_.control_steps;
      if (!problem_.motion_free(tree_[near].q, q_new)) return;
      near = tree_.add(q_new, problem_.project(q_new), near);
    }
  }

  // Alg. 3: iterate the controller toward goal g from the nearest node not yet used for g, until a
  // collision, the goal, the step cap, or no progress.
  void connect(int g) {
    const TaskPoint& goal = goals_[g];
    int near = tree_.nearest(goal, [&](int i) { return tried_[g].count(i) == 0; });
    if (near < 0) return;
    tried_[g].insert(near);
    double best_distance = (tree_[near].x.position - goal.position).norm();
    double best_linking = tree_[near].x.linking;
    int stalled = 0;
    for (int s = 0; s < p_.connect_steps && !out_of_time(); ++s) {
      const Eigen::VectorXd q_new = problem_.control(tree_[near].q, tree_[near].x, goal);
      ++result_.control_steps;
      if (!problem_.motion_free(tree_[near].q, q_new)) return;
      const TaskPoint x_new = problem_.project(q_new);
      near = tree_.add(q_new, x_new, near);
      tried_[g].insert(near);  // continuing from it toward g would repeat this attempt
      if (problem_.reached(x_new, goal)) {
        if (!problem_.accept(q_new)) {
          ++result_.rejected_goals;
          return;  // continuing from here toward g would only hover at the same clasp
        }
        result_.success = true;
        result_.goal_index = g;
        result_.path = tree_.path_to(near);
        for (int i = near; i >= 0; i = tree_[i].parent) result_.solution_nodes.push_back(i);
        std::reverse(result_.solution_nodes.begin(), result_.solution_nodes.end());
        return;
      }
      const double distance = (x_new.position - goal.position).norm();
      const bool progress = distance < best_distance - p_.stall_position ||
                            x_new.linking > best_linking + p_.stall_linking;
      best_distance = std::min(best_distance, distance);
      best_linking = std::max(best_linking, x_new.linking);
      stalled = progress ? 0 : stalled + 1;
      if (stalled >= p_.stall_steps) return;
    }
  }

  PlanningProblem& problem_;
  const std::vector<TaskPoint>& goals_;
  const PlannerParameters& p_;
  TaskTree tree_;
  std::mt19937_64 rng_;
  std::vector<std::set<int>> tried_;  // nodes already extended toward each goal
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
