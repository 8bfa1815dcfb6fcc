// Which runs `claspplan bench` makes: a suite's scenario files times seeds, and the share of them
// one shard of a cluster job runs.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

namespace claspplan::cli {

/// One run of the benchmark: a scenario file with a seed.
struct BenchCase {
  std::string name;      ///< the scenario file's stem, e.g. purse_1_sdh or real/pitcher_sdh
  std::string scenario;  ///< path of the scenario file
  std::uint64_t seed = 1;
  /// > 0: a run of the virtual-linking tolerance sweep (paper Sec. V-C, Fig. 8): the tree's goal
  /// tolerance set to this, the first goal node taken and verified afterwards (not in the search).
  double tolerance = 0.0;
  /// The search: empty for TS-RRT, or a baseline of bench_baselines().
  std::string method;
};

/// The baselines `claspplan bench` runs beside TS-RRT on the same scenarios: grasp_rrt
/// (examples/grasp_rrt.hpp) and ompl_two_phase (examples/ompl_two_phase.hpp).
std::vector<std::string> bench_baselines();

/// The tolerances of the paper's sweep (Fig. 8).
std::vector<double> paper_tolerances();

/// The suites, each a set of scenario files under `scenarios_dir`:
///  - quick: purse_1_<hand> and jug_<hand> (a few minutes of work, bounded by cycles);
///  - real: real/*.yaml, the public meshes of real objects;
///  - paper: <object>_<pose>_<hand>.yaml and chair_obstructed_<hand>.yaml (paper Sec. V), then
///    the tolerance sweep: each <object>_1_<hand> at seed 1 with each of paper_tolerances().
/// Then each baseline on every scenario of the suite at seed 1.
std::vector<std::string> bench_suites();

/// The cases of `suite` with seeds 1..seeds, sorted by name then seed. Throws
/// std::invalid_argument for an unknown suite or a suite without scenario files.
std::vector<BenchCase> suite_cases(const std::string& suite, const std::string& scenarios_dir,
                                   int seeds);

/// The cases of the given scenario files with seeds 1..seeds, in the files' order. Throws
/// std::invalid_argument for a file that does not exist.
std::vector<BenchCase> file_cases(const std::vector<std::string>& files, int seeds);

/// Shard "K/N" (1 <= K <= N): every N-th case starting with the K-th. Throws
/// std::invalid_argument for a malformed shard.
std::vector<BenchCase> shard_cases(const std::vector<BenchCase>& cases, const std::string& shard);

}  // namespace claspplan::cli
