// The paper's experiments from the committed depth files (examples/depth/, issue 10):
// `claspplan loops` finds the paper's loop count on every scene, and every generated scenario
// parses, loads its depth files, and its `clasp: near:` picks the loop the paper clasps.
#include "examples/paper_scenes.hpp"

#include <filesystem>
#include <fstream>

#include <gtest/gtest.h>

#include "examples/scenario.hpp"
#include "robots/hand_size.hpp"
#include "test/support/cli_runner.hpp"
#include "tsrrt/clasp_scene.hpp"

namespace claspplan::test {
namespace {

namespace fs = std::filesystem;
using nlohmann::json;

const std::string kDepth = std::string(CLASPPLAN_SCENARIOS) + "/../depth";

json scene_file(const std::string& scene) {
  std::ifstream in(kDepth + "/" + scene + "/scene.json");
  return json::parse(in);
}

Eigen::Vector3d point(const json& v) {
  return Eigen::Vector3d(v[0].get<double>(), v[1].get<double>(), v[2].get<double>());
}

double distance(const json& a, const Eigen::Vector3d& b) {
  return (point(a) - b).norm();
}

class PaperScene : public ::testing::TestWithParam<std::string> {};

// The loop count of Fig. 3 among the stable and among the claspable loops seen from the three
// views; the loop nearest the clasped hole is claspable.
TEST_P(PaperScene, LoopsFindsThePapersLoops) {
  const std::string dir = kDepth + "/" + GetParam();
  const json scene = scene_file(GetParam());
  const auto& w = scene["workspace"];
  std::string crop;
  for (const char* end : {"min", "max"})
    for (int k = 0; k < 3; ++k)
      crop += (crop.empty() ? "" : ",") + std::to_string(w[end][k].get<double>());
  std::vector<std::string> args = {"loops"};
  for (const auto& v : scene["views"]) {
    args.push_back(dir + "/" + v["image"].get<std::string>());
    args.push_back("--camera");
    args.push_back(dir + "/" + v["camera"].get<std::string>());
  }
  for (const char* a : {"--robot", "kr5_sdh", "--json"}) args.push_back(a);
  args.push_back("--crop=" + crop);
  const CliResult r = run_cli(args);
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const json out = r.json();
  // Claspable, or refused only for what the cameras did not see (issue 33: the upright chairs'
  // loops under the seat lie partly in its shadow).
  int found = 0;
  for (const auto& l : out["loops"])
    found += l["claspable"].get<bool>() || l["verdict"] == "unseen_far_side";
  // The chair on its side: the loop of the face it lies on is refused for a hand (its stretcher
  // and legs on the floor leave no bar to close around).
  const int on_floor = GetParam() == "chair_3" ? 1 : 0;
  // With the third view, one of the upright chair's 7 loops fills in at d' (chair_1, chair_2).
  const int merged = GetParam() == "chair_1" || GetParam() == "chair_2" ? 1 : 0;
  EXPECT_GE(found, scene["loops"].get<int>() - on_floor - merged);
  EXPECT_GE(out["stable_loops"].get<int>(), scene["loops"].get<int>() - merged);
  const Eigen::Vector3d near = point(scene["near"]);
  const json* nearest = nullptr;
  for (const auto& l : out["loops"])
    if (!nearest || distance(l["centre"], near) < distance((*nearest)["centre"], near))
      nearest = &l;
  ASSERT_NE(nearest, nullptr);
  EXPECT_LT(distance((*nearest)["centre"], near), 0.12);  // the chair's loops are 30-40 cm wide
  // (Fig. 7's loop under the obstructed chair's seat is seen through only with its fourth view,
  // from the side below the seat: the seat shades the space beyond it from the other three.)
  EXPECT_TRUE((*nearest)["claspable"].get<bool>()) << (*nearest)["reason"];
}

INSTANTIATE_TEST_SUITE_P(Depth, PaperScene, ::testing::ValuesIn(cli::paper_scene_names()));

class PaperScenario : public ::testing::TestWithParam<std::string> {};

// Every scenario of a scene parses and loads its depth files; for each hand, the loop its
// `clasp: near:` chooses is the one whose hole is at that point (no other loop's centre nearer).
TEST_P(PaperScenario, NearChoosesTheClaspedLoop) {
  for (const std::string hand : {"sdh", "dlr", "icub", "armar3"}) {
    const std::string file =
        std::string(CLASPPLAN_SCENARIOS) + "/" + GetParam() + "_" + hand + ".yaml";
    if (GetParam() == "purse_1") continue;  // the hand-written purse_1 renders at run time
    const cli::Scenario s = cli::load_scenario(file);
    ASSERT_EQ(s.object.depth.size(), GetParam() == "chair_obstructed" ? 4u : 3u) << file;
    ASSERT_TRUE(s.loop_hint) << file;
    const perception::PerceptionInputs in = cli::scenario_inputs(s);
    ASSERT_EQ(in.depth_views.size(), s.object.depth.size());
    perception::PerceptionOptions o = s.perception;
    const robots::HandSize size = robots::hand_size(robots::load_robot(s.robot));
    o.finger_thickness = size.finger_thickness;
    o.closed_aperture = size.closed_aperture;
    const perception::ObjectModel model = perception::build_object_model(in, o);
    const int chosen = tsrrt::choose_loop(model, s.loop_hint);
    ASSERT_GE(chosen, 0) << file;
    const double d = (model.loops[chosen].centre - *s.loop_hint).norm();
    EXPECT_LT(d, 0.12) << file;  // the chair's loops are 30-40 cm wide
    for (const auto& l : model.loops) {
      if (!l.claspable) continue;
      EXPECT_GE((l.centre - *s.loop_hint).norm(), d) << file;
    }
  }
}

INSTANTIATE_TEST_SUITE_P(Depth, PaperScenario, ::testing::ValuesIn(cli::paper_scene_names()));

// The committed depth files are what `claspplan render-paper` writes today (regenerated by
// examples/scripts/paper_examples.sh): same camera files, same image sizes.
TEST(PaperDepthFiles, MatchTheRenderer) {
  TempDir tmp;
  const CliResult r = run_cli({"render-paper", tmp.file("d"), "--scene", "purse_2", "--json"});
  ASSERT_EQ(r.exit_code, 0) << r.err;
  for (const std::string f : {"view_0.yaml", "view_1.yaml", "scene.json"}) {
    std::ifstream a(tmp.file("d") + "/purse_2/" + f), b(kDepth + "/purse_2/" + f);
    const std::string ta((std::istreambuf_iterator<char>(a)), {}),
        tb((std::istreambuf_iterator<char>(b)), {});
    EXPECT_EQ(ta, tb) << f;
  }
  EXPECT_EQ(fs::file_size(tmp.file("d") + "/purse_2/view_0.png"),
            fs::file_size(kDepth + "/purse_2/view_0.png"));
}

}  // namespace
}  // namespace claspplan::test
