// BUILD-TS-RRT on a toy problem: a point in the plane with a "hand" coordinate that closes only
// near the goal, a wall (environment) between start and goal, and optionally an "object" block in
// front of the goal and a joint limit.
#include "tsrrt/planner.hpp"

#include <algorithm>
#include <chrono>
#include <cstdint>
#include <functional>
#include <limits>

#include <gtest/gtest.h>

#include "core/random_draws.hpp"

namespace claspplan::test {
namespace {

using tsrrt::TaskPoint;

// q = (x, y, closure). The task position is (x, y, 0); the linking is the closure.
class ToyProblem : public tsrrt::PlanningProblem {
 public:
  bool wall = true;     // environment: x in (0.4, 0.6), y < 0.8
  bool object = false;  // the object: x in (0.88, 0.92), |y| < 0.1, in front of (1, 0)
  double y_max = std::numeric_limits<double>::infinity();  // a joint limit on y
  std::vector<TaskPoint> detours;                          // approaches() of every goal
  int reject_first = 0;  // accept() refuses this many goal nodes first (insecure clasps)
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
    limited = q[1] > y_max;  // held at the limit
    q[1] = std::min(q[1], y_max);
    return q;
  }
  bool control_limited() const override { return limited; }
  virtual tsrrt::MotionCheck collision(const Eigen::VectorXd& q) const {
    if (wall && q[0] > 0.4 && q[0] < 0.6 && q[1] < 0.8) return tsrrt::MotionCheck::kEnvironment;
    if (object && q[0] > 0.88 && q[0] < 0.92 && std::abs(q[1]) < 0.1) {
      return tsrrt::MotionCheck::kObject;
    }
    return tsrrt::MotionCheck::kFree;
  }
  bool blocked(const Eigen::VectorXd& q) const { return collision(q) != tsrrt::MotionCheck::kFree; }
  tsrrt::MotionCheck check_motion(const Eigen::VectorXd& q0, const Eigen::VectorXd& q1) override {
    ++checks;
    const int n = 1 + static_cast<int>((q1 - q0).head<2>().norm() / 0.005);
    for (int i = 0; i <= n; ++i) {
      const auto c = collision(q0 + (q1 - q0) * (static_cast<double>(i) / n));
      if (c != tsrrt::MotionCheck::kFree) return c;
    }
    return tsrrt::MotionCheck::kFree;
  }
  std::vector<TaskPoint> approaches(int goal) override {
    (void)goal;
    return detours;
  }
  bool reached(const TaskPoint& x, const TaskPoint& goal) const override {
    return x.linking >= 0.8 && (x.position - goal.position).norm() < 0.02;
  }
  bool accept(const Eigen::VectorXd& q) override {
    (void)q;
    return ++accepts > reject_first;
  }
  int accepts = 0;

