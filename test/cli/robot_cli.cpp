// `claspplan robot` as a user runs it: joints, tool0 and finger curves; bad input is exit 2.
#include <algorithm>
#include <cmath>
#include <filesystem>
#include <string>

#include <gtest/gtest.h>

#include "robots/embedded_models.hpp"
#include "test/support/cli_runner.hpp"

namespace claspplan::test {
namespace {

TEST(RobotCli, BuiltinRobotsAsJson) {
  const std::vector<std::pair<std::string, int>> robots = {
      {"kr5_sdh", 6}, {"kr5_dlr", 12}, {"kr5_icub", 15}, {"kr5_armar3", 10}};
  const std::vector<size_t> curve_counts = {2, 3, 4, 4};
  for (size_t r = 0; r < robots.size(); ++r) {
    const CliResult out = run_cli({"robot", robots[r].first, "--json"});
    ASSERT_EQ(out.exit_code, 0) << out.err;
    const auto j = out.json();
    ASSERT_EQ(j["joints"].size(), 6u + robots[r].second);
    int hand = 0;
    for (const auto& joint : j["joints"]) {
      EXPECT_TRUE(joint.contains("name"));
      EXPECT_LE(joint["lower"].get<double>(), joint["upper"].get<double>());
      hand += joint["hand"].get<bool>();
    }
    EXPECT_EQ(hand, robots[r].second);
    EXPECT_EQ(j["joints"][0]["name"], "joint_a1");
    EXPECT_FALSE(j["joints"][0]["hand"].get<bool>());
    // HOME: tool0 at (0.560, 0, 0.790), its z axis along world x.
    const auto p = j["tool0"]["position"];
    EXPECT_NEAR(p[0].get<double>(), 0.560, 1e-3);
    EXPECT_NEAR(p[1].get<double>(), 0.0, 1e-3);
    EXPECT_NEAR(p[2].get<double>(), 0.790, 1e-3);
    ASSERT_EQ(j["tool0"]["rotation"].size(), 3u);
    EXPECT_NEAR(j["tool0"]["rotation"][0][2].get<double>(), 1.0, 1e-9);
    ASSERT_EQ(j["finger_curves"].size(), curve_counts[r]);
    for (const auto& curve : j["finger_curves"]) {
      EXPECT_GE(curve.size(), 7u);
      for (const auto& point : curve) EXPECT_EQ(point.size(), 3u);
    }
    EXPECT_FALSE(j["self_collision"].get<bool>());
  }
}

TEST(RobotCli, QOverridesAPrefix) {
  const CliResult zero = run_cli({"robot", "kr5_sdh", "--q=0,0,0,0,0,0", "--json"});
  ASSERT_EQ(zero.exit_code, 0) << zero.err;
  const auto p = zero.json()["tool0"]["position"];
  EXPECT_NEAR(p[0].get<double>(), 0.925, 1e-3);
  EXPECT_NEAR(p[2].get<double>(), 0.425, 1e-3);
  // The hand keeps its open pre-shape (finger_12_joint = -1).
  EXPECT_DOUBLE_EQ(zero.json()["q"][6].get<double>(), -1.0);
  // Degrees of the facts' 4th pose, in radians, with a leading minus after a space.
  const double d = M_PI / 180;
  std::string q;
  for (double v : {30.0, -60.0, 100.0, 20.0, 40.0, 10.0})
    q += (q.empty() ? "" : ",") + std::to_string(v * d);
  const CliResult posed = run_cli({"robot", "kr5_icub", "--q", q, "--json"});
  ASSERT_EQ(posed.exit_code, 0) << posed.err;
  const auto t = posed.json()["tool0"]["position"];
  EXPECT_NEAR(t[0].get<double>(), 0.5467, 1e-3);
  EXPECT_NEAR(t[1].get<double>(), -0.3360, 1e-3);
  EXPECT_NEAR(t[2].get<double>(), 0.3833, 1e-3);
  // The human summary lists the joints and curves.
  const CliResult human = run_cli({"robot", "kr5_armar3"});
  EXPECT_EQ(human.exit_code, 0);
  EXPECT_NE(human.out.find("thumb_j1"), std::string::npos);
  EXPECT_NE(human.out.find("finger curve index-thumb"), std::string::npos);
}

TEST(RobotCli, DescriptionFileFromAnyFolder) {
  TempDir dir;
  dir.write("kr5_sdh.urdf", robots::embedded_model_file("kr5_sdh.urdf"));
  const std::string yaml = dir.write("my_robot.yaml", robots::embedded_model_file("kr5_sdh.yaml"));
  const CliResult r = run_cli({"robot", yaml, "--json"});
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_EQ(r.json()["joints"].size(), 12u);
}

// What the hand can clasp: the narrowest hole its fingers take and the thickest bar it closes
// around, from the same rules that rank loops; a finger link thicker than 4 cm is warned of.
TEST(RobotCli, PrintsTheHandsClaspRange) {
  const CliResult icub = run_cli({"robot", "kr5_icub", "--json"});
  ASSERT_EQ(icub.exit_code, 0) << icub.err;
  const auto hand = icub.json()["hand"];
  const double thickness = hand["finger_thickness"].get<double>();
  EXPECT_NEAR(thickness, 0.014, 0.002);
  EXPECT_NEAR(hand["narrowest_hole"].get<double>(), thickness + 0.013, 1e-9);
  EXPECT_NEAR(hand["widest_bar"].get<double>(), hand["closed_aperture"].get<double>() - 0.01, 1e-9);
  EXPECT_EQ(hand["warning"], "");
  const CliResult human = run_cli({"robot", "kr5_icub"});
  EXPECT_NE(human.out.find("clasps holes from 2.7 cm wide and bars up to 4.3 cm thick"),
            std::string::npos)
      << human.out;

  TempDir dir;
  std::string urdf = robots::embedded_model_file("kr5_sdh.urdf");
  const std::string finger = "<cylinder radius=\"0.0145\" length=\"0.0865\"/>";
  urdf.replace(urdf.find(finger), finger.size(), "<box size=\"0.05 0.03 0.0865\"/>");
  dir.write("kr5_sdh.urdf", urdf);
  const std::string yaml = dir.write("thick.yaml", robots::embedded_model_file("kr5_sdh.yaml"));
  const CliResult thick = run_cli({"robot", yaml, "--json"});
  ASSERT_EQ(thick.exit_code, 0) << thick.err;
  const std::string warning = thick.json()["hand"]["warning"].get<std::string>();
  EXPECT_NE(warning.find("finger thickness 5.8 cm comes from link 'finger_12_link'"),
            std::string::npos)
      << warning;
}

// --start-above prints a start to paste into a scenario; none is exit 1 with the reason.
TEST(RobotCli, FindsAStartAboveAPoint) {
  const CliResult r = run_cli({"robot", "kr5_icub", "--start-above=0.5,0,0.1", "--json"});
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const auto start = r.json()["start"];
  ASSERT_EQ(start["q"].size(), 6u);
  EXPECT_LE(start["position_error"].get<double>(), 0.005);
  EXPECT_NEAR(r.json()["tcp"][2].get<double>(), 0.35, 0.005);
  EXPECT_FALSE(r.json()["self_collision"].get<bool>());
  const CliResult human = run_cli({"robot", "kr5_icub", "--start-above=0.5,0,0.1"});
  EXPECT_NE(human.out.find("\nstart: ["), std::string::npos) << human.out;
  const CliResult far = run_cli({"robot", "kr5_icub", "--start-above=3,0,0"});
  EXPECT_EQ(far.exit_code, 1);
  EXPECT_NE(far.err.find("no start with the tcp 0.250 m above (3, 0, 0)"), std::string::npos)
      << far.err;
}

void expect_bad(const std::vector<std::string>& args, const std::string& reason_piece) {
  const CliResult r = run_cli(args);
  std::string all;
  for (const auto& a : args) all += a + " ";
  EXPECT_EQ(r.exit_code, 2) << all << ": " << r.out << r.err;
  EXPECT_EQ(std::count(r.err.begin(), r.err.end(), '\n'), 1) << all << ": " << r.err;
  EXPECT_NE(r.err.find("claspplan: error: "), std::string::npos) << all << ": " << r.err;
  EXPECT_NE(r.err.find(reason_piece), std::string::npos) << all << ": " << r.err;
}

TEST(RobotCli, BadQIsExitTwo) {
  expect_bad({"robot", "kr5_sdh", "--start-above=0.5,0"}, "--start-above: expected x,y,z");
  expect_bad({"robot", "kr5_sdh", "--start-above=0.5,0,0", "--q=0"}, "excludes");
  expect_bad({"robot", "kr5_sdh", "--q=0,abc"}, "'abc' is not a number");
  expect_bad({"robot", "kr5_sdh", "--q=0,,1"}, "value 2 is empty");
  expect_bad({"robot", "kr5_sdh", "--q=0,nan"}, "not finite");
  expect_bad({"robot", "kr5_sdh", "--q=0,1e999"}, "not a number");
  expect_bad({"robot", "kr5_sdh", "--q=1,2,"}, "expected comma-separated");
  expect_bad({"robot", "kr5_sdh", "--q=0,1.0"}, "joint_a2 = 1 is outside its limits");
  expect_bad({"robot", "kr5_sdh", "--q=0,0,0,0,0,0,0,0,0,0,0,0,0"}, "12 actuated joints, got 13");
  const CliResult j = run_cli({"robot", "kr5_sdh", "--q=x", "--json"});
  EXPECT_EQ(j.exit_code, 2);
  EXPECT_EQ(j.json()["exit_code"], 2);
}

TEST(RobotCli, BadDescriptionFilesAreExitTwo) {
  TempDir dir;
  const std::string urdf = robots::embedded_model_file("kr5_sdh.urdf");
  const std::string yaml = robots::embedded_model_file("kr5_sdh.yaml");
  auto with = [](std::string text, const std::string& from, const std::string& to) {
    const size_t at = text.find(from);
    EXPECT_NE(at, std::string::npos) << from;
    if (at != std::string::npos) text.replace(at, from.size(), to);
    return text;
  };
  struct Case {
    std::string name, yaml, urdf, reason;
  };
  const std::vector<Case> cases = {
      {"missing_link", yaml, with(urdf, "<link name=\"thumb_3_tip\"/>", ""), "not a valid URDF"},
      {"truncated_xml", yaml, urdf.substr(0, 3000), "not a valid URDF"},
      {"unknown_joint", with(yaml, "name: thumb_2_joint", "name: thumb_9_joint"), urdf,
       "unknown joint 'thumb_9_joint'"},
      {"unknown_link", with(yaml, "{link: thumb_3_tip}", "{link: thumb_tip}"), urdf,
       "unknown link 'thumb_tip'"},
      {"malformed_yaml", "name: kr5\nurdf: [x\n", urdf, "malformed YAML"},
      {"empty_curve",
       yaml.substr(0, yaml.find("    - name: finger_2-thumb")) +
           "    - name: finger_2-thumb\n      points: []\n" + yaml.substr(yaml.find("  tcp:")),
       urdf, "hand.curves[1].points: a finger curve needs at least 3 points"},
  };
  for (const Case& c : cases) {
    const std::string folder = c.name + "/";
    std::filesystem::create_directories(dir.path() / c.name);
    dir.write(folder + "kr5_sdh.urdf", c.urdf);
    const std::string path = dir.write(folder + "my.yaml", c.yaml);
    expect_bad({"robot", path}, c.reason);
  }
  expect_bad({"robot", dir.file("missing.yaml")}, "neither a built-in robot");
  expect_bad({"robot", "kr5_nothing"}, "kr5_sdh");
  EXPECT_EQ(run_cli({"robot"}).exit_code, 2);
}

TEST(RobotCli, HelpIsAvailable) {
  const CliResult r = run_cli({"robot", "--help"});
  EXPECT_EQ(r.exit_code, 0);
  EXPECT_NE(r.out.find("--q"), std::string::npos);
}

}  // namespace
}  // namespace claspplan::test
