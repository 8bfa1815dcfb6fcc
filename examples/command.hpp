// The conventions every `claspplan` subcommand follows.
//
// Exit codes: 0 success, 1 a valid problem without an answer (no claspable loop, no clasp found,
// not secure), 2 malformed input or usage (a one-line reason on stderr), 3 internal error.
// Malformed input is signalled by throwing claspplan::InputError (core/input_error.hpp)
// anywhere below a command; any other exception, std::invalid_argument included, is an internal
// error. With --json a command prints exactly one JSON object on stdout.
#pragma once

#include <functional>
#include <string>
#include <vector>

#include <CLI/CLI.hpp>
#include <nlohmann/json.hpp>

namespace claspplan::cli {

enum ExitCode : int { kOk = 0, kNoAnswer = 1, kBadInput = 2, kInternalError = 3 };

/// The selected command's action; set by the subcommand's parse callback, run by main().
using Action = std::function<int()>;

/// Runs a command's action and maps what it throws to an exit code: InputError -> kBadInput,
/// anything else -> kInternalError ("internal error: ..."), each with one line on stderr (and with
/// `json` one object {error, exit_code} on stdout).
int run_action(const Action& action, bool json);

/// The one-line failure report of run_action() and of usage errors; returns `code`.
int report_failure(int code, const std::string& reason, bool json);

/// Prints one JSON object on stdout (stable key order, full double precision).
void print_json(const nlohmann::json& object);

/// Progress and notes for humans go to stderr, so that stdout stays clean for --json.
void progress(const std::string& message);

/// The program's description, the first line of `claspplan --help`.
const char* program_description();

/// A subcommand's name and its one-line description (what `claspplan --help` lists).
struct CommandInfo {
  const char* name;
  const char* description;
};
/// Every subcommand but the hidden helpers, in the order of `claspplan --help`.
const std::vector<CommandInfo>& command_list();
/// The description of the subcommand `name` (std::logic_error if there is none).
const char* command_description(const std::string& name);

/// Whether the command line asks for --json (then failures are reported as JSON too).
bool wants_json(int argc, char** argv);

/// Parses the command line into `app` (whose subcommands set `action`) and runs the action:
/// usage errors are exit 2 with the one-line report, --help prints and exits 0.
int run_app(CLI::App& app, const Action& action, int argc, char** argv);

// One function per subcommand, each in its cmd_<name>.cpp.
void add_bench_command(CLI::App& app, Action& action);
void add_demo_command(CLI::App& app, Action& action);
void add_describe_command(CLI::App& app, Action& action);
void add_linking_command(CLI::App& app, Action& action);
void add_robot_command(CLI::App& app, Action& action);
void add_loops_command(CLI::App& app, Action& action);
void add_run_command(CLI::App& app, Action& action);
void add_verify_command(CLI::App& app, Action& action);
void add_render_paper_command(CLI::App& app, Action& action);

}  // namespace claspplan::cli