 private:
  bool limited = false;
};

tsrrt::PlannerParameters toy_parameters() {
  tsrrt::PlannerParameters p;
  p.sample_min = Eigen::Vector3d(-0.5, -1.5, 0.0);
  p.sample_max = Eigen::Vector3d(1.5, 1.5, 0.0);
  p.pre_expansions = 20;
  p.max_cycles = 2000;
  p.random_probability = 0.5;
  p.time_limit = 0.0;    // bounded by cycles: no test depends on the clock
  p.restart_cycles = 0;  // one tree, as in Alg. 1
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

// 60 cycles toward a goal inside the wall.
tsrrt::PlanResult search_into_the_wall(int restart_cycles) {
  ToyProblem toy;
  auto p = toy_parameters();
  p.max_cycles = 60;
  p.restart_cycles = restart_cycles;
  return tsrrt::build_ts_rrt(toy, kStart, {{Eigen::Vector3d(0.5, 0.0, 0.0), 1.0}}, p);
}

TEST(TsRrt, UnreachableGoalEndsWithAReason) {
  const auto r = search_into_the_wall(0);
  EXPECT_FALSE(r.success);
  EXPECT_EQ(r.cycles, 60);
  EXPECT_NE(r.reason.find("60 cycles"), std::string::npos) << r.reason;
  EXPECT_FALSE(r.timed_out);
}

TEST(TsRrt, TimeLimitEndsTheSearch) {
  // A wall-clock limit is a contract: the search stops by it, not before, and not long after (the
  // margin is generous so that a busy machine cannot fail the test; how close the stop comes to
  // the limit is a matter of speed, not of this test).
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
  EXPECT_LE(elapsed, 0.5 + 10.0);
}

TEST(TsRrt, ConnectOutcomesAddUpToTheAttempts) {
  ToyProblem toy;
  const auto r = tsrrt::build_ts_rrt(toy, kStart, kGoals, toy_parameters());
  ASSERT_TRUE(r.success) << r.reason;
  const tsrrt::ConnectOutcomes& o = r.outcomes;
  EXPECT_GT(o.attempts, 1);
  EXPECT_EQ(o.endings(), o.attempts);
  EXPECT_EQ(o.accepted, 1);
  EXPECT_GE(o.contact_environment, 1);  // the wall
  EXPECT_EQ(o.contact_object, 0);
  EXPECT_EQ(o.self_collision, 0);
  EXPECT_EQ(o.detours, 0);  // the toy offers no approaches
  EXPECT_GT(o.extend_collisions, 0);

  // A failed search: the same sum, and a reason naming the main cause.
  const std::vector<TaskPoint> inside_wall = {{Eigen::Vector3d(0.5, 0.0, 0.0), 1.0}};
  auto p = toy_parameters();
  p.max_cycles = 60;
  ToyProblem again;
  const auto f = tsrrt::build_ts_rrt(again, kStart, inside_wall, p);
  ASSERT_FALSE(f.success);
  EXPECT_EQ(f.outcomes.endings(), f.outcomes.attempts);
  EXPECT_EQ(f.outcomes.accepted, 0);
  EXPECT_GT(f.outcomes.contact_environment, f.outcomes.attempts / 2);
  const std::string expected =
      "no clasp found within 60 cycles: " + std::to_string(f.outcomes.attempts) +
      " connect attempts; most ended in contact with the environment (" +
      std::to_string(f.outcomes.contact_environment) + "); 0 detours";
  EXPECT_EQ(f.reason, expected);
}

// The object right in front of the goal: the direct approach ends in contact with it; the goal is
// reachable from the sides.
tsrrt::PlannerParameters detour_parameters() {
  auto p = toy_parameters();
  p.pre_expansions = 0;
  p.random_probability = 0.0;  // connects only: every attempt comes from a contact or a detour
  p.max_cycles = 50;
  return p;
}
const std::vector<TaskPoint> kGoalBehindObject = {{Eigen::Vector3d(1.0, 0.0, 0.0), 1.0}};

TEST(TsRrt, ContactWithTheObjectLeadsToAnotherApproach) {
  ToyProblem toy;
  toy.wall = false;
  toy.object = true;
  toy.detours = {{Eigen::Vector3d(1.0, 0.4, 0.0), 0.0},
                 {Eigen::Vector3d(1.0, -0.4, 0.0), 0.0},
                 {Eigen::Vector3d(1.3, 0.0, 0.0), 0.0}};
  const auto r = tsrrt::build_ts_rrt(toy, kStart, kGoalBehindObject, detour_parameters());
  ASSERT_TRUE(r.success) << r.reason;
  const tsrrt::ConnectOutcomes& o = r.outcomes;
  EXPECT_EQ(o.endings(), o.attempts);
  EXPECT_GE(o.contact_object, 1);  // the direct approach ...
  EXPECT_GE(o.detours, 1);         // ... is followed by one from another side
  EXPECT_GE(o.attempts, 2);
  EXPECT_EQ(o.accepted, 1);
  // The path leaves the line of the direct approach, around the object, and is collision-free.
  bool around = false;
  for (std::size_t i = 0; i + 1 < r.path.size(); ++i) {
    EXPECT_EQ(toy.check_motion(r.path[i], r.path[i + 1]), tsrrt::MotionCheck::kFree) << i;
    around |= std::abs(r.path[i][1]) >= 0.1;
  }
  EXPECT_TRUE(around);
  // Deterministic.
  ToyProblem same = toy;
  const auto r2 = tsrrt::build_ts_rrt(same, kStart, kGoalBehindObject, detour_parameters());
  EXPECT_EQ(r2.nodes, r.nodes);
  EXPECT_EQ(r2.outcomes.attempts, o.attempts);
  EXPECT_EQ(r2.path, r.path);

  // Without approaches the contact ends the search: no other node is left to connect from.
  ToyProblem plain;
  plain.wall = false;
  plain.object = true;
  const auto f = tsrrt::build_ts_rrt(plain, kStart, kGoalBehindObject, detour_parameters());
  EXPECT_FALSE(f.success);
  EXPECT_EQ(f.outcomes.attempts, 1);
  EXPECT_EQ(f.outcomes.contact_object, 1);
  EXPECT_EQ(f.outcomes.detours, 0);
  EXPECT_NE(f.reason.find("1 connect attempt; it ended in contact with the object (1)"),
            std::string::npos)
      << f.reason;
}

// Contact with the environment (the wall between start and goal) is followed by a detour too: a
// loop just above the floor needs an approach from the side.
TEST(TsRrt, ContactWithTheEnvironmentLeadsToAnotherApproach) {
  ToyProblem toy;                                         // the wall: x in (0.4, 0.6), y < 0.8
  toy.detours = {{Eigen::Vector3d(0.3, 1.6, 0.0), 0.0}};  // from there the goal is in sight
  auto p = detour_parameters();
  p.detour_steps = 80;  // around the wall's end
  const auto r = tsrrt::build_ts_rrt(toy, kStart, kGoalBehindObject, p);
  ASSERT_TRUE(r.success) << r.reason;
  EXPECT_GE(r.outcomes.contact_environment, 1);
  EXPECT_GE(r.outcomes.detours, 1);
  ToyProblem plain;  // without approach points nothing leads around the wall
  const auto f = tsrrt::build_ts_rrt(plain, kStart, kGoalBehindObject, p);
  EXPECT_FALSE(f.success);
  EXPECT_EQ(f.outcomes.detours, 0);
}

// A goal node the clasp check rejects is followed by a detour: from nearby, the controller would
// bring the next attempt to the same rejected pose.
// A goal in a pocket open only away from the start (walls on its three other sides), and no
// random extensions: every connect attempt from the tree runs into the pocket's front wall.
class PocketProblem : public ToyProblem {
 public:
  PocketProblem() { wall = false; }
  bool sampling = true;
  // The pocket is the object; ToyProblem::check_motion interpolates over it.
  tsrrt::MotionCheck collision(const Eigen::VectorXd& q) const override {
    const bool front = q[0] > 0.88 && q[0] < 0.92 && std::abs(q[1]) < 0.2;
    const bool sides = q[0] > 0.88 && q[0] < 1.2 && std::abs(q[1]) > 0.16 && std::abs(q[1]) < 0.2;
    return front || sides ? tsrrt::MotionCheck::kObject : tsrrt::MotionCheck::kFree;
  }
  bool sample_configuration(const std::function<std::uint64_t()>& bits,
                            Eigen::VectorXd& q) override {
    if (!sampling) return false;
    q = Eigen::Vector3d(-0.5 + 2.0 * uniform01(bits()), -1.5 + 3.0 * uniform01(bits()), 0.0);
    return !blocked(q);
  }
};

TEST(TsRrt, GoalSamplingReachesAClaspTheTreeCannotAndJoinsIt) {
  const std::vector<TaskPoint> goal = {{Eigen::Vector3d(1.0, 0.0, 0.0), 1.0}};
  auto p = toy_parameters();
  p.random_probability = 0.0;
  p.max_cycles = 300;
  PocketProblem paper;  // Alg. 1 alone
  paper.sampling = false;
  const auto without = tsrrt::build_ts_rrt(paper, kStart, goal, p);
  EXPECT_FALSE(without.success);
  EXPECT_EQ(without.outcomes.contact_object, without.outcomes.attempts);
  EXPECT_EQ(without.outcomes.sampled, 0);

  PocketProblem toy;
  const auto r = tsrrt::build_ts_rrt(toy, kStart, goal, p);
  ASSERT_TRUE(r.success) << r.reason;
  EXPECT_GT(r.cycles, p.sample_after);  // no sampling in the first cycles
  EXPECT_GT(r.outcomes.sampled, 0);
  EXPECT_GE(r.outcomes.sampled_clasps, 1);
  EXPECT_EQ(r.outcomes.joined, 1);
  EXPECT_EQ(r.outcomes.accepted, 0);  // no attempt from the tree got there
  EXPECT_EQ(r.path.front(), kStart);
  EXPECT_TRUE(toy.reached(toy.project(r.path.back()), goal[0]));
  for (std::size_t i = 0; i + 1 < r.path.size(); ++i)
    EXPECT_TRUE(toy.motion_free(r.path[i], r.path[i + 1])) << "segment " << i;
  // It came in from the open side.
  bool behind = false;
  for (const auto& q : r.path) behind |= q[0] > 1.2;
  EXPECT_TRUE(behind);
  // The same seed gives the same plan.
  PocketProblem again;
  const auto r2 = tsrrt::build_ts_rrt(again, kStart, goal, p);
  ASSERT_EQ(r2.path.size(), r.path.size());
  for (std::size_t i = 0; i < r.path.size(); ++i) EXPECT_EQ(r2.path[i], r.path[i]);
}

TEST(TsRrt, RestartsGrowNewTreesAfterLubysIntervals) {
  const auto once = search_into_the_wall(0);
  EXPECT_EQ(once.outcomes.restarts, 0);
  const auto r = search_into_the_wall(10);  // trees of 10, 10, 20, 10 and 10 cycles
  EXPECT_FALSE(r.success);
  EXPECT_EQ(r.cycles, 60);
  EXPECT_EQ(r.outcomes.restarts, 4);
  EXPECT_NE(r.reason.find("; 4 restarts"), std::string::npos) << r.reason;
  // The last tree alone: rooted at the start, grown in 10 cycles against the single tree's 60.
  EXPECT_LT(r.nodes, once.nodes);
  ASSERT_EQ(static_cast<int>(r.tree_points.size()), r.nodes);
  EXPECT_EQ(r.tree_parents[0], -1);
  EXPECT_EQ(r.tree_points[0].position, Eigen::Vector3d::Zero());  // kStart's
  for (int i = 1; i < r.nodes; ++i) EXPECT_LT(r.tree_parents[i], i);
}

TEST(TsRrt, ARestartFindsWhatTheFirstTreeMissed) {
  // The pocket's goal, no goal sampling and no random extensions after the pre-expansion: a tree
  // whose pre-expansion did not get round the pocket keeps running into its front wall; a new
  // tree's pre-expansion may.
  const std::vector<TaskPoint> goal = {{Eigen::Vector3d(1.0, 0.0, 0.0), 1.0}};
  auto p = toy_parameters();
  p.random_probability = 0.0;
  p.sample_probability = 0.0;
  p.max_cycles = 300;
  p.pre_expansions = 50;
  p.seed = 1;  // a seed whose first tree does not get round
  PocketProblem one;
  const auto without = tsrrt::build_ts_rrt(one, kStart, goal, p);
  EXPECT_FALSE(without.success);
  EXPECT_EQ(without.outcomes.contact_object, without.outcomes.attempts);
  p.restart_cycles = 10;
  PocketProblem toy;
  const auto r = tsrrt::build_ts_rrt(toy, kStart, goal, p);
  ASSERT_TRUE(r.success) << r.reason;
  EXPECT_GE(r.outcomes.restarts, 1);
  EXPECT_EQ(r.path.front(), kStart);
  bool behind = false;
  for (const auto& q : r.path) behind |= q[0] > 1.2;
  EXPECT_TRUE(behind);
  for (std::size_t i = 0; i + 1 < r.path.size(); ++i)
    EXPECT_TRUE(toy.motion_free(r.path[i], r.path[i + 1])) << "segment " << i;
}

TEST(TsRrt, ARejectedGoalNodeLeadsToAnotherApproach) {
  ToyProblem toy;
  toy.wall = false;
  toy.reject_first = 1;
  toy.detours = {{Eigen::Vector3d(1.0, 0.4, 0.0), 0.0}, {Eigen::Vector3d(1.0, -0.4, 0.0), 0.0}};
  const auto r = tsrrt::build_ts_rrt(toy, kStart, kGoalBehindObject, detour_parameters());
  ASSERT_TRUE(r.success) << r.reason;
  const tsrrt::ConnectOutcomes& o = r.outcomes;
  EXPECT_EQ(o.rejected, 1);
  EXPECT_EQ(o.contact_object, 0);
  EXPECT_EQ(o.detours, 1);  // the rejection's, the only failed ending
  EXPECT_EQ(o.accepted, 1);
  EXPECT_EQ(o.attempts, 2);  // the direct one, then the one after the detour, which is accepted
  // The accepted path comes from the detour's side.
  bool aside = false;
  for (const auto& q : r.path) aside |= std::abs(q[1]) >= 0.3;
  EXPECT_TRUE(aside);
}

TEST(TsRrt, DetoursCycleThroughTheApproaches) {
  // The first approach lies behind the object, straight through it: its detour ends in contact
  // again, and the next attempt's detour takes the next approach.
  ToyProblem toy;
  toy.wall = false;
  toy.object = true;
  toy.detours = {{Eigen::Vector3d(1.3, 0.0, 0.0), 0.0}, {Eigen::Vector3d(0.95, 0.5, 0.0), 0.0}};
  const auto r = tsrrt::build_ts_rrt(toy, kStart, kGoalBehindObject, detour_parameters());
  ASSERT_TRUE(r.success) << r.reason;
  EXPECT_GE(r.outcomes.detours, 2);
  EXPECT_GE(r.outcomes.contact_object, 2);
  EXPECT_EQ(r.outcomes.endings(), r.outcomes.attempts);
}

TEST(TsRrt, AHeldJointEndsAnAttemptAtTheJointLimits) {
  ToyProblem toy;
  toy.wall = false;
  toy.y_max = 0.1;
  const std::vector<TaskPoint> high = {{Eigen::Vector3d(1.0, 0.3, 0.0), 1.0}};
  const auto r = tsrrt::build_ts_rrt(toy, kStart, high, detour_parameters());
  EXPECT_FALSE(r.success);
  EXPECT_EQ(r.outcomes.attempts, 1);
  EXPECT_EQ(r.outcomes.joint_limits, 1);
  EXPECT_EQ(r.outcomes.stall, 0);
  EXPECT_NE(r.reason.find("ended at the joint limits (1)"), std::string::npos) << r.reason;
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

// Shortcuts are found by the search's check, and each kept one must pass the finer
// shortcut_free(): one refused gives back the steps it cut, the others stay.
TEST(PathPruning, AShortcutRefusedByTheFinerCheckGivesBackItsSteps) {
  struct FinerToy : ToyProblem {
    double refuse_beyond_x = 0.0;  // no shortcut may end past this x
    int refused = 0, calls = 0;
    bool shortcut_free(const Eigen::VectorXd& q0, const Eigen::VectorXd& q1) override {
      ++calls;
      if (std::max(q0[0], q1[0]) > refuse_beyond_x) return ++refused, false;
      return motion_free(q0, q1);
    }
  };
  FinerToy toy;
  toy.refuse_beyond_x = std::numeric_limits<double>::infinity();
  const auto r = tsrrt::build_ts_rrt(toy, kStart, kGoals, toy_parameters());
  ASSERT_TRUE(r.success);
  const auto pruned = tsrrt::prune_path(toy, r.path, 200, 3);
  ASSERT_LT(pruned.size(), r.path.size());
  EXPECT_EQ(toy.refused, 0);
  EXPECT_LT(toy.calls, static_cast<int>(pruned.size()));  // the kept shortcuts only
  // Refusing the shortcuts near the goal keeps the path's end as the search made it.
  toy.refuse_beyond_x = r.path[r.path.size() / 2][0];
  const auto finer = tsrrt::prune_path(toy, r.path, 200, 3);
  EXPECT_GT(toy.refused, 0);
  EXPECT_GT(finer.size(), pruned.size());
  EXPECT_EQ(finer.front(), r.path.front());
  std::size_t k = 0;  // every waypoint is the search's, in its order
  for (const auto& q : finer) {
    while (k < r.path.size() && r.path[k] != q) ++k;
    ASSERT_LT(k, r.path.size());
  }
  for (std::size_t i = 0; i + 1 < finer.size(); ++i) {
    const bool shortcut = std::find(r.path.begin(), r.path.end(), finer[i + 1]) -
                              std::find(r.path.begin(), r.path.end(), finer[i]) >
                          1;
    if (shortcut) {
      EXPECT_LE(std::max(finer[i][0], finer[i + 1][0]), toy.refuse_beyond_x);
    }
  }
  // Refusing every shortcut gives the search's path back.
  toy.refuse_beyond_x = -std::numeric_limits<double>::infinity();
  EXPECT_EQ(tsrrt::prune_path(toy, r.path, 200, 3), r.path);
}

}  // namespace
}  // namespace claspplan::test
