// Exit codes are honest: 2 only when the user's input is bad (InputError), 3 for every internal
// failure, std::invalid_argument from an internal precondition included.
#include <stdexcept>

#include <gtest/gtest.h>

#include "core/input_error.hpp"
#include "examples/command.hpp"
#include "servo/linking.hpp"
#include "test/support/cli_runner.hpp"

namespace claspplan::cli {
namespace {

using test::CliResult;
using test::run_cli;
using test::TempDir;

int exit_code_of(const Action& action) {
  testing::internal::CaptureStderr();
  const int code = run_action(action, /*json=*/false);
  const std::string err = testing::internal::GetCapturedStderr();
  if (code >= kBadInput) {
    EXPECT_EQ(std::count(err.begin(), err.end(), '\n'), 1) << err;
  }
  if (code == kInternalError) {
    EXPECT_NE(err.find("internal error"), std::string::npos) << err;
  }
  return code;
}

TEST(ExitCodes, OnlyInputErrorsAreExitTwo) {
  EXPECT_EQ(exit_code_of([] { return kNoAnswer; }), kNoAnswer);
  EXPECT_EQ(exit_code_of([]() -> int { throw InputError("scenario.yaml: bad"); }), kBadInput);
  // Internal preconditions: curves that touch inside a run, a motion check with too many samples.
  EXPECT_EQ(exit_code_of([]() -> int { throw servo::CurvesIntersect("the curves touch"); }),
            kInternalError);
  EXPECT_EQ(exit_code_of([]() -> int { throw std::invalid_argument("motion_free: 1e9 samples"); }),
            kInternalError);
  EXPECT_EQ(exit_code_of([]() -> int { throw std::runtime_error("unexpected"); }), kInternalError);
  EXPECT_EQ(exit_code_of([]() -> int { throw 42; }), kInternalError);
}

TEST(ExitCodes, SharedChecksCalledOnUserInputBecomeInputErrors) {
  EXPECT_THROW(as_input_error([]() -> int { throw std::invalid_argument("bad mesh"); }),
               InputError);
  EXPECT_THROW(as_input_error([]() -> int { throw std::logic_error("bug"); }), std::logic_error);
  EXPECT_EQ(as_input_error([] { return 7; }), 7);
}

TEST(ExitCodes, TheBinaryReportsUserInputAsTwo) {
  TempDir dir;
  // Curves given by the user that touch: their input is bad (exit 2), not an internal failure.
  const std::string a = dir.write("a.txt", "0 0 0\n1 0 0\n1 1 0\n0 1 0\n");
  const std::string b = dir.write("b.txt", "0.5 0 0\n0.5 0 1\n0.5 1 1\n");
  const CliResult touching = run_cli({"linking", a, b, "--json"});
  EXPECT_EQ(touching.exit_code, 2) << touching.err;
  EXPECT_EQ(touching.json()["exit_code"], 2);
  // A scenario value of the wrong YAML type.
  const CliResult scenario =
      run_cli({"run", dir.write("s.yaml", "robot: kr5_sdh\nobject: {shape: {type: [1]}}\n")});
  EXPECT_EQ(scenario.exit_code, 2) << scenario.err;
  EXPECT_EQ(scenario.err.find("internal error"), std::string::npos) << scenario.err;
}

}  // namespace
}  // namespace claspplan::cli
