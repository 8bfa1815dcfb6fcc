// The open-passage probe of the loop ranking (perception/loops.hpp): a finger's line through a hole
// may tilt away from material beside it, but only through space a camera saw.
#include <cmath>

#include <gtest/gtest.h>

#include "perception/loops.hpp"

namespace claspplan::perception {
namespace {

// A ring of points (radius 2.5 cm, at z = 0.3 m, axis z) and a small blob of material 3 cm above
// the hole, 9 mm off its axis: the straight probe along the axis (radius 0.45 x 3 cm) meets the
// blob; lines tilted 15 or 30 degrees away from it pass clear.
struct RingBesideMaterial {
  Loop loop;
  PointCloud cloud;
  Eigen::Vector3d centre{0.5, 0.0, 0.3};

  RingBesideMaterial() {
    for (int i = 0; i < 80; ++i) {
      const double a = 2.0 * M_PI * i / 80.0;
      const Eigen::Vector3d p = centre + 0.025 * Eigen::Vector3d(std::cos(a), std::sin(a), 0);
      loop.points.push_back(p);
      cloud.push_back(p);
    }
    for (int i = 0; i < 5; ++i)
      cloud.push_back(centre + Eigen::Vector3d(0.001 * (i - 2), 0.009, 0.03));
  }
};

// A camera 0.5 m above the hole looking down; every pixel sees the floor 1 m below it, except an
// annulus around the hole's axis (30-90 pixels out, beyond the hole's centre) that sees a surface
// 10 cm in front of the camera: the tilted lines above the hole then run through space hidden
// behind it.
DepthView camera_above(const Eigen::Vector3d& centre, bool hidden_annulus) {
  DepthView v;
  v.camera = look_at_camera(centre + Eigen::Vector3d(0, 0, 0.5), centre, 0.1);
  v.image = DepthImage(v.camera.width, v.camera.height);
  const Eigen::Vector3d axis = v.camera.project(centre);
  for (int r = 0; r < v.image.height; ++r) {
    for (int u = 0; u < v.image.width; ++u) {
      const double px = std::hypot(u - axis.x(), r - axis.y());
      v.image.at(u, r) = hidden_annulus && px > 30 && px < 90 ? 0.1f : 1.5f;
    }
  }
  return v;
}

TEST(LoopProbe, WithoutCamerasOnlyTheStraightLineCounts) {
  RingBesideMaterial s;
  assess_loop(s.loop, s.cloud, {}, RankingOptions{});
  EXPECT_EQ(s.loop.verdict, perception::LoopVerdict::kTubeWall) << s.loop.reason;
}

TEST(LoopProbe, ALineTiltedAwayFromMaterialPassesThroughSeenSpace) {
  RingBesideMaterial s;
  assess_loop(s.loop, s.cloud, {camera_above(s.centre, false)}, RankingOptions{});
  EXPECT_EQ(s.loop.verdict, perception::LoopVerdict::kClaspable) << s.loop.reason;
  EXPECT_NE(s.loop.reason.find("degrees from its axis"), std::string::npos) << s.loop.reason;
  EXPECT_NEAR(s.loop.hole_width, 0.05, 0.002);
}

TEST(LoopProbe, TiltedLinesThroughUnseenSpaceDoNotCount) {
  RingBesideMaterial s;
  assess_loop(s.loop, s.cloud, {camera_above(s.centre, true)}, RankingOptions{});
  EXPECT_EQ(s.loop.verdict, perception::LoopVerdict::kTubeWall) << s.loop.reason;
}

}  // namespace
}  // namespace claspplan::perception
