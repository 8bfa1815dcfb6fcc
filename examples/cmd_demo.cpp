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
  const auto& s = outcome.summary;
  if (s.value("verified", false)) {
    std::printf(
        "verified clasp: found after %d cycles (%d tree nodes) in %.2f s of planning; "
        "virtual linking %.3f\n",
        s.value("cycles", 0), s.value("nodes", 0), s.value("seconds", 0.0),
        s.value("virtual_linking", 0.0));
  } else {
    std::printf("no verified clasp: %s\n", s.value("reason", std::string()).c_str());
  }
  std::printf(
      "look at %s/clasp_front.png, clasp_side.png, tree.png and poses.png; the plan is in "
      "result.json, the depth images in depth_*.png\n",
      o.run.out_dir.c_str());
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
