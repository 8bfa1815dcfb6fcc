// Baseline E of `claspplan bench`: a two-phase clasp planner to compare TS-RRT with. Phase 1
// finds clasp goal configurations with the clasp controller alone (servo::run_controller) from
// sampled collision-free arm configurations, each closed and checked as TS-RRT's candidates are;
// phase 2 plans from the start to one of the secure ones with OMPL's RRTConnect in joint space.
// The usual split of a clasp into "where to hold" and "how to get there", each solved by a
// standard tool; TS-RRT does both in one search.
#pragma once

#include "tsrrt/clasp_setup.hpp"

namespace claspplan::cli {

struct TwoPhaseOptions {
  int max_goals = 3;           ///< secure clasp goals to collect before phase 2 starts
  double goal_share = 0.6;     ///< of the time limit, at most this much for phase 1 ...
  int controller_steps = 400;  ///< ... and at most this many controller steps per sampled start
};

/// The two-phase search (a tsrrt::ClaspSearch). Within the planner's time limit, or with no time
/// limit within max_cycles sampled starts and max_cycles RRTConnect iterations (then the result
/// depends on the seed only).
void ompl_two_phase(const tsrrt::ClaspScene& scene, tsrrt::ClaspResult& result,
                    const TwoPhaseOptions& options = {});

}  // namespace claspplan::cli
