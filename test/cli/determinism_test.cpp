// Determinism: every committed scenario kind, run twice with the same seed, writes the same
// result.json byte for byte (the searches are bounded by cycles, so the machine's speed does not
// matter), and the secure-clasp check gives the same report on any number of threads. purse_1 is
// run twice by run_cli.cpp (PlannedPurse.SameSeedSameResultFile). Each case here is a verified
// clasp.
#include <gtest/gtest.h>

#include "test/support/cli_runner.hpp"

namespace claspplan::test {
namespace {

struct Case {
  std::string scenario;  // under examples/scenarios, without .yaml
  std::string seed;
  std::vector<std::string> bound;  // --max-cycles N, or --controller-only
};

void PrintTo(const Case& c, std::ostream* os) {
  *os << c.scenario << " --seed " << c.seed;
}

class SameSeed : public ::testing::TestWithParam<Case> {};

TEST_P(SameSeed, SameResultFileAndSameVerificationOnAnyThreadCount) {
  const Case& c = GetParam();
  TempDir dir;
  for (const char* out : {"a", "b"}) {
    std::vector<std::string> args = {
        "run",           std::string(CLASPPLAN_SCENARIOS) + "/" + c.scenario + ".yaml",
        "--seed",        c.seed,
        "--no-pictures", "--out",
        dir.file(out)};
    args.insert(args.end(), c.bound.begin(), c.bound.end());
    const CliResult r = run_cli(args);
    ASSERT_EQ(r.exit_code, 0) << r.err;
  }
  const std::string a = slurp(dir.file("a/result.json"));
  ASSERT_FALSE(a.empty());
  EXPECT_EQ(a, slurp(dir.file("b/result.json")));
  if (c.bound.front() == "--controller-only") return;
  // A verified clasp: its check again, on 1, 2 and 3 threads, gives one report.
  std::string first;
  for (const char* threads : {"1", "2", "3"}) {
    const CliResult v = run_cli({"verify", dir.file("a/result.json"), "--threads", threads,
                                 "--sequences", "4", "--motions", "100", "--json"});
    EXPECT_EQ(v.exit_code, 0) << v.err;
    if (first.empty()) first = v.out;
    EXPECT_EQ(v.out, first) << threads << " threads";
  }
}

INSTANTIATE_TEST_SUITE_P(
    EveryScenarioKind, SameSeed,
    ::testing::Values(Case{"controller_ring_icub", "2", {"--controller-only"}},
                      Case{"jug_armar3", "1", {"--max-cycles", "40"}},
                      Case{"obstructed_ring_armar3", "1", {"--max-cycles", "400"}},
                      Case{"real/utensil_rail_icub", "3", {"--max-cycles", "40"}}),
    [](const auto& info) {
      std::string name = info.param.scenario;
      for (char& ch : name)
        if (ch == '/') ch = '_';
      return name;
    });

}  // namespace
}  // namespace claspplan::test
