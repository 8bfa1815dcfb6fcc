// BUILD-TS-RRT on a toy problem: a point in the plane with a "hand" coordinate that closes only
// near the goal, and a wall between start and goal.
#include "tsrrt/planner.hpp"

#include <chrono>

#include <gtest/gtest.h>

namespace claspplan::test {
namespace {

using tsrrt::TaskPoint;

// q = (x, y, closure). The task position is (x, y, 0); the linking is the closure.
class ToyProblem : public tsrrt::PlanningProblem {
 public:
  bool wall = true;
  int checks = 0;

  TaskPoint project(const Eigen::VectorXd& q) override {
    return {Eigen::Vector3d(q[0], q[1], 0.0), q[2]};
  }
  // A proportional step toward x1; the hand closes only within 5 cm of the target position, like
  // Alg. 4's gain shifting priority from position to hand.
  Eigen::VectorXd control(const Eigen::VectorXd& q0, const TaskPoint& x0,
                          const TaskPoint& x1) override {
    Eigen::VectorXd q = q0;
    Eigen::Vector2d d = (x1.position - x0.position).head<2>();
    if (d.norm() > 0.02) d *= 0.02 / d.norm();
    q.head<2>() += d;
    if ((x1.position - x0.position).norm() < 0.05) {
      q[2] += std::clamp(x1.linking - x0.linking, -0.05, 0.05);
    }
    return q;
  }
  bool blocked(const Eigen::VectorXd& q) const {
    return wall && q[0] > 0.4 && q[0] < 0.6 && q[1] < 0.8;
  }
  bool motion_free(const Eigen::VectorXd& q0, const Eigen::VectorXd& q1) override {
    ++checks;
    const int n = 1 + static_cast<int>((q1 - q0).head<2>().norm() / 0.005);
    for (int i = 0; i <= n; ++i) {
      if (blocked(q0 + (q1 - q0) * (static_cast<double>(i) / n))) return false;
    }
    return true;
  }
  bool reached(const TaskPoint& x, const TaskPoint& goal) const override {
    return x.linking >= 0.8 && (x.position - goal.position).norm() < 0.02;
  }
};

tsrrt::PlannerParameters toy_parameters() {
  tsrrt::PlannerParameters p;
  p.sample_min = Eigen::Vector3d(-0.5, -1.5, 0.0);
  p.sample_max = Eigen::Vector3d(1.5, 1.5, 0.0);
  p.pre_expansions = 20;
  p.max_cycles = 2000;
  p.random_probability = 0.5;
  p.seed = 11;
  return p;
}

const Eigen::VectorXd kStart = Eigen::Vector3d(0.0, 0.0, 0.0);
const std::vector<TaskPoint> kGoals = {{Eigen::Vector3d(1.0, 0.0, 0.0), 1.0},
                                       {Eigen::Vector3d(1.0, 0.1, 0.0), 1.0}};

TEST(TsRrt, ConnectsDirectlyWhenUnobstructed) {
  ToyProblem toy;
  toy.wall = false;
  auto p = toy_parameters();
  p.random_probability = 0.0;
  const auto r = tsrrt::build_ts_rrt(toy, kStart, kGoals, p);
  ASSERT_TRUE(r.success) << r.reason;
  EXPECT_EQ(r.cycles, 1);
  EXPECT_GE(r.path.back()[2], 0.8);
  EXPECT_EQ(r.path.front(), kStart);
}

TEST(TsRrt, GoesAroundAnObstacleWithCollisionFreeSegments) {
  ToyProblem toy;
  const auto r = tsrrt::build_ts_rrt(toy, kStart, kGoals, toy_parameters());
  ASSERT_TRUE(r.success) << r.reason;
  EXPECT_GT(r.cycles, 1);  // the first connect attempts hit the wall
  EXPECT_EQ(static_cast<int>(r.solution_nodes.size()), static_cast<int>(r.path.size()));
  bool went_around = false;
  for (std::size_t i = 0; i + 1 < r.path.size(); ++i) {
    // Checked at ten times the planner's resolution.
    for (int k = 0; k <= 100; ++k) {
      const Eigen::VectorXd q = r.path[i] + (r.path[i + 1] - r.path[i]) * (k / 100.0);
      ASSERT_FALSE(toy.blocked(q)) << "segment " << i;
    }
    went_around |= r.path[i][1] >= 0.8;
  }
  EXPECT_TRUE(went_around);
  EXPECT_TRUE(toy.reached(toy.project(r.path.back()), kGoals[r.goal_index]));
}

TEST(TsRrt, SameSeedSamePlan) {
  ToyProblem a, b;
  const auto ra = tsrrt::build_ts_rrt(a, kStart, kGoals, toy_parameters());
  const auto rb = tsrrt::build_ts_rrt(b, kStart, kGoals, toy_parameters());
  ASSERT_TRUE(ra.success);
  EXPECT_EQ(ra.cycles, rb.cycles);
  EXPECT_EQ(ra.nodes, rb.nodes);
  ASSERT_EQ(ra.path.size(), rb.path.size());
  for (std::size_t i = 0; i < ra.path.size(); ++i) EXPECT_EQ(ra.path[i], rb.path[i]);
  auto p = toy_parameters();
  p.seed = 12;
  ToyProblem c;
  const auto rc = tsrrt::build_ts_rrt(c, kStart, kGoals, p);
  EXPECT_NE(rc.nodes, ra.nodes);
}

TEST(TsRrt, UnreachableGoalEndsWithAReason) {
  ToyProblem toy;
  const std::vector<TaskPoint> inside_wall = {{Eigen::Vector3d(0.5, 0.0, 0.0), 1.0}};
  auto p = toy_parameters();
  p.max_cycles = 60;
  const auto r = tsrrt::build_ts_rrt(toy, kStart, inside_wall, p);
  EXPECT_FALSE(r.success);
  EXPECT_EQ(r.cycles, 60);
  EXPECT_NE(r.reason.find("60 cycles"), std::string::npos) << r.reason;
}

TEST(TsRrt, TimeLimitIsRespectedWithinTenPercent) {
  // A wall-clock limit is a contract, so it is tested: the search must stop by it.
  ToyProblem toy;
  const std::vector<TaskPoint> inside_wall = {{Eigen::Vector3d(0.5, 0.0, 0.0), 1.0}};
  auto p = toy_parameters();
  p.max_cycles = 100000000;
  p.time_limit = 0.5;
  const auto start = std::chrono::steady_clock::now();
  const auto r = tsrrt::build_ts_rrt(toy, kStart, inside_wall, p);
  const double elapsed =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  EXPECT_FALSE(r.success);
  EXPECT_TRUE(r.timed_out);
  EXPECT_GE(elapsed, 0.5);
  EXPECT_LE(elapsed, 0.55);
}

TEST(PathPruning, ShortensAndKeepsTheEnds) {
  ToyProblem toy;
  const auto r = tsrrt::build_ts_rrt(toy, kStart, kGoals, toy_parameters());
  ASSERT_TRUE(r.success);
  const auto pruned = tsrrt::prune_path(toy, r.path, 200, 3);
  EXPECT_LT(pruned.size(), r.path.size());
  EXPECT_EQ(pruned.front(), r.path.front());
  EXPECT_EQ(pruned.back(), r.path.back());
  for (std::size_t i = 0; i + 1 < pruned.size(); ++i)
    EXPECT_TRUE(toy.motion_free(pruned[i], pruned[i + 1]));
  EXPECT_EQ(tsrrt::prune_path(toy, r.path, 200, 3), pruned);  // seeded
}

}  // namespace
}  // namespace claspplan::test
