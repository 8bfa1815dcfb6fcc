// What `claspplan bench` keeps of each run, and the report it writes from them: cases.json (the
// records, read back by --merge), cases.csv, report.md and PNG plots.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

namespace claspplan::cli {

/// One run's outcome (from its --json summary, timing.json and result.json).
struct BenchRecord {
  std::string name;
  std::string scenario;
  std::uint64_t seed = 1;
  /// > 0: a run of the tolerance sweep (BenchCase::tolerance), reported apart from the others.
  double tolerance = 0.0;
  std::string method;  ///< empty: TS-RRT; else the baseline (BenchCase::method)
  int exit_code = 0;   ///< as `claspplan run` would exit
  bool success = false;
  bool verified = false;
  bool controller_only = false;  ///< the clasp controller alone: success = its goal reached
  int cycles = 0;                ///< TS-RRT cycles after the pre-expansion
  int steps = 0;                 ///< control steps of the controller alone
  int nodes = 0;
  double seconds = 0;  ///< planning with the clasp checks (perception excluded)
  double perception = 0, planning = 0, closing = 0, verification = 0, total = 0;  ///< seconds
  /// Paper Fig. 6: over the finger curves of the final pose, |Lk| of the open curves and VLk
  /// (NaN when the run has no final pose).
  double min_open_linking, max_open_linking, min_virtual_linking, max_virtual_linking;
  double final_linking;  ///< mean VLk (eq. 4) of the final pose, the fingers closed; NaN if none
  std::string reason;
  /// A verified path checked against the scene its depth was rendered from (truth_check.hpp):
  /// truth_contact names the first contact ("" none).
  bool truth_checked = false;
  std::string truth_contact;
  BenchRecord();
  /// What the run was for: a verified clasp, or with the controller alone its goal.
  bool achieved() const { return controller_only ? success : verified; }
};

nlohmann::json record_json(const BenchRecord& r);
/// Throws std::invalid_argument when a field is missing or of the wrong type.
BenchRecord record_from_json(const nlohmann::json& j);

/// {cases, success, verified, median_seconds, max_seconds} over TS-RRT's records outside the
/// tolerance sweep (seconds of the runs that achieved what they were for: see
/// BenchRecord::achieved()); and for each of bench_baselines() an object {cases, success,
/// verified, median_seconds} under its name (0 cases when it did not run).
nlohmann::json bench_summary(const std::vector<BenchRecord>& records);

/// Writes cases.json, cases.csv, report.md, time_per_case.png, linking_scatter.png and, with sweep
/// runs, tolerance_sweep.png, with baseline runs <method>_time.png, into out_dir (created if
/// needed). Throws std::runtime_error when a file cannot be written.
void write_bench_report(const std::vector<BenchRecord>& records, const std::string& out_dir,
                        const std::string& title);

/// The records of a cases.json written by write_bench_report(). Throws std::invalid_argument for
/// a missing or malformed file.
std::vector<BenchRecord> read_bench_cases(const std::string& path);

}  // namespace claspplan::cli
