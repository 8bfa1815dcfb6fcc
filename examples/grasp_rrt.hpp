// Baseline D of `claspplan bench`: a Grasp-RRT-style planner (after Vahrenkamp et al., "Integrated
// grasp and motion planning", ICRA 2010), to measure how often a grasp planner's grasps happen to
// be clasps. A configuration-space RRT grows from the start with the hand open; some iterations
// instead pick a point of the seen surface and drive the hand from the nearest tree node along
// the point's normal until it touches the object, then close the fingers and score the grasp.
// The first grasp that scores ends the search; the secure-clasp check then says whether it is
// also a clasp (the paper: under 5 % of such grasps are).
#pragma once

#include "tsrrt/clasp_setup.hpp"

namespace claspplan::cli {

struct GraspRrtOptions {
  double approach_probability = 0.3;  ///< share of iterations that try an approach
  double step = 0.1;                  ///< rad: the RRT's extension step (arm joints)
  double standoff = 0.1;              ///< m: approaches start from the node nearest this far out
  int approach_steps = 80;            ///< Jacobian steps of one approach at most
  double approach_step = 0.01;        ///< m of hand travel per approach step
  /// The grasp score: fingers (the thumb among them) touching the object after closing, at
  /// least this many (a stand-in for the force-closure test of the original).
  int min_contact_fingers = 2;
};

/// The Grasp-RRT search (a tsrrt::ClaspSearch): `success` when a grasp scored, `verified` when it
/// is a secure clasp. Within the planner's time limit, or with no time limit within max_cycles
/// iterations (then the result depends on the seed only).
void grasp_rrt(const tsrrt::ClaspScene& scene, tsrrt::ClaspResult& result,
               const GraspRrtOptions& options = {});

}  // namespace claspplan::cli
