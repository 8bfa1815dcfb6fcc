// The close-up pictures' choice of viewpoint: past the environment, not through it.
#include "examples/result_pictures.hpp"

#include <vector>

#include <gtest/gtest.h>

namespace claspplan::cli {
namespace {

EnvironmentBox table() {  // 1 x 1 m, its top at z = 0.1
  EnvironmentBox b;
  b.size = Eigen::Vector3d(1.0, 1.0, 0.1);
  b.pose.translation() = Eigen::Vector3d(0.0, 0.0, 0.05);
  return b;
}

TEST(ResultPictures, ALineOfSightThroughABoxIsBlocked) {
  View view;
  view.target = Eigen::Vector3d(0.0, 0.0, 0.2);
  view.eye = Eigen::Vector3d(0.0, 0.0, -1.0);  // below the table, looking up through it
  EXPECT_TRUE(blocks_sight(table(), view));
  view.eye = Eigen::Vector3d(0.3, 0.2, 0.07);  // inside it
  EXPECT_TRUE(blocks_sight(table(), view));
  view.eye = Eigen::Vector3d(0.0, -1.0, 0.3);  // beside it, above its top
  EXPECT_FALSE(blocks_sight(table(), view));
  view.eye = Eigen::Vector3d(2.0, 0.0, 0.05);  // level with it, the target beyond its edge
  view.target = Eigen::Vector3d(0.6, 0.0, 0.05);
  EXPECT_FALSE(blocks_sight(table(), view));
  EnvironmentBox turned = table();  // turned 45 degrees about z: its corner reaches x = 0.707
  turned.pose.linear() = Eigen::AngleAxisd(0.785398, Eigen::Vector3d::UnitZ()).toRotationMatrix();
  EXPECT_TRUE(blocks_sight(turned, view));
}

TEST(ResultPictures, ACloseUpLooksPastTheTableNotUpThroughIt) {
  const std::vector<Eigen::Vector3d> hand = {{0.0, 0.0, 0.15}, {0.05, 0.02, 0.2}};
  const Eigen::Vector3d under(0.2, -0.5, -1.0), over(0.2, -0.5, 1.0);
  const View view = unobstructed_view(hand, {under, over}, {table()});
  EXPECT_FALSE(blocks_sight(table(), view));
  EXPECT_GT(view.eye.z(), 0.1);
  // Unblocked, the first direction is kept.
  EXPECT_LT(unobstructed_view(hand, {under, over}, {}).eye.z(), 0.1);
  // Every direction blocked: the one with the fewest boxes in the way.
  EnvironmentBox lid = table();
  lid.pose.translation().z() = 0.33;  // around the raised eye
  const View blocked = unobstructed_view(hand, {under, over}, {table(), lid, lid});
  EXPECT_LT(blocked.eye.z(), 0.1);
}

}  // namespace
}  // namespace claspplan::cli
