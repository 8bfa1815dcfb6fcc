// claspplan: plans a collision-free arm and hand motion that clasps a loop of an object seen in
// depth data (Stork, Pokorny, Kragic, IROS 2013). See README.md.
#include <cstring>
#include <iostream>

#include "examples/command.hpp"

namespace {

bool wants_json(int argc, char** argv) {
  for (int i = 1; i < argc; ++i)
    if (std::strcmp(argv[i], "--json") == 0) return true;
  return false;
}

}  // namespace

int main(int argc, char** argv) {
  using namespace claspplan::cli;
  CLI::App app{"claspplan: integrated motion and clasp planning with virtual linking"};
  app.require_subcommand(1);
  app.fallthrough(false);
  Action action;
  add_demo_command(app, action);
  add_bench_command(app, action);
  add_linking_command(app, action);
  add_robot_command(app, action);
  add_loops_command(app, action);
  add_run_command(app, action);
  add_verify_command(app, action);
  add_render_paper_command(app, action);

  const bool json = wants_json(argc, argv);
  try {
    app.parse(argc, argv);
  } catch (const CLI::CallForHelp& e) {
    return app.exit(e);
  } catch (const CLI::CallForAllHelp& e) {
    return app.exit(e);
  } catch (const CLI::ParseError& e) {
    // CLI11 would exit with 100-127; usage errors are exit 2 here.
    return report_failure(kBadInput, std::string(e.what()) + " (see --help)", json);
  }

  return run_action(action, json);
}
