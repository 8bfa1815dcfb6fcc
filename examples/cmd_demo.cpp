// `claspplan demo`: the embedded default scenario end to end. A box with a ring handle seen by two
// depth cameras -> loops -> TS-RRT plan -> fingers closed -> verified clasp, with pictures.
#include <cstdio>

#include "examples/command.hpp"
#include "examples/demo_scenario.hpp"
#include "examples/run_scenario.hpp"

namespace claspplan::cli {
namespace {

struct DemoOptions {
  RunOptions run;
  std::uint64_t seed = 0;
  bool json = false;
};

int run_demo(DemoOptions& o) {
  const Scenario scenario = load_scenario_text(kDemoScenarioText, kDemoScenarioName, ".");
  o.run.quiet = o.json;
  if (!o.json) {
    std::printf(
        "claspplan demo: %s (the KR5 R850 with a Schunk SDH, a box with a ring handle seen "
        "by two depth cameras)\n",
        kDemoScenarioName);
  }
  const RunOutcome outcome = run_scenario(scenario, o.run);
  if (o.json) {
    print_json(outcome.summary);
    return outcome.exit_code;
  }
  print_run_summary(outcome.summary, /*controller_only=*/false);
  std::printf(
      "look at clasp_front.png, clasp_side.png, tree.png and poses.png there; the depth "
      "images it planned from are depth_*.png\n");
  return outcome.exit_code;
}

}  // namespace

void add_demo_command(CLI::App& app, Action& action) {
  auto o = std::make_shared<DemoOptions>();
  o->run.out_dir = "claspplan-demo";
  CLI::App* cmd = app.add_subcommand(
      "demo",
      "Run the embedded default scenario end to end (a few seconds) and write its pictures");
  cmd->add_option("--out", o->run.out_dir, "output folder")->capture_default_str();
  cmd->add_option("--seed", o->seed, "random seed (default: the scenario's)");
  cmd->add_flag("--json", o->json, "print one JSON summary object instead of the text");
  cmd->callback([o, cmd, &action] {
    if (cmd->count("--seed")) o->run.seed = o->seed;
    action = [o] { return run_demo(*o); };
  });
}

}  // namespace claspplan::cli
