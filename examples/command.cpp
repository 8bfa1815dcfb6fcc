#include "examples/command.hpp"

#include <cstring>
#include <exception>
#include <iostream>
#include <stdexcept>

#include "core/input_error.hpp"

namespace claspplan::cli {

void print_json(const nlohmann::json& object) {
  std::cout << object.dump(2) << std::endl;
}

void progress(const std::string& message) {
  std::cerr << message << std::endl;
}

// One line on stderr and, with --json, one object on stdout, so scripts always get JSON.
int report_failure(int code, const std::string& reason, bool json) {
  const std::string line = one_line(reason);
  std::cerr << "claspplan: error: " << line << "\n";
  if (json) print_json({{"error", line}, {"exit_code", code}});
  return code;
}

const char* program_description() {
  return "claspplan: integrated motion and clasp planning with virtual linking";
}

// One line per subcommand, in the order of `claspplan --help`: the commands take their
// descriptions from here, and the launcher (main.cpp) lists them without loading the commands.
const std::vector<CommandInfo>& command_list() {
  static const std::vector<CommandInfo> list = {
      {"demo",
       "Run the embedded default scenario end to end (a few seconds) and write its pictures"},
      {"bench",
       "Run a suite of scenarios over seeds (the same pipeline as `run`, without pictures) and "
       "write report.md, cases.csv, cases.json and PNG plots; or merge the outputs of shards. "
       "Exit 0 when the report is written, 2 on bad input."},
      {"linking",
       "Linking number of two closed curves, or virtual linking (eq. 2) of a closed curve A and an "
       "open curve B with --virtual. Curve files: one 'x y z' per line (metres), '#' comments; a "
       "closed curve's last point joins its first."},
      {"robot",
       "The actuated joints (name, limits, arm or hand), the pose of tool0 and the finger curves "
       "of a robot at a configuration. NAME is a built-in robot (kr5_sdh, kr5_dlr, kr5_icub, "
       "kr5_armar3) or the path of a hand-description YAML file."},
      {"describe",
       "Draft a hand description for a robot from its URDF (and a hand's own URDF): arm chain, "
       "fingers, finger curves, tcp, v_fwd, v_swd, vlink_goal and allowed collision pairs, with "
       "what was guessed. Exit 0 when written, 2 on bad input."},
      {"loops",
       "Perception only (paper Sec. IV-A): the object's loops from depth images (PNG + --camera), "
       "clouds (.pcd .ply .xyz) or meshes (.obj .ply .stl .off); beta1, d, the loops ranked "
       "best first with their verdicts, and clasp targets on the best loop. Exit 0 for any valid "
       "input, beta1 = 0 included."},
      {"run",
       "Run a scenario: depth -> loops -> plan -> close the fingers -> prune -> verify. Exit 0 on "
       "a verified clasp (or, with --controller-only, when the controller reaches the hand's "
       "virtual-linking goal), 1 when there is none, 2 on bad input."},
      {"verify",
       "The secure-clasp check of a saved result: random translations and rotations of the object "
       "relative to the closed hand, each pursued until collision. Exit 0 secure, 1 not."},
      {"render-paper",
       "Render the paper's experiment scenes (purse, bag, travel bag, lawn mower, chair in three "
       "poses, and the obstructed chair) into depth files: DIR/<scene>/view_<i>.png + .yaml and "
       "scene.json"},
  };
  return list;
}

const char* command_description(const std::string& name) {
  for (const auto& c : command_list())
    if (name == c.name) return c.description;
  throw std::logic_error("no description for the command '" + name + "'");
}

int run_action(const Action& action, bool json) {
  try {
    return action ? action() : kOk;
  } catch (const InputError& e) {
    return report_failure(kBadInput, e.what(), json);
  } catch (const std::exception& e) {
    // Not the user's fault: a broken internal precondition (std::invalid_argument too) or a bug.
    return report_failure(kInternalError, std::string("internal error: ") + e.what(), json);
  } catch (...) {
    return report_failure(kInternalError, "internal error: an unknown exception", json);
  }
}

bool wants_json(int argc, char** argv) {
  for (int i = 1; i < argc; ++i)
    if (std::strcmp(argv[i], "--json") == 0) return true;
  return false;
}

int run_app(CLI::App& app, const Action& action, int argc, char** argv) {
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

}  // namespace claspplan::cli
