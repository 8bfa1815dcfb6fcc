// `claspplan linking` and `claspplan demo` as a user runs them.
#include <cstdlib>
#include <filesystem>
#include <sstream>
#include <utility>

#include <gtest/gtest.h>

#include "test/support/cli_runner.hpp"
#include "test/support/curves.hpp"

namespace claspplan::test {
namespace {

std::string curve_text(const Curve& c) {
  std::ostringstream out;
  out.precision(17);
  out << "# x y z (metres)\n";
  for (const auto& p : c) out << p.x() << " " << p.y() << " " << p.z() << "\n";
  return out.str();
}

const std::string kSquare = "0 0 0\n2 0 0\n2 2 0\n0 2 0\n0 0 0  # repeated first point\n";
const std::string kPiercing = "1 1 -1\n1 1 1\n3 1 1\n3 1 -1\n";

TEST(LinkingCli, RightHandRuleAndJson) {
  TempDir dir;
  const auto a = dir.write("a.txt", kSquare);
  const auto b = dir.write("b.txt", kPiercing);
  const CliResult r = run_cli({"linking", a, b, "--json"});
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_EQ(r.json()["linking"], 1);
  const CliResult human = run_cli({"linking", a, b});
  EXPECT_EQ(human.exit_code, 0);
  EXPECT_NE(human.out.find("Lk(A, B) = 1"), std::string::npos) << human.out;
  const auto rb =
      dir.write("rb.txt", curve_text(reversed({{1, 1, -1}, {1, 1, 1}, {3, 1, 1}, {3, 1, -1}})));
  EXPECT_EQ(run_cli({"linking", a, rb, "--json"}).json()["linking"], -1);
}

TEST(LinkingCli, VirtualLinkingOfAnOpenFingerCurve) {
  TempDir dir;
  const auto loop = dir.write(
      "loop.txt",
      curve_text(circle({0, 0, 0}, 0.1, Eigen::Vector3d::UnitX(), Eigen::Vector3d::UnitY(), 48)));
  Curve finger;
  for (int i = 0; i < 9; ++i) {
    const double t = kPi - 2.5 + 5.0 * i / 8.0;  // a 286° arc around the strand at (0.1, 0, 0)
    finger.emplace_back(0.1 + 0.04 * std::cos(t), 0.0, 0.04 * std::sin(t));
  }
  const auto f = dir.write("finger.txt", curve_text(finger));
  const CliResult r = run_cli({"linking", loop, f, "--virtual", "--json"});
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const auto j = r.json();
  EXPECT_EQ(std::abs(j["linking"].get<int>()), 1);
  const double vlk = j["virtual_linking"], open = j["open_linking"];
  EXPECT_GT(std::abs(vlk), 0.7);
  EXPECT_LT(std::abs(vlk), 1.0);
  EXPECT_GT(std::abs(open), 0.5);
  // Without --virtual the open finger would be read as a closed curve: a different question.
  EXPECT_EQ(run_cli({"linking", loop, f, "--json"}).exit_code, 0);
}

TEST(LinkingCli, BadInputIsExitTwoWithOneLineReason) {
  TempDir dir;
  const auto good = dir.write("good.txt", kSquare);
  const std::vector<std::pair<std::string, std::string>> bad = {
      {"empty.txt", ""},
      {"comments.txt", "# nothing here\n\n"},
      {"one_point.txt", "1 2 3\n"},
      {"two_numbers.txt", "0 0 0\n1 1\n2 0 0\n"},
      {"word.txt", "0 0 0\n1 x 0\n2 0 0\n"},
      {"nan.txt", "0 0 0\nnan 0 0\n2 0 0\n"},
      {"inf.txt", "0 0 0\n1 inf 0\n2 0 0\n"},
      {"zero_segment.txt", "0 0 5\n1 0 5\n1 0 5\n0 1 5\n"},
      {"binary.txt", std::string("\x89PNG\r\n\x1a\n\0\0\0", 11)},
      {"crossing.txt", "1 -1 0\n1 1 0\n3 1 0\n3 -1 0\n"},  // crosses the square in its plane
  };
  for (const auto& [name, content] : bad) {
    const auto path = dir.write(name, content);
    const CliResult r = run_cli({"linking", good, path});
    EXPECT_EQ(r.exit_code, 2) << name << ": " << r.out << r.err;
    EXPECT_NE(r.err.find("error"), std::string::npos) << name;
    EXPECT_EQ(std::count(r.err.begin(), r.err.end(), '\n'), 1) << name << ": " << r.err;
  }
  EXPECT_EQ(run_cli({"linking", good, dir.file("missing.txt")}).exit_code, 2);
  EXPECT_EQ(run_cli({"linking", good}).exit_code, 2);
  EXPECT_EQ(run_cli({"linking", good, good, "--no-such-flag"}).exit_code, 2);
  EXPECT_EQ(run_cli({"no-such-command"}).exit_code, 2);
  // With --json the error is also one JSON object on stdout.
  const CliResult j = run_cli({"linking", good, dir.file("missing.txt"), "--json"});
  EXPECT_EQ(j.exit_code, 2);
  EXPECT_EQ(j.json()["exit_code"], 2);
}

TEST(LinkingCli, HelpIsAvailable) {
  const CliResult r = run_cli({"linking", "--help"});
  EXPECT_EQ(r.exit_code, 0);
  EXPECT_NE(r.out.find("--virtual"), std::string::npos);
  EXPECT_EQ(run_cli({"--help"}).exit_code, 0);
}

// The launcher answers --help and runs `linking` on its own (neither loads the planner's
// libraries), and starts claspplan-commands, found next to it, for everything else.
TEST(Launcher, HelpAndLinkingWithoutTheCommandsProgram) {
  TempDir dir;
  const std::string alone = dir.file("claspplan");
  std::filesystem::copy_file(CLASPPLAN_EXE, alone);
  std::filesystem::permissions(alone, std::filesystem::perms::owner_all);
  const auto run = [&](const std::string& args) {
    const std::string out = dir.file("out"), err = dir.file("err");
    const int status =
        std::system((shell_quote(alone) + " " + args + " >" + out + " 2>" + err).c_str());
    return std::make_pair(WIFEXITED(status) ? WEXITSTATUS(status) : -1, slurp(out) + slurp(err));
  };
  const auto help = run("--help");
  EXPECT_EQ(help.first, 0);
  for (const char* command : {"demo", "bench", "linking", "robot", "loops", "run", "verify"})
    EXPECT_NE(help.second.find(std::string("  ") + command + " "), std::string::npos) << command;
  const auto a = dir.write("a.txt", kSquare), b = dir.write("b.txt", kPiercing);
  const auto linking = run("linking " + a + " " + b);
  EXPECT_EQ(linking.first, 0) << linking.second;
  EXPECT_NE(linking.second.find("Lk(A, B) = 1"), std::string::npos) << linking.second;
  EXPECT_EQ(run("--bogus").first, 2);
  // Any other command needs claspplan-commands: an internal error (exit 3), in one line.
  const auto robot = run("robot kr5_sdh");
  EXPECT_EQ(robot.first, 3);
  EXPECT_NE(robot.second.find("claspplan-commands is not installed"), std::string::npos);
  // Next to the real launcher, the same command runs.
  EXPECT_EQ(run_cli({"robot", "kr5_sdh"}).exit_code, 0);
}

}  // namespace
}  // namespace claspplan::test
