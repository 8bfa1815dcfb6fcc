// `claspplan loops` as a user runs it: depth files, clouds and meshes in, loops and targets out;
// every bad input is exit 2 with a one-line reason; an object without loops is exit 0.
#include <gtest/gtest.h>
#include <opencv2/core.hpp>
#include <opencv2/imgcodecs.hpp>

#include "core/file_io.hpp"
#include "examples/objects.hpp"
#include "test/support/cli_runner.hpp"

namespace claspplan::test {
namespace {

void expect_bad_input(const std::vector<std::string>& args, const std::string& fragment) {
  const CliResult r = run_cli(args);
  EXPECT_EQ(r.exit_code, 2) << r.err;
  // One line on stderr, naming the problem.
  EXPECT_EQ(r.err.rfind("claspplan: error: ", 0), 0u) << r.err;
  EXPECT_EQ(std::count(r.err.begin(), r.err.end(), '\n'), 1) << r.err;
  EXPECT_NE(r.err.find(fragment), std::string::npos) << r.err;
}

std::vector<std::string> depth_args(const TempDir& dir, int cameras, double sigma = 0.0) {
  perception::DepthNoise noise;
  noise.sigma = sigma;
  std::vector<std::string> args{"loops"};
  for (const auto& [png, yaml] :
       objects::write_purse_depth_example(dir.file("depth"), cameras, noise)) {
    args.push_back(png);
    args.push_back("--camera");
    args.push_back(yaml);
  }
  return args;
}

TEST(LoopsCli, DepthFilesJsonAndPicture) {
  TempDir dir;
  auto args = depth_args(dir, 2);
  for (const char* extra : {"--json", "--targets", "9", "--png"}) args.push_back(extra);
  args.push_back(dir.file("k.png"));
  const CliResult r = run_cli(args);
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const auto j = r.json();
  for (const char* key : {"beta1", "d", "points", "loops", "targets", "seconds"})
    EXPECT_TRUE(j.contains(key)) << key;
  EXPECT_GE(j["beta1"].get<int>(), 1);
  EXPECT_EQ(j["points"], 2000);
  EXPECT_GT(j["d"].get<double>(), 0.005);
  EXPECT_LT(j["d"].get<double>(), 0.05);
  EXPECT_GT(j["seconds"].get<double>(), 0.0);
  const auto& best = j["loops"][0];
  EXPECT_EQ(best["rank"], 1);
  EXPECT_TRUE(best["claspable"].get<bool>()) << best["reason"];
  EXPECT_GT(best["length"].get<double>(), 0.3);
  EXPECT_GE(best["points"].size(), 10u);
  EXPECT_EQ(best["points"][0].size(), 3u);
  ASSERT_EQ(j["targets"].size(), 9u);
  const auto& t = j["targets"][0];
  EXPECT_EQ(t["p"].size(), 3u);
  const double tn = std::hypot(t["tangent"][0].get<double>(), t["tangent"][1].get<double>(),
                               t["tangent"][2].get<double>());
  EXPECT_NEAR(tn, 1.0, 1e-9);
  // The targets lie on the loop's handle, above the body.
  for (const auto& target : j["targets"]) EXPECT_GT(target["p"][2].get<double>(), 0.19);
  const cv::Mat picture = cv::imread(dir.file("k.png"));
  EXPECT_EQ(picture.cols, 900);
  EXPECT_EQ(picture.rows, 700);
}

TEST(LoopsCli, HumanSummaryAndDeterminism) {
  TempDir dir;
  auto args = depth_args(dir, 1, 0.001);
  const CliResult human = run_cli(args);
  ASSERT_EQ(human.exit_code, 0) << human.err;
  EXPECT_NE(human.out.find("beta1 = "), std::string::npos) << human.out;
  EXPECT_NE(human.out.find("loop rank 1: length"), std::string::npos) << human.out;
  EXPECT_NE(human.out.find("claspable"), std::string::npos) << human.out;
  EXPECT_NE(human.err.find("automatic d"), std::string::npos) << human.err;  // progress on stderr
  args.push_back("--json");
  auto a = run_cli(args).json(), b = run_cli(args).json();
  a.erase("seconds"), a.erase("timings"), b.erase("seconds"), b.erase("timings");
  EXPECT_EQ(a, b);
  args.push_back("--seed");
  args.push_back("5");
  auto c = run_cli(args).json();
  EXPECT_NE(c["d"], a["d"]);
}

TEST(LoopsCli, MeshesAndClouds) {
  TempDir dir;
  write_obj(objects::sphere_mesh(0.1), dir.file("sphere.obj"));
  const CliResult sphere = run_cli({"loops", dir.file("sphere.obj")});
  EXPECT_EQ(sphere.exit_code, 0) << sphere.err;
  EXPECT_NE(sphere.out.find("no loops"), std::string::npos) << sphere.out;
  const auto sj = run_cli({"loops", dir.file("sphere.obj"), "--json"}).json();
  EXPECT_EQ(sj["beta1"], 0);
  EXPECT_TRUE(sj["loops"].empty());
  EXPECT_TRUE(sj["targets"].empty());

  write_ply(objects::torus_mesh(0.1, 0.03), dir.file("torus.ply"));
  EXPECT_EQ(run_cli({"loops", dir.file("torus.ply"), "--json"}).json()["beta1"], 2);
  EXPECT_EQ(run_cli({"loops", dir.file("torus.ply"), "--d", "0.09", "--json"}).json()["beta1"], 1);

  // The purse's visible surface from two positions (one with a negative coordinate).
  write_stl(objects::purse(), dir.file("purse.stl"));
  const auto pj = run_cli({"loops", dir.file("purse.stl"), "--view", "0.25,-0.75,0.65",
                           "--view=-0.35,0.7,0.7", "--json"})
                      .json();
  EXPECT_GE(pj["beta1"].get<int>(), 1);
  EXPECT_TRUE(pj["loops"][0]["claspable"].get<bool>());

  // A cloud file: the torus sampled, as .xyz and .pcd.
  write_xyz(sample_surface(objects::torus_mesh(0.1, 0.03), 8000, 3), dir.file("torus.xyz"));
  EXPECT_EQ(run_cli({"loops", dir.file("torus.xyz"), "--d", "0.09", "--json"}).json()["beta1"], 1);
  write_pcd(sample_surface(objects::torus_mesh(0.1, 0.03), 8000, 3), dir.file("torus.pcd"));
  // A cloud goes through the depth stages: --keep-plane, or the torus's flat underside is taken
  // for its table.
  const auto tj =
      run_cli({"loops", dir.file("torus.pcd"), "--points", "1000", "--keep-plane", "--json"})
          .json();
  EXPECT_EQ(tj["points"], 1000);
  EXPECT_EQ(tj["beta1"], 2);
}

TEST(LoopsCli, BadInputIsExitTwoWithOneLine) {
  TempDir dir;
  expect_bad_input({"loops", dir.write("empty.xyz", "")}, "empty");
  // NaN points are skipped (issue 33): three points are left.
  expect_bad_input({"loops", dir.write("nan.xyz", "0 0 0\n1 0 0\n0 nan 1\n0 0 1\n")},
                   "fewer than 4 distinct");
  expect_bad_input({"loops", dir.write("three.xyz", "0 0 0\n1 0 0\n0 1 0\n1 0 0\n")},
                   "fewer than 4 distinct");
  std::string flat;
  for (int i = 0; i < 50; ++i) flat += std::to_string(i % 7) + " " + std::to_string(i / 7) + " 0\n";
  expect_bad_input({"loops", dir.write("flat.xyz", flat)}, "coplanar");
  expect_bad_input({"loops", dir.write("wrong.ply", "solid\nfacet\n")}, "not a PLY");
  expect_bad_input({"loops", dir.write("wrong.dat", "1 2 3\n")}, "unknown file type");
  write_ply(objects::torus_mesh(0.1, 0.03), dir.file("torus.ply"));
  std::string ply = slurp(dir.file("torus.ply"));
  expect_bad_input({"loops", dir.write("cut.ply", ply.substr(0, ply.size() / 2))}, "truncated");
  expect_bad_input({"loops", dir.file("missing.pcd")}, "not found");

  const auto files = objects::write_purse_depth_example(dir.file("depth"), 1);
  const std::string cam = files[0].second;
  expect_bad_input({"loops", files[0].first}, "camera");  // PNG without --camera
  cv::imwrite(dir.file("zero.png"), cv::Mat(480, 640, CV_16UC1, cv::Scalar(0)));
  expect_bad_input({"loops", dir.file("zero.png"), "--camera", cam}, "all pixels are 0");
  cv::imwrite(dir.file("eight.png"), cv::Mat(480, 640, CV_8UC1, cv::Scalar(9)));
  expect_bad_input({"loops", dir.file("eight.png"), "--camera", cam}, "16-bit");
  std::string png = slurp(files[0].first);
  expect_bad_input({"loops", dir.write("cut.png", png.substr(0, png.size() / 3)), "--camera", cam},
                   "decode");
  expect_bad_input({"loops", files[0].first, "--camera", dir.write("c.yaml", "fx: 1\n")},
                   "missing key");
  expect_bad_input({"loops", dir.file("torus.ply"), "--points", "abc"}, "--points");
  expect_bad_input({"loops", dir.file("torus.ply"), "--min-hole", "-1"}, "--min-hole");
  expect_bad_input({"loops", dir.file("torus.ply"), "--view", "1,2"}, "--view");
  // With --json the error is also one JSON object on stdout.
  const CliResult r = run_cli({"loops", dir.file("missing.pcd"), "--json"});
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_EQ(r.json()["exit_code"], 2);
}

}  // namespace
}  // namespace claspplan::test
