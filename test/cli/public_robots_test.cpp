// Public robots used as they are (examples/robots/, issue 35): a UR5, a Panda (7 joints) and a
// Jaco (continuous joints, COLLADA meshes as hulls), each with the 16-joint Allegro hand from its
// own URDF, load from their unmodified URDFs and plan verified clasps of the purse, the jug and
// the bag; the ring placed in front of the hand is verified for every shipped robot.
#include <string>

#include <gtest/gtest.h>

#include "test/support/cli_runner.hpp"
#include "test/support/temp_dir.hpp"

namespace claspplan::test {
namespace {

const std::string kRobots = CLASPPLAN_ROBOTS;
const std::string kUr5Allegro = kRobots + "/ur5_allegro.yaml";

struct PublicRobot {
  std::string name;
  int arm_dof, meshes;
};

class PublicRobots : public ::testing::TestWithParam<PublicRobot> {};

TEST_P(PublicRobots, LoadFromTheirUnmodifiedUrdfs) {
  const CliResult r = run_cli({"robot", kRobots + "/" + GetParam().name + ".yaml", "--json"});
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const auto j = r.json();
  EXPECT_EQ(j["arm_dof"].get<int>(), GetParam().arm_dof);
  EXPECT_EQ(j["hand_dof"].get<int>(), 16);
  EXPECT_EQ(j["mesh_shapes"].get<int>(), GetParam().meshes);  // the arm's links
  EXPECT_TRUE(j["warnings"].empty());
  EXPECT_FALSE(j["self_collision"].get<bool>());
  EXPECT_GT(j["hand"]["closed_aperture"].get<double>(), 0.03);
}

// Bounded by cycles, so that the outcome does not depend on the machine. One seed of the bench
// (`bench examples/robots/scenarios/{jug,purse_1,bag_2}_{ur5,panda,jaco}_allegro.yaml --seeds 4
// --max-cycles 100`: 34 of 36 verified, the UR5's jug at seeds 1 and 4 not).
TEST_P(PublicRobots, ClaspThePurseTheJugAndTheBag) {
  TempDir dir;
  for (const char* object : {"purse_1", "jug", "bag_2"}) {
    const std::string scenario = kRobots + "/scenarios/" + object + "_" + GetParam().name + ".yaml";
    const CliResult r = run_cli({"run", scenario, "--seed", "2", "--max-cycles", "100",
                                 "--no-pictures", "--out", dir.file(object), "--json"});
    ASSERT_EQ(r.exit_code, 0) << object << ": " << r.out << r.err;
    EXPECT_TRUE(r.json()["verified"].get<bool>()) << object;
  }
}

INSTANTIATE_TEST_SUITE_P(ArmsWithTheAllegroHand, PublicRobots,
                         ::testing::Values(PublicRobot{"ur5_allegro", 6, 7},
                                           PublicRobot{"panda_allegro", 7, 8},
                                           PublicRobot{"jaco_allegro", 6, 7}),
                         [](const auto& info) { return info.param.name; });

// The first check of any robot: a ring placed from the hand's own tcp, v_fwd and v_swd
// (object.in_front_of_hand), planned and verified, and clasped by the controller alone. The
// built-in hands reach their linking goal untouched; the Allegro's thumb, which sweeps wider than
// the bar, touches it inside the goal region, and the fingers closed there hold the ring.
TEST(ShippedRobots, VerifyTheRingInFrontOfTheHand) {
  TempDir dir;
  const std::string robots[] = {"kr5_sdh",
                                "kr5_dlr",
                                "kr5_icub",
                                "kr5_armar3",
                                kUr5Allegro,
                                kRobots + "/panda_allegro.yaml",
                                kRobots + "/jaco_allegro.yaml",
                                kRobots + "/drafted/ur5_allegro.yaml",
                                kRobots + "/drafted/panda_allegro.yaml",
                                kRobots + "/drafted/jaco_allegro.yaml"};
  for (const std::string& robot : robots) {
    const bool builtin = robot.rfind("kr5_", 0) == 0;
    const std::string start = builtin ? "start: [0, -1.5707963, 1.5707963, 0, 1.5707963, 0]\n" : "";
    const std::string path =
        dir.write("ring.yaml", "robot: " + robot + "\n" + start +
                                   "object:\n"
                                   "  shape: {type: torus, major_radius: 0.1, minor_radius: 0.01}\n"
                                   "  in_front_of_hand: 0.3\n");
    const CliResult r = run_cli({"run", path, "--max-cycles", "100", "--no-pictures", "--out",
                                 dir.file("ring_out"), "--json"});
    EXPECT_EQ(r.exit_code, 0) << robot << ": " << r.out << r.err;
    const CliResult c = run_cli({"run", path, "--controller-only", "--no-pictures", "--out",
                                 dir.file("controller_out"), "--json"});
    ASSERT_EQ(c.exit_code, 0) << robot << ": " << c.out << c.err;
    const auto j = c.json();
    EXPECT_TRUE(j["success"].get<bool>()) << robot;
    EXPECT_EQ(j["collided"].get<bool>(), !builtin) << robot;
    // Closed after a touch, it is verified; untouched, no check runs (the paper's test).
    EXPECT_EQ(j.value("verified", false), !builtin) << robot;
    const auto result = nlohmann::json::parse(slurp(dir.file("controller_out/result.json")));
    EXPECT_EQ(result.contains("verification"), !builtin) << robot;
  }
}

// `claspplan describe` on the UR5's and the Allegro hand's unmodified URDFs: the drafted
// description, unedited, loads, finds the Allegro's thumb and turns it to oppose the fingers, and
// its ring is verified; the committed drafts (examples/robots/drafted/) clasp the purse.
TEST(DescribeCommand, DraftsARobotThatClaspsTheRingUnedited) {
  TempDir dir;
  const std::string urdfs = kRobots + "/example-robot-data/robots/";
  const std::string out = dir.file("ur5_allegro.yaml");
  const CliResult d =
      run_cli({"describe", urdfs + "ur_description/urdf/ur5_robot.urdf", "--hand-urdf",
               urdfs + "allegro_hand_description/urdf/allegro_right_hand.urdf", "--mount", "tool0",
               "--mount-xyz", "0,0,0.095", "--samples", "200", "-o", out, "--json"});
  ASSERT_EQ(d.exit_code, 0) << d.err;
  const auto j = d.json();
  EXPECT_EQ(j["arm_dof"].get<int>(), 6);
  EXPECT_EQ(j["hand_dof"].get<int>(), 16);
  ASSERT_EQ(j["fingers"].size(), 4u);
  int thumbs = 0;
  for (const auto& f : j["fingers"]) thumbs += f["thumb"].get<bool>();
  EXPECT_EQ(thumbs, 1);
  std::string guesses;
  for (const auto& g : j["guesses"]) guesses += g.get<std::string>() + "\n";
  EXPECT_NE(guesses.find("thumb: the finger of link_12.0"), std::string::npos) << guesses;
  EXPECT_NE(guesses.find("joint_12.0 held at"), std::string::npos) << guesses;
  EXPECT_GT(j["hand"]["closed_aperture"].get<double>(), 0.03);
  const std::string ring =
      dir.write("ring.yaml", "robot: " + out +
                                 "\nobject:\n"
                                 "  shape: {type: torus, major_radius: 0.1, minor_radius: 0.01}\n"
                                 "  in_front_of_hand: 0.3\n");
  const CliResult r = run_cli(
      {"run", ring, "--max-cycles", "100", "--no-pictures", "--out", dir.file("ring"), "--json"});
  EXPECT_EQ(r.exit_code, 0) << r.out << r.err;
  // The same inputs and seed draft the same file.
  const std::string again = dir.file("again.yaml");
  ASSERT_EQ(run_cli({"describe", urdfs + "ur_description/urdf/ur5_robot.urdf", "--hand-urdf",
                     urdfs + "allegro_hand_description/urdf/allegro_right_hand.urdf", "--mount",
                     "tool0", "--mount-xyz", "0,0,0.095", "--samples", "200", "-o", again})
                .exit_code,
            0);
  EXPECT_EQ(slurp(out), slurp(again));
}

TEST(DescribeCommand, TheCommittedDraftsClaspThePurse) {
  TempDir dir;
  for (const char* robot : {"ur5", "panda", "jaco"}) {
    const CliResult r =
        run_cli({"run", kRobots + "/scenarios/purse_1_" + robot + "_allegro.yaml", "--robot",
                 kRobots + "/drafted/" + robot + "_allegro.yaml", "--seed", "2", "--max-cycles",
                 "100", "--no-pictures", "--out", dir.file(robot), "--json"});
    EXPECT_EQ(r.exit_code, 0) << robot << ": " << r.out << r.err;
  }
}

// A public hand of one motor: Romeo's left hand (every finger joint mimics LHand, closed at 0),
// cut from the humanoid's unmodified URDF below its wrist and mounted on the Panda. The draft finds
// its four fingers through their mimic joints and opens the motor at its upper limit; with
// --adaptive the mimic joints are adaptive joints, so that each finger stops on its own, and its
// 8 mm wire ring is verified. The hand is small (2 cm inside when closed), so the purse's 2.4 cm
// strap is refused for that reason.
TEST(DescribeCommand, DraftsAOneMotorHandCutFromAHumanoid) {
  TempDir dir;
  const std::string urdfs = kRobots + "/example-robot-data/robots/";
  const std::string out = dir.file("panda_romeo.yaml");
  const CliResult d =
      run_cli({"describe", urdfs + "panda_description/urdf/panda.urdf", "--hand-urdf",
               urdfs + "romeo_description/urdf/romeo.urdf", "--hand-urdf-root", "l_wrist",
               "--mount", "panda_link8", "--mount-rpy", "0,-1.5707963,0", "--replaces",
               "panda_hand", "--adaptive", "--samples", "200",
               "--home=0,-0.785398,0,-2.356194,0,1.570796,0.785398", "-o", out, "--json"});
  ASSERT_EQ(d.exit_code, 0) << d.err;
  const auto j = d.json();
  EXPECT_EQ(j["arm_dof"].get<int>(), 7);
  EXPECT_EQ(j["hand_dof"].get<int>(), 12);  // LHand and the 11 joints that mimic it
  ASSERT_EQ(j["fingers"].size(), 4u);
  const std::string yaml = slurp(out);
  EXPECT_NE(yaml.find("{name: LHand, open: 1, closing: -1}"), std::string::npos) << yaml;
  // The thumb's base turns against the motor (multiplier -1), so it closes the other way.
  EXPECT_NE(yaml.find("{name: LThumb1, closing: 1}  # adaptive: follows LHand"), std::string::npos)
      << yaml;
  const CliResult ring =
      run_cli({"run", kRobots + "/scenarios/romeo/wire_ring.yaml", "--robot", out, "--seed", "1",
               "--no-pictures", "--out", dir.file("ring"), "--json"});
  ASSERT_EQ(ring.exit_code, 0) << ring.out << ring.err;
  EXPECT_TRUE(ring.json()["verified"].get<bool>());
  // A start with a finger off its motor (LFinger21 half closed, LHand open) is no open hand.
  const std::string off = dir.write(
      "off.yaml", slurp(kRobots + "/scenarios/romeo/wire_ring.yaml") +
                      "start: [0, -0.785398, 0, -2.356194, 0, 1.570796, 0.785398, 1, 0.5]\n");
  const CliResult start = run_cli(
      {"run", off, "--robot", out, "--no-pictures", "--out", dir.file("off"), "--max-cycles", "5"});
  EXPECT_EQ(start.exit_code, 2) << start.out << start.err;
  EXPECT_NE(start.err.find("'LFinger21' is an adaptive joint"), std::string::npos) << start.err;
  EXPECT_NE(yaml.find("root: l_wrist"), std::string::npos) << yaml;
  EXPECT_LT(j["hand"]["widest_bar"].get<double>(), 0.02);
  const CliResult purse =
      run_cli({"run", kRobots + "/scenarios/purse_1_panda_allegro.yaml", "--robot", out,
               "--max-cycles", "5", "--no-pictures", "--out", dir.file("purse")});
  EXPECT_EQ(purse.exit_code, 1) << purse.out << purse.err;
  EXPECT_NE((purse.out + purse.err).find("bar too thick for this hand"), std::string::npos)
      << purse.out << purse.err;
  // A hand root that the URDF does not have.
  EXPECT_EQ(run_cli({"describe", urdfs + "panda_description/urdf/panda.urdf", "--hand-urdf",
                     urdfs + "romeo_description/urdf/romeo.urdf", "--hand-urdf-root", "l_palm",
                     "--mount", "panda_link8", "--replaces", "panda_hand", "-o", dir.file("x")})
                .exit_code,
            2);
}

TEST(DescribeCommand, BadInputIsExitTwoWithAReason) {
  TempDir dir;
  const std::string urdfs = kRobots + "/example-robot-data/robots/";
  const CliResult missing = run_cli({"describe", dir.file("none.urdf"), "-o", dir.file("a.yaml")});
  EXPECT_EQ(missing.exit_code, 2);
  EXPECT_NE(missing.err.find("not found"), std::string::npos) << missing.err;
  // An arm without a hand: nothing to draft, and the way out is named.
  const CliResult arm =
      run_cli({"describe", urdfs + "ur_description/urdf/ur5_robot.urdf", "-o", dir.file("b.yaml")});
  EXPECT_EQ(arm.exit_code, 2);
  EXPECT_NE(arm.err.find("--hand-root"), std::string::npos) << arm.err;
  const CliResult mount = run_cli(
      {"describe", urdfs + "ur_description/urdf/ur5_robot.urdf", "--hand-urdf",
       urdfs + "allegro_hand_description/urdf/allegro_right_hand.urdf", "-o", dir.file("c.yaml")});
  EXPECT_EQ(mount.exit_code, 2);
  EXPECT_NE(mount.err.find("--mount"), std::string::npos) << mount.err;
  EXPECT_EQ(run_cli({"describe", "--help"}).exit_code, 0);
}

}  // namespace
}  // namespace claspplan::test
