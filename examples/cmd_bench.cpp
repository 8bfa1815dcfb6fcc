// `claspplan bench --suite quick|real|paper | SCENARIO... [--seeds N] [--jobs N] [--shard K/N]
// [--out DIR] [--json]` and `claspplan bench --merge DIR...`: runs a suite's scenarios over seeds
// through the same pipeline as `claspplan run` and writes a report (examples/bench_report.hpp).
#include <algorithm>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <mutex>
#include <tuple>

#include <unistd.h>

#include "core/input_error.hpp"
#include "core/parallel.hpp"
#include "examples/bench_report.hpp"
#include "examples/bench_suite.hpp"
#include "examples/command.hpp"
#include "examples/grasp_rrt.hpp"
#include "examples/ompl_two_phase.hpp"
#include "examples/run_scenario.hpp"
#include "examples/truth_check.hpp"
#include "tsrrt/elapsed.hpp"

namespace claspplan::cli {
namespace {

namespace fs = std::filesystem;

struct BenchOptions {
  std::string suite;
  std::vector<std::string> files;  ///< scenario files: a suite of their own
  std::vector<std::string> merge;
  std::string scenarios = CLASPPLAN_SCENARIOS_DIR;
  int seeds = 1;
  int jobs = 1;
  std::string shard;
  std::string out = "claspplan-bench";
  double time_limit = 0;
  int max_cycles = 0;
  bool controller_only = false;
  int next_views = 0;  ///< run's --next-views, for the scenarios that render their depth
  bool json = false;
  std::string robot;  ///< replaces every scenario's robot
};

nlohmann::json read_json_file(const fs::path& path) {
  std::ifstream f(path);
  if (!f) return nlohmann::json::object();
  try {
    return nlohmann::json::parse(f);
  } catch (const nlohmann::json::exception&) {
    return nlohmann::json::object();
  }
}

double value_or(const nlohmann::json& j, const char* key, double fallback) {
  return j.contains(key) && j[key].is_number() ? j[key].get<double>() : fallback;
}

// One case through `claspplan run`'s pipeline, without pictures; its record from the run's
// summary and files. Malformed input is exit 2, anything else unexpected exit 3.
BenchRecord run_case(const BenchCase& c, const BenchOptions& o, const fs::path& dir) {
  BenchRecord r;
  r.name = c.name;
  r.scenario = c.scenario;
  r.seed = c.seed;
  r.tolerance = c.tolerance;
  r.method = c.method;
  RunOptions run;
  run.out_dir = dir.string();
  run.seed = c.seed;
  run.pictures = false;
  run.quiet = true;
  if (o.time_limit > 0) run.time_limit = o.time_limit;
  if (o.max_cycles > 0) run.max_cycles = o.max_cycles;
  run.controller_only = o.controller_only;
  if (c.method == "ompl_two_phase") {
    run.search = [](const tsrrt::ClaspScene& scene, tsrrt::ClaspResult& result) {
      ompl_two_phase(scene, result);
    };
  } else if (c.method == "grasp_rrt") {
    run.search = [](const tsrrt::ClaspScene& scene, tsrrt::ClaspResult& result) {
      grasp_rrt(scene, result);
    };
  }
  nlohmann::json summary;
  std::optional<Scenario> scenario;
  try {
    scenario = load_scenario(c.scenario);
    if (!o.robot.empty()) use_robot(*scenario, o.robot);
    if (c.tolerance > 0) {  // the sweep: the first goal node at this tolerance, verified after
      scenario->planning.closable_linking = c.tolerance;
      scenario->planning.verify_in_search = false;
    }
    if (!scenario->object.cameras.empty() && c.method.empty()) run.next_views = o.next_views;
    const RunOutcome outcome = run_scenario(*scenario, run);
    r.exit_code = outcome.exit_code;
    summary = outcome.summary;
  } catch (const InputError& e) {
    r.exit_code = kBadInput;
    r.reason = e.what();
    return r;
  } catch (const std::exception& e) {
    r.exit_code = kInternalError;
    r.reason = std::string("internal error: ") + e.what();
    return r;
  }
  r.success = summary.value("success", false);
  r.verified = summary.value("verified", false);
  r.controller_only = o.controller_only;
  r.cycles = summary.value("cycles", 0);
  r.steps = summary.value("steps", 0);
  r.nodes = summary.value("nodes", 0);
  r.seconds = value_or(summary, "seconds", 0.0);
  r.reason = summary.value("reason", std::string());
  const nlohmann::json timing = read_json_file(dir / "timing.json");
  r.perception = value_or(timing, "perception", 0.0);
  r.planning = value_or(timing, "planning", 0.0);
  r.closing = value_or(timing, "closing", 0.0);
  r.verification = value_or(timing, "verification", 0.0);
  r.total = value_or(timing, "total", 0.0);
  const nlohmann::json result = read_json_file(dir / "result.json");
  r.final_linking = value_or(result, "virtual_linking", r.final_linking);
  if (result.contains("verification") && result["verification"].is_object()) {
    const auto& v = result["verification"];
    r.min_open_linking = value_or(v, "min_open_linking", r.min_open_linking);
    r.max_open_linking = value_or(v, "max_open_linking", r.max_open_linking);
    r.min_virtual_linking = value_or(v, "min_virtual_linking", r.min_virtual_linking);
    r.max_virtual_linking = value_or(v, "max_virtual_linking", r.max_virtual_linking);
  }
  if (!r.verified) return r;
  try {
    const TruthContact truth = check_path_against_truth(*scenario, (dir / "result.json").string());
    r.truth_checked = truth.checked;
    if (truth.touches)
      r.truth_contact = truth.what + " (segment " + std::to_string(truth.segment + 1) + " of " +
                        std::to_string(truth.segments) + ")";
  } catch (const std::exception& e) {
    r.exit_code = kInternalError;
    r.reason = std::string("internal error: the path against the rendered scene: ") + e.what();
  }
  return r;
}

// A progress bar on stderr (redrawn in place on a terminal, one line per case otherwise).
class Progress {
 public:
  explicit Progress(int total) : total_(total), tty_(isatty(fileno(stderr)) != 0) {}
  void done(const BenchRecord& r) {
    std::lock_guard<std::mutex> lock(mutex_);
    ++finished_;
    verified_ += r.verified;
    const double s = tsrrt::since(start_);
    const int width = 30, filled = total_ > 0 ? width * finished_ / total_ : width;
    std::string bar(filled, '=');
    bar.resize(width, ' ');
    if (tty_) {
      std::fprintf(stderr, "\rbench [%s] %d/%d runs, %d verified, %.0f s", bar.c_str(), finished_,
                   total_, verified_, s);
      if (finished_ == total_) std::fprintf(stderr, "\n");
    } else {
      std::fprintf(stderr, "bench [%s] %d/%d runs, %d verified, %.0f s: %s seed %llu exit %d\n",
                   bar.c_str(), finished_, total_, verified_, s, r.name.c_str(),
                   static_cast<unsigned long long>(r.seed), r.exit_code);
    }
    std::fflush(stderr);
  }

