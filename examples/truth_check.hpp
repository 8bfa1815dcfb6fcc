// A planned path against the scene its depth was rendered from (the scenario's mesh, boxes and
// clutter, not what the cameras saw of them): does the robot touch anything real on its way? The
// benchmark's check that "verified" means executable, at a finer motion resolution than planning.
#pragma once

#include <string>

#include "examples/scenario.hpp"

namespace claspplan::cli {

struct TruthContact {
  bool checked = false;  ///< the scenario renders its depth and the result has a path
  bool touches = false;
  int segment = -1;  ///< the first path segment that touches (0: from the start)
  int segments = 0;  ///< segments checked
  std::string what;  ///< "link_5 and object"
};

/// How finely the truth check samples: no robot point travels more than kTruthTravel between two
/// checked configurations, no joint more than kTruthResolution.
constexpr double kTruthTravel = 0.001;
constexpr double kTruthResolution = 0.002;

/// Checks result.json's waypoints against rendered_scene(scenario). The fingers' closing (the
/// last segment when the arm no longer moves) is left out: closed fingers rest on the seen
/// surface, which lies within the depth noise of the true one. Nothing is checked (checked false)
/// without a rendered scene or without waypoints. Throws InputError for an unreadable result.
TruthContact check_path_against_truth(const Scenario& scenario, const std::string& result_json);

}  // namespace claspplan::cli
