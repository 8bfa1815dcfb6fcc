// `claspplan run SCENARIO.yaml [--out DIR] [--seed N] [--time-limit S] [--max-cycles N]
// [--robot R] [--controller-only] [--next-views N] [--json]`: the main job on a scenario file.
#include <cstdio>

#include "examples/command.hpp"
#include "examples/run_scenario.hpp"

namespace claspplan::cli {
namespace {

struct RunCommandOptions {
  std::string scenario;
  std::string robot;  // replaces the scenario's
  RunOptions run;
  std::uint64_t seed = 0;
  double time_limit = 0.0;
  int max_cycles = 0;
  bool no_pictures = false;
  bool json = false;
};

}  // namespace

void add_run_command(CLI::App& app, Action& action) {
  auto o = std::make_shared<RunCommandOptions>();
  CLI::App* cmd = app.add_subcommand("run", command_description("run"));
  cmd->add_option("SCENARIO", o->scenario, "scenario file (YAML, see the README)")->required();
  cmd->add_option("--out", o->run.out_dir, "output folder for result.json, timing.json and PNGs")
      ->capture_default_str();
  cmd->add_option("--seed", o->seed, "random seed (overrides the scenario's)");
  cmd->add_option("--time-limit", o->time_limit, "planning wall-clock limit in seconds")
      ->check(CLI::PositiveNumber);
  cmd->add_option("--max-cycles", o->max_cycles,
                  "bound the search by TS-RRT cycles instead of time (reproducible on any "
                  "machine; no time limit unless --time-limit is given too)")
      ->check(CLI::Range(1, 10000000));
  cmd->add_option(
      "--robot", o->robot,
      "plan with this robot instead of the scenario's (built-in name or hand-description "
      "file); the scenario's start must fit its arm");
  cmd->add_flag("--controller-only", o->run.controller_only,
                "no planning: iterate the clasp controller toward the nearest clasp target");
  cmd->add_option("--next-views", o->run.next_views,
                  "when the run fails naming a camera for unseen space, render that view, add it "
                  "and run again, up to this many added cameras (scenarios with object: cameras)")
      ->check(CLI::Range(0, 10));
  cmd->add_flag("--no-pictures", o->no_pictures, "skip the PNG pictures");
  cmd->add_flag("--json", o->json, "print one JSON summary object instead of the text summary");
  cmd->callback([o, cmd, &action] {
    if (cmd->count("--seed")) o->run.seed = o->seed;
    if (cmd->count("--time-limit")) o->run.time_limit = o->time_limit;
    if (cmd->count("--max-cycles")) o->run.max_cycles = o->max_cycles;
    action = [o] {
      o->run.pictures = !o->no_pictures;
      o->run.quiet = o->json;
      Scenario scenario = load_scenario(o->scenario);
      if (!o->robot.empty()) use_robot(scenario, o->robot);
      const RunOutcome outcome = run_scenario(scenario, o->run);
      if (o->json) {
        print_json(outcome.summary);
      } else {
        print_run_summary(outcome.summary, o->run.controller_only);
      }
      return outcome.exit_code;
    };
  });
}

}  // namespace claspplan::cli