 private:
  std::mutex mutex_;
  int total_, finished_ = 0, verified_ = 0;
  bool tty_;
  tsrrt::Clock::time_point start_ = tsrrt::Clock::now();
};

std::vector<BenchRecord> run_cases(const std::vector<BenchCase>& cases, const BenchOptions& o) {
  std::vector<BenchRecord> records(cases.size());
  Progress progress(static_cast<int>(cases.size()));
  parallel_for(cases.size(), o.jobs, [&](std::size_t i, int) {
    std::string stem = cases[i].name;
    for (char& ch : stem) ch = ch == '/' ? '_' : ch;
    if (!cases[i].method.empty()) stem += "_" + cases[i].method;
    if (cases[i].tolerance > 0) {
      char tolerance[32];
      std::snprintf(tolerance, sizeof tolerance, "_tolerance%.2f", cases[i].tolerance);
      stem += tolerance;
    }
    const fs::path dir =
        fs::path(o.out) / "runs" / (stem + "_seed" + std::to_string(cases[i].seed));
    records[i] = run_case(cases[i], o, dir);
    progress.done(records[i]);
  });
  return records;
}

int run_bench(const BenchOptions& o) {
  std::vector<BenchRecord> records;
  std::string title;
  if (!o.merge.empty()) {
    for (const auto& dir : o.merge) {
      const auto part = read_bench_cases((fs::path(dir) / "cases.json").string());
      records.insert(records.end(), part.begin(), part.end());
    }
    // The suites' order: TS-RRT's runs by name and seed, the sweep's by tolerance and name, then
    // the baselines' by method and name.
    std::stable_sort(records.begin(), records.end(), [](const auto& a, const auto& b) {
      return std::tie(a.method, a.tolerance, a.name, a.seed) <
             std::tie(b.method, b.tolerance, b.name, b.seed);
    });
    title = "claspplan bench: " + std::to_string(o.merge.size()) + " outputs merged";
  } else {
    std::vector<BenchCase> cases =
        o.files.empty() ? suite_cases(o.suite, o.scenarios, o.seeds) : file_cases(o.files, o.seeds);
    if (o.controller_only) {  // the baselines are searches: nothing to run them against
      cases.erase(std::remove_if(cases.begin(), cases.end(),
                                 [](const BenchCase& c) { return !c.method.empty(); }),
                  cases.end());
    }
    if (!o.shard.empty()) cases = shard_cases(cases, o.shard);
    if (!o.json) {
      progress("bench: " + (o.files.empty() ? "suite " + o.suite : "scenario files") + ", " +
               std::to_string(cases.size()) + " runs, " + std::to_string(o.jobs) + " at a time");
    }
    records = run_cases(cases, o);
    title = "claspplan bench " + (o.files.empty() ? "--suite " + o.suite : "(scenario files)") +
            (o.controller_only ? " --controller-only" : "") +
            (o.next_views > 0 ? " --next-views " + std::to_string(o.next_views) : "") +
            " --seeds " + std::to_string(o.seeds) + (o.shard.empty() ? "" : " --shard " + o.shard);
  }
  write_bench_report(records, o.out, title);
  nlohmann::json summary = bench_summary(records);
  summary["out"] = o.out;
  if (o.json) {
    print_json(summary);
  } else {
    std::printf("%d of %d runs planned a verified clasp; report: %s/report.md\n",
                summary["verified"].get<int>(), summary["cases"].get<int>(), o.out.c_str());
  }
  return kOk;
}

}  // namespace

void add_bench_command(CLI::App& app, Action& action) {
  auto o = std::make_shared<BenchOptions>();
  CLI::App* cmd = app.add_subcommand("bench", command_description("bench"));
  auto* suite = cmd->add_option("--suite", o->suite,
                                "quick (purse_1 and jug, all hands), real (real/*), paper "
                                "(<object>_<pose>_<hand> and chair_obstructed_<hand>)");
  auto* merge = cmd->add_option("--merge", o->merge, "combine these bench output folders");
  auto* files = cmd->add_option("SCENARIO", o->files, "scenario files: a suite of their own");
  suite->excludes(merge)->excludes(files);
  merge->excludes(suite)->excludes(files);
  cmd->add_option("--scenarios", o->scenarios, "the folder of the suites' scenario files")
      ->capture_default_str();
  cmd->add_option("--seeds", o->seeds, "seeds 1..N per scenario")
      ->check(CLI::Range(1, 1000))
      ->capture_default_str();
  cmd->add_option("--jobs", o->jobs, "runs at a time (each check also uses 2 threads)")
      ->check(CLI::Range(1, 256))
      ->capture_default_str();
  cmd->add_option("--shard", o->shard, "K/N: run every N-th case from the K-th (cluster arrays)");
  cmd->add_option("--out", o->out, "output folder")->capture_default_str();
  cmd->add_option("--time-limit", o->time_limit, "planning limit per run in seconds")
      ->check(CLI::PositiveNumber);
  cmd->add_option("--max-cycles", o->max_cycles,
                  "bound each run by TS-RRT cycles instead of time (machine-independent)")
      ->check(CLI::Range(1, 10000000));
  cmd->add_option(
      "--robot", o->robot,
      "plan with this robot instead of the scenario's (built-in name or hand-description "
      "file); the scenario's start must fit its arm");
  cmd->add_flag("--controller-only", o->controller_only,
                "no planning: the clasp controller alone (success = its goal reached)");
  cmd->add_option("--next-views", o->next_views,
                  "as run's, for the scenarios that render their depth (object: cameras); the "
                  "others and the baselines run as they are")
      ->check(CLI::Range(0, 10));
  cmd->add_flag("--json", o->json, "print one JSON summary object");
  cmd->callback([o, &action] {
    if (o->suite.empty() && o->merge.empty() && o->files.empty())
      throw CLI::ValidationError("bench", "give --suite NAME, scenario files or --merge DIR...");
    if (o->suite == "quick" && o->max_cycles == 0 && o->time_limit == 0) o->max_cycles = 300;
    action = [o] { return run_bench(*o); };
  });
}

}  // namespace claspplan::cli
