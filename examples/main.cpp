// claspplan: plans a collision-free arm and hand motion that clasps a loop of an object seen in
// depth data (Stork, Pokorny, Kragic, IROS 2013). See README.md.
//
// This is a launcher: it answers `--help` and runs `linking` itself, and starts
// claspplan-commands (commands_main.cpp) with the same arguments for every other subcommand.
// Loading the libraries the planner needs (ViSP, PCL, FCL, OpenCV, OMPL: some 50 shared objects)
// takes about 0.1 s, which these two need not pay.
#include <cerrno>
#include <climits>
#include <cstring>
#include <string>

#include <unistd.h>

#include "examples/command.hpp"

namespace {

using namespace claspplan::cli;

// claspplan-commands next to this program (the build folder), or in
// ../libexec/claspplan/ (an installed prefix).
std::string commands_program() {
  char self[PATH_MAX];
  const ssize_t n = readlink("/proc/self/exe", self, sizeof self - 1);
  if (n <= 0) return "";
  const std::string path(self, static_cast<std::size_t>(n));
  const std::string dir = path.substr(0, path.rfind('/') + 1);
  for (const std::string& candidate :
       {dir + "claspplan-commands", dir + "../libexec/claspplan/claspplan-commands"}) {
    if (access(candidate.c_str(), X_OK) == 0) return candidate;
  }
  return "";
}

bool handled_here(const char* first) {
  return std::strcmp(first, "linking") == 0 || first[0] == '-';
}

}  // namespace

int main(int argc, char** argv) {
  if (argc > 1 && !handled_here(argv[1])) {
    const std::string program = commands_program();
    const bool json = wants_json(argc, argv);
    if (program.empty())
      return report_failure(kInternalError,
                            "internal error: claspplan-commands is not installed next to claspplan",
                            json);
    execv(program.c_str(), argv);
    return report_failure(kInternalError,
                          "internal error: cannot start " + program + ": " + std::strerror(errno),
                          json);
  }
  CLI::App app{program_description()};
  app.require_subcommand(1);
  app.fallthrough(false);
  Action action;
  for (const auto& c : command_list()) {
    if (std::strcmp(c.name, "linking") == 0)
      add_linking_command(app, action);
    else
      app.add_subcommand(c.name, c.description);  // listed here, run by claspplan-commands
  }
  return run_app(app, action, argc, argv);
}
