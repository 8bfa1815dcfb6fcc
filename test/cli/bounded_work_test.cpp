// Bounded work: requests that would run for hours are refused as bad input (exit 2), naming the
// cap: K_d on more than perception::kMaxPoints points, a secure-clasp check of more than
// kMaxVerificationMotions motions (a check with no time limit must still end).
#include <gtest/gtest.h>

#include "test/support/cli_runner.hpp"

namespace claspplan::test {
namespace {

void expect_refused(const CliResult& r, const std::string& cap) {
  EXPECT_EQ(r.exit_code, 2) << r.out << r.err;
  EXPECT_EQ(std::count(r.err.begin(), r.err.end(), '\n'), 1) << r.err;
  EXPECT_NE(r.err.find(cap), std::string::npos) << r.err;
}

TEST(BoundedWork, TooManyPointsAreRefused) {
  TempDir dir;
  const std::string cloud = dir.write("tetra.xyz", "0 0 0\n1 0 0\n0 1 0\n0 0 1\n");
  expect_refused(run_cli({"loops", cloud, "--points", "50001"}), "50000");
  expect_refused(run_cli({"run", dir.write("s.yaml",
                                           "robot: kr5_sdh\n"
                                           "object: {shape: {type: torus}}\n"
                                           "perception: {points: 50001}\n")}),
                 "50000");
}

TEST(BoundedWork, TooLongSecureClaspChecksAreRefused) {
  TempDir dir;
  expect_refused(
      run_cli({"verify", dir.file("any.json"), "--sequences", "11", "--motions", "10000"}),
      "100000");
  expect_refused(
      run_cli({"run", dir.write("s.yaml",
                                "robot: kr5_sdh\n"
                                "object: {shape: {type: torus}}\n"
                                "planner: {verify_sequences: 11, verify_motions: 10000}\n")}),
      "100000");
}

}  // namespace
}  // namespace claspplan::test
