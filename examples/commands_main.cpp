// claspplan-commands: every subcommand of `claspplan`, which starts it for all but `linking` and
// `--help` (main.cpp). It can be run directly too, with the same command line.
#include "examples/command.hpp"

int main(int argc, char** argv) {
  using namespace claspplan::cli;
  CLI::App app{program_description()};
  app.require_subcommand(1);
  app.fallthrough(false);
  Action action;
  add_demo_command(app, action);
  add_bench_command(app, action);
  add_linking_command(app, action);
  add_robot_command(app, action);
  add_describe_command(app, action);
  add_loops_command(app, action);
  add_run_command(app, action);
  add_verify_command(app, action);
  add_render_paper_command(app, action);
  return run_app(app, action, argc, argv);
}
