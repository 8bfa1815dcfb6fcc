#include "examples/ompl_two_phase.hpp"

#include <algorithm>
#include <chrono>
#include <memory>
#include <random>

#include <ompl/base/PlannerData.h>
#include <ompl/base/ProblemDefinition.h>
#include <ompl/base/SpaceInformation.h>
#include <ompl/base/goals/GoalStates.h>
#include <ompl/base/spaces/RealVectorStateSpace.h>
#include <ompl/geometric/PathGeometric.h>
#include <ompl/geometric/PathSimplifier.h>
#include <ompl/geometric/planners/rrt/RRTConnect.h>
#include <ompl/util/Console.h>

#include "core/random_draws.hpp"
#include "tsrrt/elapsed.hpp"

namespace claspplan::cli {
namespace {

namespace ob = ompl::base;
namespace og = ompl::geometric;
using tsrrt::Clock;
using tsrrt::since;

// OMPL's samplers draw from per-instance generators seeded here, not from its process-wide seed
// (which several benchmark runs in one process would share).
class SeededSampler : public ob::RealVectorStateSampler {
 public:
  SeededSampler(const ob::StateSpace* space, std::uint_fast32_t seed)
      : ob::RealVectorStateSampler(space) {
    rng_.setLocalSeed(seed);
  }
};

class SeededRRTConnect : public og::RRTConnect {
 public:
  SeededRRTConnect(const ob::SpaceInformationPtr& si, std::uint_fast32_t seed) : RRTConnect(si) {
    rng_.setLocalSeed(seed);
  }
};

struct Goal {
  Eigen::VectorXd q_open;
  std::vector<Eigen::VectorXd> approach;  // to contact, before closing (may be empty)
  Eigen::VectorXd q_closed;
  int target = -1;
  tsrrt::SecureClaspReport check;
};

Eigen::VectorXd to_q(const ob::State* s, int dof) {
  const auto* v = s->as<ob::RealVectorStateSpace::StateType>();
  return Eigen::Map<const Eigen::VectorXd>(v->values, dof);
}

}  // namespace

void ompl_two_phase(const tsrrt::ClaspScene& scene, tsrrt::ClaspResult& r,
                    const TwoPhaseOptions& o) {
  const robots::RobotModel& model = scene.robot;
  const tsrrt::PlannerParameters& pp = scene.planning.planner;
  const int dof = model.dof();
  const auto start = Clock::now();
  const double limit = pp.time_limit;  // 0: bounded by max_cycles instead
  const auto out_of_time = [&](double share) { return limit > 0 && since(start) >= share * limit; };
  std::mt19937_64 rng(pp.seed);
  const Eigen::VectorXd lower = model.lower(), upper = model.upper();

  // Phase 1: the controller alone from sampled arm configurations (the hand as at the start).
  servo::ControllerRunOptions run;
  const double reach_linking = tsrrt::closable_tolerance(scene.planning, scene.goal_linking);
  run.max_steps = o.controller_steps;
  run.collision_resolution = scene.planning.collision_resolution;
  std::vector<Goal> goals;
  int starts = 0, reached = 0, candidates = 0;
  tsrrt::SecureClaspReport last_check;
  while (static_cast<int>(goals.size()) < o.max_goals && !out_of_time(o.goal_share) &&
         (limit > 0 || starts < pp.max_cycles)) {
    Eigen::VectorXd q = r.start;
    for (int j = 0; j < model.arm_dof; ++j)
      q[j] = lower[j] + uniform01(rng()) * (upper[j] - lower[j]);
    ++starts;
    if (scene.world.in_collision(q)) continue;
    const servo::ControllerRun reach =
        servo::run_controller(scene.controller, scene.world, q, reach_linking, run);
    r.statistics.control_steps += static_cast<int>(reach.waypoints.size()) - 1;
    if (!reach.success) continue;
    ++reached;
    ++candidates;
    const tsrrt::ClaspCandidate c =
        tsrrt::close_and_check(scene, reach.waypoints.back(), r.timings);
    if (c.refused) continue;
    last_check = c.check;
    if (c.check.secure)
      goals.push_back({reach.waypoints.back(), c.approach, c.q_closed, reach.target, c.check});
  }
  r.statistics.clasp_candidates = candidates;
  r.statistics.cycles = starts;
  r.verification = last_check;
  if (goals.empty()) {
    r.reason = "two-phase baseline: no secure clasp goal from " + std::to_string(starts) +
               " sampled starts (" + std::to_string(reached) + " reached the linking goal, " +
               std::to_string(candidates) + " closed)";
    return;
  }

  // Phase 2: RRTConnect from the start to any of the goals. OMPL's log level is process-wide: set
  // once, also when several benchmark runs start at the same time.
  static const bool quiet = (ompl::msg::setLogLevel(ompl::msg::LOG_NONE), true);
  (void)quiet;
  auto space = std::make_shared<ob::RealVectorStateSpace>(dof);
  ob::RealVectorBounds bounds(dof);
  for (int j = 0; j < dof; ++j) {
    bounds.setLow(j, lower[j]);
    bounds.setHigh(j, std::max(upper[j], lower[j] + 1e-9));  // OMPL needs low < high
  }
  space->setBounds(bounds);
  const auto seed = static_cast<std::uint_fast32_t>(pp.seed);
  space->setStateSamplerAllocator(
      [seed](const ob::StateSpace* s) { return std::make_shared<SeededSampler>(s, seed); });
  auto si = std::make_shared<ob::SpaceInformation>(space);
  si->setStateValidityChecker(
      [&](const ob::State* s) { return !scene.world.in_collision(to_q(s, dof)); });
  // The same spacing of checked configurations along motions as TS-RRT's.
  si->setStateValidityCheckingResolution(scene.planning.collision_resolution /
                                         space->getMaximumExtent());
  si->setup();
  auto pdef = std::make_shared<ob::ProblemDefinition>(si);
  ob::ScopedState<ob::RealVectorStateSpace> s0(space);
  for (int j = 0; j < dof; ++j) s0[j] = r.start[j];
  pdef->addStartState(s0);
  auto targets = std::make_shared<ob::GoalStates>(si);
  for (const auto& g : goals) {
    ob::ScopedState<ob::RealVectorStateSpace> s(space);
    for (int j = 0; j < dof; ++j) s[j] = g.q_open[j];
    targets->addState(s);
  }
  pdef->setGoal(targets);
  SeededRRTConnect planner(si, seed);
  planner.setProblemDefinition(pdef);
  planner.setup();
  int iterations = 0;
  const ob::PlannerTerminationCondition stop(
      [&] { return limit > 0 ? out_of_time(1.0) : ++iterations > pp.max_cycles; });
  const ob::PlannerStatus status = planner.solve(stop);
  ob::PlannerData data(si);
  planner.getPlannerData(data);
  r.statistics.nodes = static_cast<int>(data.numVertices());
  if (status != ob::PlannerStatus::EXACT_SOLUTION) {
    r.reason = "two-phase baseline: " + std::to_string(goals.size()) +
               " secure clasp goals, but RRTConnect found no path to them (" +
               std::string(status.asString()) + ")";
    return;
  }
  auto& path = *pdef->getSolutionPath()->as<og::PathGeometric>();
  og::PathSimplifier(si).reduceVertices(path);
  for (const ob::State* s : path.getStates()) r.motion.waypoints.push_back(to_q(s, dof));
  // The goal reached: the one the path ends at.
  std::size_t best = 0;
  for (std::size_t i = 1; i < goals.size(); ++i) {
    if ((goals[i].q_open - r.motion.waypoints.back()).norm() <
        (goals[best].q_open - r.motion.waypoints.back()).norm())
      best = i;
  }
  for (const auto& q : goals[best].approach) r.motion.waypoints.push_back(q);
  r.motion.waypoints.push_back(goals[best].q_closed);
  r.verification = goals[best].check;
  r.motion.target = goals[best].target;
  r.verified = true;
  r.status = tsrrt::ClaspStatus::kSuccess;
  r.reason = "verified clasp";
}

}  // namespace claspplan::cli
