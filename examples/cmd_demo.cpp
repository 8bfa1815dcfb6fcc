// `claspplan demo`: the embedded default scenario end to end. A shoulder bag on a table seen by two
// depth cameras (the committed depth files, embedded) -> loops -> TS-RRT plan -> fingers closed ->
// verified clasp, with pictures.
#include <cstdio>
#include <filesystem>
#include <fstream>

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

// Writes the embedded depth files under <out>/input/ as examples/ holds them, and returns the
// folder the scenario's relative paths start from.
std::string unpack_demo_files(const std::string& out_dir) {
  namespace fs = std::filesystem;
  const fs::path root = fs::path(out_dir) / "input";
  for (const EmbeddedFile& f : kDemoFiles) {
    const fs::path path = root / f.path;
    fs::create_directories(path.parent_path());
    std::ofstream(path, std::ios::binary)
        .write(reinterpret_cast<const char*>(f.data), static_cast<std::streamsize>(f.size));
  }
  return (root / "scenarios").string();
}

int run_demo(DemoOptions& o) {
  const Scenario scenario =
      load_scenario_text(kDemoScenarioText, kDemoScenarioName, unpack_demo_files(o.run.out_dir));
  o.run.quiet = o.json;
  if (!o.json) {
    std::printf(
        "claspplan demo: %s (the KR5 R850 with a Schunk SDH, a shoulder bag on a table seen "
        "by three depth cameras: the paper's bag, pose 2, from its committed depth files)\n",
        kDemoScenarioName);
  }
  const RunOutcome outcome = run_scenario(scenario, o.run);
  if (o.json) {
    print_json(outcome.summary);
    return outcome.exit_code;
  }
  print_run_summary(outcome.summary, /*controller_only=*/false);
  std::printf(
      "look at clasp_front.png, clasp_side.png, tree.png, poses.png and sensed.png there; the "
      "depth "
      "images it planned from are in input/depth/\n");
  return outcome.exit_code;
}

}  // namespace

void add_demo_command(CLI::App& app, Action& action) {
  auto o = std::make_shared<DemoOptions>();
  o->run.out_dir = "claspplan-demo";
  CLI::App* cmd = app.add_subcommand("demo", command_description("demo"));
  cmd->add_option("--out", o->run.out_dir, "output folder")->capture_default_str();
  cmd->add_option("--seed", o->seed, "random seed (default: the scenario's)");
  cmd->add_flag("--json", o->json, "print one JSON summary object instead of the text");
  cmd->callback([o, cmd, &action] {
    if (cmd->count("--seed")) o->run.seed = o->seed;
    action = [o] { return run_demo(*o); };
  });
}

}  // namespace claspplan::cli
