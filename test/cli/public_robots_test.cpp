// Public robots used as they are (examples/robots/, issue 35): the UR5 with the Allegro hand
// loads from its two unmodified URDFs (STL collision meshes, package:// URIs, a 16-joint hand in
// its own URDF), and plans verified clasps of the purse, the jug and the bag; the ring placed in
// front of the hand is verified for every shipped robot.
#include <string>

#include <gtest/gtest.h>

#include "test/support/cli_runner.hpp"
#include "test/support/temp_dir.hpp"

namespace claspplan::test {
namespace {

const std::string kUr5Allegro = std::string(CLASPPLAN_ROBOTS) + "/ur5_allegro.yaml";

TEST(PublicRobots, Ur5AllegroLoadsFromItsUnmodifiedUrdfs) {
  const CliResult r = run_cli({"robot", kUr5Allegro, "--json"});
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const auto j = r.json();
  EXPECT_EQ(j["arm_dof"].get<int>(), 6);
  EXPECT_EQ(j["hand_dof"].get<int>(), 16);
  EXPECT_EQ(j["mesh_shapes"].get<int>(), 7);  // the UR5's links
  EXPECT_TRUE(j["warnings"].empty());
  EXPECT_FALSE(j["self_collision"].get<bool>());
  EXPECT_GT(j["hand"]["closed_aperture"].get<double>(), 0.03);
}

// Bounded by cycles, so that the outcome does not depend on the machine.
TEST(PublicRobots, Ur5AllegroClaspsThePurseTheJugAndTheBag) {
  TempDir dir;
  for (const char* object : {"purse_1", "jug", "bag_2"}) {
    const std::string scenario =
        std::string(CLASPPLAN_ROBOTS) + "/scenarios/" + object + "_ur5_allegro.yaml";
    const CliResult r = run_cli({"run", scenario, "--seed", "2", "--max-cycles", "100",
                                 "--no-pictures", "--out", dir.file(object), "--json"});
    ASSERT_EQ(r.exit_code, 0) << object << ": " << r.out << r.err;
    EXPECT_TRUE(r.json()["verified"].get<bool>()) << object;
  }
}

// The first check of any robot: a ring placed from the hand's own tcp, v_fwd and v_swd
// (object.in_front_of_hand), planned and verified.
TEST(PublicRobots, TheRingInFrontOfTheHandIsVerifiedForEveryShippedRobot) {
  TempDir dir;
  const std::string robots[] = {"kr5_sdh", "kr5_dlr", "kr5_icub", "kr5_armar3", kUr5Allegro};
  for (const std::string& robot : robots) {
    const std::string start =
        robot.rfind("kr5_", 0) == 0 ? "start: [0, -1.5707963, 1.5707963, 0, 1.5707963, 0]\n" : "";
    const std::string path =
        dir.write("ring.yaml", "robot: " + robot + "\n" + start +
                                   "object:\n"
                                   "  shape: {type: torus, major_radius: 0.1, minor_radius: 0.01}\n"
                                   "  in_front_of_hand: 0.3\n");
    const CliResult r = run_cli({"run", path, "--max-cycles", "100", "--no-pictures", "--out",
                                 dir.file("ring_out"), "--json"});
    EXPECT_EQ(r.exit_code, 0) << robot << ": " << r.out << r.err;
  }
}

}  // namespace
}  // namespace claspplan::test
