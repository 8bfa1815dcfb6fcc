// The paper's five objects (Fig. 3) are closed surfaces of the genus the paper counts: purse,
// bag and travel bag 1, lawn mower 2, chair 7 (chi = 2 - 2g), and the loop points they name lie
// in a hole, outside the material.
#include "examples/paper_objects.hpp"

#include <gtest/gtest.h>

#include "examples/scenario.hpp"

namespace claspplan::test {
namespace {

TEST(PaperObjects, GenusIsThePapersLoopCount) {
  const std::map<std::string, int> paper = {
      {"purse", 1}, {"bag", 1}, {"travelbag", 1}, {"lawnmower", 2}, {"chair", 7}};
  for (const auto& name : objects::paper_object_names()) {
    const objects::PaperObject o = objects::paper_object(name);
    EXPECT_EQ(o.loops, paper.at(name)) << name;
    EXPECT_EQ(euler_characteristic(o.mesh), 2 - 2 * o.loops) << name;
    // The hole centres are empty space: no vertex within 1 cm.
    for (const auto& p : {o.clasp, o.hidden}) {
      double nearest = 1e9;
      for (const auto& v : o.mesh.vertices) nearest = std::min(nearest, (v - p).norm());
      EXPECT_GT(nearest, 0.01) << name;
    }
  }
}

TEST(PaperObjects, ScenarioShapeTypesAndErrors) {
  const std::string text = "robot: kr5_sdh\nobject:\n  shape: {type: chair}\n";
  const cli::Scenario s = cli::load_scenario_text(text, "chair.yaml", ".");
  ASSERT_TRUE(s.object.shape);
  EXPECT_EQ(s.object.shape->type, "chair");
  EXPECT_THROW(cli::load_scenario_text(
                   "robot: kr5_sdh\nobject:\n  shape: {type: chair, holes: 2}\n", "c.yaml", "."),
               std::invalid_argument);
  EXPECT_THROW(
      cli::load_scenario_text("robot: kr5_sdh\nobject:\n  shape: {type: sofa}\n", "c.yaml", "."),
      std::invalid_argument);
  EXPECT_THROW(objects::paper_object("sofa"), std::invalid_argument);
}

}  // namespace
}  // namespace claspplan::test
