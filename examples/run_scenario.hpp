// The main job, shared by `claspplan run` and `claspplan demo`: a scenario becomes a
// tsrrt::ClaspRequest (depth → loops → plan, or the controller alone → close the fingers → prune
// → verify: tsrrt/clasp_setup.hpp), and its ClaspResult becomes the result files and pictures.
#pragma once

#include <cstdint>
#include <functional>
#include <optional>
#include <string>

#include <nlohmann/json.hpp>

#include "core/input_error.hpp"
#include "examples/scenario.hpp"
#include "perception/next_view.hpp"

namespace claspplan::cli {

struct RunOptions {
  std::string out_dir = "claspplan-out";
  std::optional<std::uint64_t> seed;  ///< overrides the scenario's seed
  std::optional<double> time_limit;   ///< seconds, overrides the scenario's planner time limit
  /// Bound the search by cycles instead (no time limit unless time_limit is given too): results
  /// then do not depend on the machine's speed or load.
  std::optional<int> max_cycles;
  bool controller_only = false;
  tsrrt::ClaspSearch search;  ///< replaces TS-RRT when set (the benchmark's baselines)
  /// A run that fails naming a camera (`next_best_view`) is run again with that camera added to
  /// the scenario's rendered ones, up to this many added cameras (0: none). Scenarios whose depth
  /// is rendered (object: cameras) only: run_scenario throws InputError for others.
  int next_views = 0;
  bool pictures = true;
  bool quiet = false;          ///< no progress lines on stderr
  std::function<bool()> stop;  ///< ends the search early (tsrrt::ClaspRequest::stop)
};

struct RunOutcome {
  int exit_code = 0;       ///< 0 verified clasp (or controller goal reached), 1 no answer
  nlohmann::json summary;  ///< what `run --json` prints
  /// The camera a failed run names (summary's `next_best_view`), if any.
  std::optional<perception::ViewSuggestion> next_view;
};

/// The planner's request for a scenario, its robot and its read inputs: the run options replace
/// its seed and search bound.
tsrrt::ClaspRequest clasp_request(const Scenario& scenario, const RunOptions& options,
                                  std::shared_ptr<const robots::RobotModel> robot,
                                  perception::PerceptionInputs inputs);

/// Runs a scenario and writes result.json, timing.json and the pictures into options.out_dir
/// (with options.next_views, those of the last run, whose result.json lists the `added_views`).
/// Throws InputError for malformed input (a start pose in collision included).
RunOutcome run_scenario(const Scenario& scenario, const RunOptions& options);

/// The secure-clasp check's outcome as JSON (result.json's `verification`, `verify --json`).
nlohmann::json verification_json(const tsrrt::SecureClaspReport& report);

/// The human summary of a run's outcome (its --json object), for `run` and `demo`.
void print_run_summary(const nlohmann::json& summary, bool controller_only);

}  // namespace claspplan::cli
