// Loop choice for a hand (issue "Real objects"): a container's mouth is never a clasp, a jug's
// handle is chosen by every hand, and a hole narrower than a hand's fingers is refused with the
// reason, in the library and in `claspplan loops --robot`.
#include <gtest/gtest.h>

#include "core/file_io.hpp"
#include "examples/objects.hpp"
#include "examples/scenario.hpp"
#include "perception/depth_render.hpp"
#include "perception/pipeline.hpp"
#include "robots/hand_size.hpp"
#include "test/support/cli_runner.hpp"
#include "test/support/floor_scene.hpp"

namespace claspplan::test {
namespace {

const std::vector<std::string> kHands = {"sdh", "dlr", "icub", "armar3"};

perception::ObjectModel perceive(const perception::PerceptionInputs& in, const std::string& hand) {
  perception::PerceptionOptions o;
  o.workspace = floor_workspace();
  if (!hand.empty()) {
    const robots::HandSize size = robots::hand_size(robots::load_robot("kr5_" + hand));
    o.finger_thickness = size.finger_thickness;
    o.closed_aperture = size.closed_aperture;
  }
  return perception::build_object_model(in, o);
}

objects::Container jug() {
  objects::Container c;
  c.radius = 0.06;
  c.height = 0.22;
  c.handle_radius = 0.075;
  c.handle_tube = 0.01;
  return c;
}

TEST(LoopChoice, CupMouthIsRejectedForEveryHand) {
  objects::Container cup;
  cup.radius = 0.05;
  cup.height = 0.12;
  const auto in = seen_on_floor(objects::container(cup));
  for (const std::string& hand : kHands) {
    const perception::ObjectModel m = perceive(in, hand);
    EXPECT_EQ(m.best(), nullptr) << hand << ": " << (m.loops.empty() ? "" : m.loops[0].reason);
    EXPECT_TRUE(m.targets.empty()) << hand;
  }
}

TEST(LoopChoice, JugHandleIsChosenAndItsMouthRejectedForEveryHand) {
  const objects::Container c = jug();
  // The handle towards +y, its hole facing the cameras.
  const auto in = seen_on_floor(objects::container(c), M_PI / 2);
  const Eigen::Vector3d handle =
      Eigen::Vector3d(0.55, 0, 0) +
      Eigen::AngleAxisd(M_PI / 2, Eigen::Vector3d::UnitZ()) * objects::container_handle_centre(c);
  for (const std::string& hand : kHands) {
    const perception::ObjectModel m = perceive(in, hand);
    ASSERT_NE(m.best(), nullptr) << hand;
    EXPECT_LT((m.best()->centre - handle).norm(), 0.04) << hand << ": " << m.best()->reason;
    // The mouth was found and refused (a cavity's opening, enclosed or unseen space beyond it,
    // or the loop around its wall).
    bool mouth = false;
    for (const auto& l : m.loops) mouth |= !l.claspable && l.centre.z() > 0.18;
    std::string verdicts;
    for (const auto& l : m.loops)
      verdicts += " [" + std::string(perception::verdict_name(l.verdict)) + " z " +
                  std::to_string(l.centre.z()) + "]";
    EXPECT_TRUE(mouth) << hand << verdicts;
    // Targets lie on the handle, where the closed hand fits around it.
    ASSERT_FALSE(m.targets.empty());
    for (const auto& t : m.targets) EXPECT_GT(t.point.y(), 0.055) << hand;
  }
}

// The shipped pitcher (examples/meshes, YCB) turned so that both cameras see its handle's front
// only: the handle's back is hidden, yet its bar is measured and it is the iCub's loop (its hole,
// 3 cm, is too narrow for the other hands' fingers). At 2,000 points the hole is near the
// resolution (d' = 2.2 cm): at one of the scenario's seeds 1-4 (seed 2) it fills in at d' and is
// dropped as unstable; the test asks for 3 of 4.
TEST(LoopChoice, AHandleSeenFromTheFrontOnlyIsMeasuredAndChosen) {
  cli::Scenario s =
      cli::load_scenario(std::string(CLASPPLAN_SCENARIOS) + "/real/pitcher_icub.yaml");
  const robots::HandSize size = robots::hand_size(robots::load_robot(s.robot));
  int chosen = 0;
  for (unsigned seed = 1; seed <= 4; ++seed) {
    s.seed = seed;
    perception::PerceptionOptions o = s.perception;
    o.seed = seed;
    o.finger_thickness = size.finger_thickness;
    o.closed_aperture = size.closed_aperture;
    const perception::ObjectModel m = perception::build_object_model(cli::scenario_inputs(s), o);
    const perception::Loop* best = m.best();
    if (best == nullptr) continue;
    EXPECT_GT(best->centre.z(), 0.12) << seed;  // the handle is on the pitcher's upper half
    EXPECT_LT(best->bar_thickness, 0.03) << seed;
    ++chosen;
  }
  EXPECT_GE(chosen, 3);
}

// The pitcher on a table with a box 6 cm behind it (conditions/): the box takes its share of the
// 2,000 points, d' grows to 3.5 cm and fills the handle's 3 cm hole. The second pass, each object
// sampled as if alone (pipeline.hpp, step 7), keeps it: the handle is the iCub's loop again.
TEST(LoopChoice, AHandleBesideASecondObjectIsFoundWithEachObjectSampledAlone) {
  cli::Scenario s =
      cli::load_scenario(std::string(CLASPPLAN_SCENARIOS) + "/conditions/pitcher_yaw0_icub.yaml");
  const robots::HandSize size = robots::hand_size(robots::load_robot(s.robot));
  perception::PerceptionOptions o = s.perception;
  o.finger_thickness = size.finger_thickness;
  o.closed_aperture = size.closed_aperture;
  o.per_object_pass = false;
  const perception::PerceptionInputs in = cli::scenario_inputs(s);
  const perception::ObjectModel first = perception::build_object_model(in, o);
  EXPECT_EQ(first.best(), nullptr);
  o.per_object_pass = true;
  const perception::ObjectModel m = perception::build_object_model(in, o);
  EXPECT_EQ(m.objects, 2);
  ASSERT_NE(m.best(), nullptr) << m.loops.size();
  EXPECT_LT(m.persistence_d, first.persistence_d);
  EXPECT_GT(m.best()->centre.z(), 0.10 + 0.12);  // on the pitcher's upper half, above the table
  EXPECT_LT(m.best()->bar_thickness, 0.03);
  EXPECT_NE(m.d_rule.find("each of 2 objects sampled alone"), std::string::npos) << m.d_rule;
  // Twice the points may give more loops than K_d allows (homology max_beta1): the second pass
  // then stops and the first pass's result stands, rather than a valid input's becoming an error.
  ASSERT_GT(m.beta1, first.beta1 + 1);
  o.homology.max_beta1 = first.beta1 + 1;
  perception::ObjectModel capped;
  ASSERT_NO_THROW(capped = perception::build_object_model(in, o));
  EXPECT_EQ(capped.best(), nullptr);
  EXPECT_EQ(capped.beta1, first.beta1);
}

// Holes through a 19 cm block, like a cinder block's cores: from above, a core's rim shows a thin
// top face and hides the wall below it. The top face is never taken for a bar a hand closes on.
TEST(LoopChoice, AWallSeenFromItsTopIsNotABar) {
  objects::HoledPlate block;
  block.holes = 2;
  block.hole_radius = 0.05;
  block.thickness = 0.19;
  block.margin = 0.03;
  const auto in = seen_on_floor(objects::holed_plate(block));
  for (const std::string& hand : kHands) {
    for (const auto& l : perceive(in, hand).loops)
      EXPECT_TRUE(!l.claspable || l.bar_thickness > 0.09) << hand << ": " << l.reason;
  }
}

TEST(LoopChoice, HandSizesComeFromTheModel) {
  const robots::HandSize sdh = robots::hand_size(robots::load_robot("kr5_sdh"));
  const robots::HandSize icub = robots::hand_size(robots::load_robot("kr5_icub"));
  EXPECT_NEAR(sdh.finger_thickness, 0.029, 1e-9);  // the SDH fingers' capsules, radius 14.5 mm
  EXPECT_LT(icub.finger_thickness, sdh.finger_thickness);
  EXPECT_GT(sdh.closed_aperture, 0.03);
  EXPECT_LT(icub.closed_aperture, sdh.closed_aperture);
}

TEST(LoopChoice, MorePointsNeverMeanMoreLoops) {
  const auto in = seen_on_floor(objects::purse());
  std::vector<int> loops;
  for (int n : {2000, 10000, 40000}) {
    perception::PerceptionOptions o;
    o.points = n;
    o.workspace = floor_workspace();
    const perception::ObjectModel m = perception::build_object_model(in, o);
    int claspable = 0;
    for (const auto& l : m.loops) claspable += l.claspable;
    EXPECT_EQ(claspable, 1) << n << " points";
    loops.push_back(static_cast<int>(m.loops.size()));
  }
  EXPECT_LE(loops[1], loops[0]);
  EXPECT_LE(loops[2], loops[0]);
}

// A torus (centre-line radius R, tube radius r) standing upright in front of the robot, its hole
// facing x, written as an OBJ file in `dir`.
std::string upright_ring(TempDir& dir, double R, double r) {
  Eigen::Isometry3d pose = Eigen::Isometry3d::Identity();
  pose.translate(Eigen::Vector3d(0.55, 0, 0.2));
  pose.rotate(Eigen::AngleAxisd(M_PI / 2, Eigen::Vector3d::UnitY()));
  const std::string mesh = dir.file("ring.obj");
  write_obj(objects::torus_mesh(R, r, pose), mesh);
  return mesh;
}

// `claspplan loops MESH --robot ROBOT --json`.
nlohmann::json loops_for(const std::string& mesh, const std::string& robot) {
  const CliResult r = run_cli({"loops", mesh, "--robot", robot, "--json"});
  EXPECT_EQ(r.exit_code, 0) << r.err;
  return nlohmann::json::parse(r.out);  // throws (a test failure) when there is no JSON
}

TEST(LoopChoice, LoopsRobotRefusesAHoleNarrowerThanTheFingers) {
  TempDir dir;
  // A ring whose hole (30 mm) admits the iCub's fingers (14 mm + 13) but not the SDH's (29 mm).
  const std::string mesh = upright_ring(dir, 0.021, 0.006);
  const auto sdh = loops_for(mesh, "kr5_sdh");
  bool refused = false;
  for (const auto& l : sdh["loops"]) {
    if (l["verdict"] == "hand_too_large") {
      refused = true;
      EXPECT_NE(l["reason"].get<std::string>().find("too narrow for this hand"), std::string::npos);
    }
    EXPECT_FALSE(l["claspable"].get<bool>());
  }
  EXPECT_TRUE(refused);
  EXPECT_NEAR(sdh["hand"]["finger_thickness"].get<double>(), 0.029, 1e-6);
  bool icub_claspable = false;
  const auto icub = loops_for(mesh, "kr5_icub");
  for (const auto& l : icub["loops"]) icub_claspable |= l["claspable"].get<bool>();
  EXPECT_TRUE(icub_claspable);
}

TEST(LoopChoice, LoopsRobotWantsRoomBesideTheFingers) {
  TempDir dir;
  // A ring with a 26 mm hole: 12 mm wider than the iCub's fingers, short of the 13 mm it needs.
  const std::string mesh = upright_ring(dir, 0.019, 0.006);
  const auto icub = loops_for(mesh, "kr5_icub");
  ASSERT_FALSE(icub["loops"].empty());
  for (const auto& l : icub["loops"]) EXPECT_FALSE(l["claspable"].get<bool>()) << l["reason"];
  const auto& ring = icub["loops"][0];
  EXPECT_EQ(ring["verdict"], "hand_too_large");
  EXPECT_GT(ring["hole_width"].get<double>(), 0.014 + 0.010);  // the old margin let it through
  EXPECT_NE(ring["reason"].get<std::string>().find("+ 1.3 cm"), std::string::npos)
      << ring["reason"];
}

TEST(LoopChoice, LoopsRobotWantsRoomAroundTheBar) {
  TempDir dir;
  // A ring of a 4.7 cm thick bar: inside the iCub's closed aperture (5.3 cm) but not 1 cm inside
  // it; well inside the DLR hand's (10.8 cm).
  const std::string mesh = upright_ring(dir, 0.05, 0.0235);
  // The surface's other loop, around the tube, is a tube wall for every hand.
  const auto around_hole = [&](const std::string& robot) {
    const auto j = loops_for(mesh, robot);
    for (const auto& l : j["loops"])
      if (l["verdict"] != "tube_wall") return l;
    return nlohmann::json();
  };
  const auto icub = around_hole("kr5_icub");
  ASSERT_FALSE(icub.is_null());
  EXPECT_EQ(icub["verdict"], "bar_too_thick") << icub["reason"];
  EXPECT_LT(icub["bar_thickness"].get<double>(), 0.0529);  // the old rule let it through
  EXPECT_NE(icub["reason"].get<std::string>().find("less 1 cm"), std::string::npos);
  const auto dlr = around_hole("kr5_dlr");
  ASSERT_FALSE(dlr.is_null());
  EXPECT_TRUE(dlr["claspable"].get<bool>()) << dlr["reason"];
}

}  // namespace
}  // namespace claspplan::test
