// Measured material the depth surface leaves out (tsrrt/clasp_scene.hpp's unmeshed_points).
#include <gtest/gtest.h>

#include "core/mesh.hpp"
#include "examples/objects.hpp"
#include "perception/depth_render.hpp"
#include "perception/depth_surface.hpp"
#include "tsrrt/clasp_scene.hpp"

namespace claspplan::test {
namespace {

// A vertical rod `width` wide 0.6 m before a camera, a wall 0.4 m behind it: the measured points
// that the rendered view's depth surface leaves out.
struct RodScene {
  std::vector<Eigen::Vector3d> unmeshed;
  int rod_triangles = 0;  // surface triangles within 0.1 m of the rod
};
RodScene rod_scene(double width) {
  TriangleMesh scene = transformed(box_mesh({0.02, 0.6, 0.6}),
                                   Eigen::Isometry3d(Eigen::Translation3d(1.0, 0.0, 0.5)));
  append_mesh(scene, transformed(box_mesh({width, width, 0.2}),
                                 Eigen::Isometry3d(Eigen::Translation3d(0.6, 0.0, 0.5))));
  perception::DepthView view;
  view.camera = objects::kinect_camera({0.0, 0.0, 0.5}, {1.0, 0.0, 0.5});
  view.image = perception::render_depth(scene, view.camera);
  const TriangleMesh surface = perception::depth_surface_mesh({view}, {});
  RodScene out;
  for (const Eigen::Vector3i& t : surface.triangles)
    out.rod_triangles += surface.vertices[t[0]].x() < 0.7;
  const Eigen::AlignedBox3d region(Eigen::Vector3d(0.3, -0.5, 0.1), Eigen::Vector3d(1.2, 0.5, 0.9));
  out.unmeshed = tsrrt::unmeshed_points({view}, region, surface, std::nullopt);
  return out;
}

TEST(UnmeshedPoints, ARodTooThinForTheDepthSurfaceIsStillMaterial) {
  // 2 mm at 0.6 m: under two pixels across, so no grid cell of the surface lies on it.
  const RodScene thin = rod_scene(0.002);
  ASSERT_EQ(thin.rod_triangles, 0);
  // Its pixels (0.2 m / 1.1 mm per row, one or two a row) are all left out, and nothing else.
  EXPECT_GT(thin.unmeshed.size(), 150u);
  for (const Eigen::Vector3d& p : thin.unmeshed) {
    EXPECT_NEAR(p.x(), 0.6, 0.0015);
    EXPECT_NEAR(p.y(), 0.0, 0.0015);
    EXPECT_NEAR(p.z(), 0.5, 0.1 + 1e-3);
  }
}

TEST(UnmeshedPoints, ARodTheSurfaceCoversLeavesNothingOut) {
  const RodScene thick = rod_scene(0.02);
  ASSERT_GT(thick.rod_triangles, 100);
  EXPECT_TRUE(thick.unmeshed.empty()) << thick.unmeshed.size() << " points left out";
}

}  // namespace
}  // namespace claspplan::test
