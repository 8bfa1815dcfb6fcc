// `claspplan bench`: suites and shards, the quick suite end to end, merging shard outputs, and
// its bad-input answers.
#include <cmath>
#include <filesystem>
#include <set>
#include <tuple>

#include <gtest/gtest.h>

#include "examples/bench_report.hpp"
#include "examples/bench_suite.hpp"
#include "test/support/cli_runner.hpp"

namespace claspplan::test {
namespace {

using nlohmann::json;

TEST(BenchSuite, ShardsPartitionTheCasesInOrder) {
  TempDir dir;
  for (const char* name : {"jug_sdh", "jug_icub", "purse_1_dlr", "purse_1_kuka", "other"}) {
    dir.write(std::string(name) + ".yaml", "name: x\n");
  }
  const auto cases = cli::suite_cases("quick", dir.path().string(), 3);
  // 3 matching files (not purse_1_kuka, not other) x 3 seeds, then each baseline at seed 1.
  ASSERT_EQ(cases.size(), 9u + 3u * cli::bench_baselines().size());
  EXPECT_EQ(cases.front().name, "jug_icub");
  EXPECT_EQ(cases.front().seed, 1u);
  EXPECT_EQ(cases[8].name, "purse_1_dlr");
  EXPECT_EQ(cases[8].seed, 3u);
  EXPECT_EQ(cases[9].name, "jug_icub");
  EXPECT_EQ(cases[9].method, cli::bench_baselines()[0]);
  EXPECT_EQ(cases.back().seed, 1u);

  std::multiset<std::string> seen;
  for (int k = 1; k <= 4; ++k) {
    for (const auto& c : cli::shard_cases(cases, std::to_string(k) + "/4"))
      seen.insert(c.name + "#" + std::to_string(c.seed));
  }
  std::multiset<std::string> all;
  for (const auto& c : cases) all.insert(c.name + "#" + std::to_string(c.seed));
  EXPECT_EQ(seen, all);  // every case in exactly one shard
  EXPECT_EQ(cli::shard_cases(cases, "2/4").front().name, cases[1].name);

  EXPECT_THROW(cli::shard_cases(cases, "0/4"), std::invalid_argument);
  EXPECT_THROW(cli::shard_cases(cases, "5/4"), std::invalid_argument);
  EXPECT_THROW(cli::shard_cases(cases, "1-4"), std::invalid_argument);
  // purse_1_dlr at seed 1, then at seed 1 with each tolerance of the sweep, then the baselines.
  const auto paper = cli::suite_cases("paper", dir.path().string(), 1);
  const std::size_t tolerances = cli::paper_tolerances().size();
  ASSERT_EQ(paper.size(), 1u + tolerances + cli::bench_baselines().size());
  EXPECT_EQ(paper[0].tolerance, 0.0);
  EXPECT_EQ(paper.back().method, cli::bench_baselines().back());
  for (std::size_t i = 1; i <= tolerances; ++i) {
    EXPECT_EQ(paper[i].name, "purse_1_dlr");
    EXPECT_EQ(paper[i].tolerance, cli::paper_tolerances()[i - 1]);
  }
  TempDir empty;
  EXPECT_THROW(cli::suite_cases("real", empty.path().string(), 1), std::invalid_argument);
  EXPECT_THROW(cli::suite_cases("nosuch", dir.path().string(), 1), std::invalid_argument);
}

TEST(BenchReport, RecordsSurviveTheirFileAndMissingValuesStayMissing) {
  cli::BenchRecord r;
  r.name = "real/pitcher_sdh";
  r.scenario = "x.yaml";
  r.seed = 3;
  r.exit_code = 1;
  r.reason = "no claspable loop: \"quoted\", with a comma";
  const cli::BenchRecord back = cli::record_from_json(cli::record_json(r));
  EXPECT_EQ(back.name, r.name);
  EXPECT_EQ(back.seed, 3u);
  EXPECT_EQ(back.reason, r.reason);
  EXPECT_TRUE(std::isnan(back.min_open_linking));
  EXPECT_THROW(cli::record_from_json(json{{"name", "x"}}), std::invalid_argument);
}

// The tolerance sweep's runs are reported in their own section and plot, outside the summary.
TEST(BenchReport, SweepRunsHaveTheirOwnSectionAndStayOutOfTheSummary) {
  std::vector<cli::BenchRecord> records(3);
  records[0].name = "purse_1_sdh";
  records[0].verified = records[0].success = true;
  records[0].seconds = 0.4;
  for (int i : {1, 2}) {
    records[i].name = "purse_1_sdh";
    records[i].tolerance = i == 1 ? 0.5 : 0.75;
    records[i].final_linking = i == 1 ? 0.61 : 0.93;
    records[i].verified = records[i].success = i == 2;
    records[i].seconds = 9.0;
  }
  const json s = cli::bench_summary(records);
  EXPECT_EQ(s["cases"], 1);
  EXPECT_EQ(s["max_seconds"].get<double>(), 0.4);
  for (const auto& method : cli::bench_baselines()) EXPECT_EQ(s[method]["cases"], 0) << method;
  TempDir dir;
  cli::write_bench_report(records, dir.file("out"), "t");
  const std::string md = slurp(dir.file("out/report.md"));
  EXPECT_NE(md.find("| 0.50 | 1 | 1 | 0.61 | 0.61 | 0/1 |"), std::string::npos) << md;
  EXPECT_NE(md.find("| 0.75 | 1 | 1 | 0.93 | 0.93 | 1/1 |"), std::string::npos) << md;
  EXPECT_NE(md.find("| purse_1_sdh | 0.61 | 0.93 S |"), std::string::npos) << md;
  EXPECT_TRUE(std::filesystem::exists(dir.file("out/tolerance_sweep.png")));
  const auto back = cli::read_bench_cases(dir.file("out/cases.json"));
  ASSERT_EQ(back.size(), 3u);
  EXPECT_EQ(back[2].tolerance, 0.75);
  EXPECT_EQ(back[2].final_linking, 0.93);
}

// The quick suite (bounded by cycles, its default) as two shards of a cluster job, two runs at a
// time, merged into one report.
TEST(BenchCli, QuickSuiteShardsMergeIntoOneReport) {
  TempDir dir;
  int verified = 0;
  for (const char* k : {"1", "2"}) {
    const CliResult part =
        run_cli({"bench", "--suite", "quick", "--shard", std::string(k) + "/2", "--jobs", "2",
                 "--out", dir.file(std::string("shard") + k), "--json"});
    ASSERT_EQ(part.exit_code, 0) << part.err;
    EXPECT_EQ(part.json()["cases"], 4);
    for (const auto& method : cli::bench_baselines()) EXPECT_EQ(part.json()[method]["cases"], 4);
    verified += part.json()["verified"].get<int>();
  }
  const CliResult r = run_cli({"bench", "--merge", dir.file("shard1"), dir.file("shard2"), "--out",
                               dir.file("all"), "--json"});
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const json s = r.json();
  EXPECT_EQ(s["cases"], 8);
  EXPECT_EQ(s["verified"], verified);
  EXPECT_GE(verified, 6) << r.out;
  EXPECT_GT(s["median_seconds"].get<double>(), 0.0);
  EXPECT_GE(s["max_seconds"].get<double>(), s["median_seconds"].get<double>());
  // The baselines on the same 8 scenarios, in the summary with their own keys.
  for (const auto& method : cli::bench_baselines()) {
    const json& b = s[method];
    EXPECT_EQ(b["cases"], 8) << method;
    for (const char* key : {"success", "verified", "median_seconds"})
      EXPECT_TRUE(b.contains(key)) << method << " " << key;
    EXPECT_LE(b["verified"].get<int>(), b["success"].get<int>()) << method;
    EXPECT_TRUE(std::filesystem::exists(dir.file("all/" + method + "_time.png"))) << method;
  }
  // When written (seed 1): the two-phase planner verified 7 of 8 clasps; Grasp-RRT scored 8
  // grasps, none a clasp (paper Sec. V-D: under 5 %).
  EXPECT_GE(s["ompl_two_phase"]["verified"].get<int>(), 4);
  EXPECT_GE(s["grasp_rrt"]["success"].get<int>(), 4);
  EXPECT_LE(s["grasp_rrt"]["verified"].get<int>(), 2);
  for (const char* f :
       {"report.md", "cases.csv", "cases.json", "linking_scatter.png", "time_per_case.png"}) {
    EXPECT_TRUE(std::filesystem::exists(dir.file(std::string("all/") + f))) << f;
  }
  const auto records = cli::read_bench_cases(dir.file("all/cases.json"));
  ASSERT_EQ(records.size(), 8u * (1 + cli::bench_baselines().size()));
  for (std::size_t i = 0; i < records.size(); ++i) {
    const auto& rec = records[i];
    EXPECT_EQ(rec.method, i < 8 ? "" : cli::bench_baselines()[i / 8 - 1]);
    if (i % 8 != 0) {
      EXPECT_LT(records[i - 1].name, rec.name);  // merged in name order, per method
    }
    EXPECT_EQ(rec.exit_code, (rec.method.empty() ? rec.verified : rec.success) ? 0 : 1) << rec.name;
    if (rec.verified) {
      EXPECT_GT(rec.min_open_linking, 0.0) << rec.name;
      EXPECT_LE(rec.min_virtual_linking, rec.max_virtual_linking) << rec.name;
      EXPECT_GT(rec.verification, 0.0) << rec.name;
    }
  }
  // The unsharded run gives the same records in the same order (bounded by cycles, every run
  // depends on its seed only; the seconds do not take part).
  const CliResult whole =
      run_cli({"bench", "--suite", "quick", "--jobs", "2", "--out", dir.file("whole"), "--json"});
  ASSERT_EQ(whole.exit_code, 0) << whole.err;
  EXPECT_EQ(whole.json()["verified"], s["verified"]);
  const auto unsharded = cli::read_bench_cases(dir.file("whole/cases.json"));
  ASSERT_EQ(unsharded.size(), records.size());
  for (std::size_t i = 0; i < records.size(); ++i) {
    const auto &a = records[i], &b = unsharded[i];
    EXPECT_EQ(std::tie(a.name, a.seed, a.method, a.exit_code, a.verified, a.cycles, a.nodes),
              std::tie(b.name, b.seed, b.method, b.exit_code, b.verified, b.cycles, b.nodes))
        << a.name << " " << a.method;
    EXPECT_TRUE(a.final_linking == b.final_linking ||
                (std::isnan(a.final_linking) && std::isnan(b.final_linking)))
        << a.name << " " << a.method;
  }
}

// Each baseline once, briefly (one shard holds one case): cheap enough to run sanitized, where the
// quick suite as a whole is too slow.
TEST(BenchCli, EachBaselineRunsOneScenario) {
  TempDir dir;
  const std::size_t per_method = 8;  // quick: purse_1 and jug, 4 hands each
  for (std::size_t m = 0; m < cli::bench_baselines().size(); ++m) {
    const std::string method = cli::bench_baselines()[m];
    const std::string shard = std::to_string(per_method * (m + 1) + 1) + "/" +
                              std::to_string(per_method * (cli::bench_baselines().size() + 1));
    const CliResult r = run_cli({"bench", "--suite", "quick", "--shard", shard, "--max-cycles",
                                 "40", "--out", dir.file(method), "--json"});
    ASSERT_EQ(r.exit_code, 0) << r.err;
    EXPECT_EQ(r.json()["cases"], 0) << method;
    EXPECT_EQ(r.json()[method]["cases"], 1) << method;
    const auto records = cli::read_bench_cases(dir.file(method + "/cases.json"));
    ASSERT_EQ(records.size(), 1u);
    EXPECT_EQ(records[0].method, method);
    EXPECT_FALSE(records[0].reason.empty());
  }
}

TEST(BenchCli, BadInputIsExitTwoWithAReason) {
  TempDir dir;
  for (const std::vector<std::string>& args :
       {std::vector<std::string>{"bench"},
        {"bench", "--suite", "nosuch", "--out", dir.file("a")},
        {"bench", "--suite", "quick", "--shard", "3/2", "--out", dir.file("b")},
        {"bench", "--suite", "quick", "--scenarios", dir.file("missing"), "--out", dir.file("c")},
        {"bench", "--merge", dir.file("missing"), "--out", dir.file("d")},
        {"bench", "--suite", "quick", "--merge", dir.file("x")}}) {
    const CliResult r = run_cli(args);
    EXPECT_EQ(r.exit_code, 2) << args[1] << " " << (args.size() > 2 ? args[2] : "") << r.err;
    EXPECT_NE(r.err.find("error: "), std::string::npos) << r.err;
  }
}

}  // namespace
}  // namespace claspplan::test
