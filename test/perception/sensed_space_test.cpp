// The sensed space (perception/sensed_space.hpp): free in front of what a camera measured,
// occupied at it, unknown behind it and outside the image; scattered dropouts do not hide free
// space; what the robot may not enter.
#include "perception/sensed_space.hpp"

#include <cmath>

#include <gtest/gtest.h>
#include <opencv2/imgcodecs.hpp>

#include "examples/objects.hpp"
#include "perception/depth_render.hpp"
#include "perception/drawing.hpp"
#include "test/support/temp_dir.hpp"

namespace claspplan::perception {
namespace {

// A 10 cm sphere at the origin seen by one camera 0.6 m away along -x, looking along +x.
struct OneView {
  TriangleMesh sphere = objects::sphere_mesh(0.1);
  DepthView view;
  OneView(const DepthNoise& noise = {}) {
    view.camera = look_at_camera(Eigen::Vector3d(-0.6, 0, 0), Eigen::Vector3d::Zero(), 0.3);
    view.image = render_depth(sphere, view.camera, noise);
  }
  Eigen::AlignedBox3d region() const {
    return Eigen::AlignedBox3d(Eigen::Vector3d(-0.2, -0.2, -0.2), Eigen::Vector3d(0.2, 0.2, 0.2));
  }
};

// A wall 0.3 m behind the sphere, across the whole view.
TriangleMesh wall_behind() {
  TriangleMesh wall;
  wall.vertices = {{0.3, -1, -1}, {0.3, 1, -1}, {0.3, 1, 1}, {0.3, -1, 1}};
  wall.triangles = {{0, 1, 2}, {0, 2, 3}};
  return wall;
}

TEST(SensedSpace, FreeBeforeTheSurfaceOccupiedAtItUnknownBehind) {
  const OneView scene;
  const SensedSpace space({scene.view}, scene.region());
  EXPECT_EQ(space.at(Eigen::Vector3d(-0.15, 0, 0)), Sensed::kFree);
  EXPECT_EQ(space.at(Eigen::Vector3d(-0.1, 0, 0)), Sensed::kOccupied);
  EXPECT_EQ(space.at(Eigen::Vector3d(0, 0, 0)), Sensed::kUnknown);           // inside
  EXPECT_EQ(space.at(Eigen::Vector3d(0.15, 0, 0)), Sensed::kUnknown);        // in its shadow
  EXPECT_EQ(space.at(Eigen::Vector3d(0.15, 0.15, 0.15)), Sensed::kUnknown);  // no background
  EXPECT_EQ(space.at(Eigen::Vector3d(-0.15, 0.15, 0)), Sensed::kUnknown);    // ray hit nothing
  // Outside the region: unknown, but free for the robot (the rule for space far from the object).
  EXPECT_EQ(space.at(Eigen::Vector3d(1, 0, 0)), Sensed::kUnknown);
  EXPECT_TRUE(space.free_for_robot(Eigen::Vector3d(1, 0, 0)));
  EXPECT_FALSE(space.free_for_robot(Eigen::Vector3d(0, 0, 0)));
}

TEST(SensedSpace, ABackgroundMakesTheSpaceAroundTheObjectFree) {
  OneView scene;
  append_mesh(scene.sphere, wall_behind());  // rays beside the sphere now end on it
  scene.view.image = render_depth(scene.sphere, scene.view.camera);
  const SensedSpace space({scene.view}, scene.region());
  EXPECT_EQ(space.at(Eigen::Vector3d(0.15, 0.15, 0.15)), Sensed::kFree);
  EXPECT_EQ(space.at(Eigen::Vector3d(-0.15, 0.15, 0)), Sensed::kFree);
  EXPECT_EQ(space.at(Eigen::Vector3d(0.15, 0, 0)), Sensed::kUnknown);  // the shadow stays
}

TEST(SensedSpace, ScatteredDropoutsDoNotHideFreeSpace) {
  OneView clean;
  append_mesh(clean.sphere, wall_behind());
  clean.view.image = render_depth(clean.sphere, clean.view.camera);
  DepthView noisy = clean.view;
  DepthNoise noise;
  noise.dropout = 0.02;
  noisy.image = render_depth(clean.sphere, clean.view.camera, noise);
  const auto a = SensedSpace({clean.view}, clean.region()).counts();
  const auto b = SensedSpace({noisy}, clean.region()).counts();
  EXPECT_GT(b[1], 0.97 * a[1]) << "free voxels: " << a[1] << " without dropouts, " << b[1];
}

TEST(SensedSpace, TwoViewsLeaveOnlyTheJointShadowUnknown) {
  OneView front;
  front.view.camera.no_reading_is_free = true;  // the sphere is the whole scene
  DepthView side;
  side.camera = look_at_camera(Eigen::Vector3d(0, -0.6, 0), Eigen::Vector3d::Zero(), 0.3);
  side.camera.no_reading_is_free = true;
  side.image = render_depth(front.sphere, side.camera);
  const SensedSpace one({front.view}, front.region());
  const SensedSpace two({front.view, side}, front.region());
  // Behind the sphere for the first camera, in plain sight of the second.
  const Eigen::Vector3d p(0.15, -0.12, 0);
  EXPECT_EQ(one.at(p), Sensed::kUnknown);
  EXPECT_NE(two.at(p), Sensed::kUnknown);
  EXPECT_LT(two.counts()[0], one.counts()[0]);
  EXPECT_EQ(two.at(Eigen::Vector3d::Zero()), Sensed::kUnknown);  // the inside is never seen
}

// A table seen at 20 degrees, as a robot's head camera sees it: the voxels whose bottom lies
// 0.95 mm above it are free. Each ray through such a voxel leaves it before it meets the table,
// but the voxel's far corner lies beyond where the rays past its lower edge meet the table, so
// the footprint's nearest reading alone cannot tell. (Not so close that the surface tolerance
// makes them occupied.)
TEST(SensedSpace, VoxelsJustAboveAGrazingViewOfATableAreFree) {
  const TriangleMesh table = objects::ground_plane(2.0, 0.00405);
  DepthView view;
  const double elevation = 20.0 * M_PI / 180.0;
  view.camera = look_at_camera(  // 0.46 mm pixels at the table
      0.6 * Eigen::Vector3d(0, -std::cos(elevation), std::sin(elevation)), Eigen::Vector3d::Zero(),
      0.1);
  view.image = render_depth(table, view.camera);
  const Eigen::AlignedBox3d region(Eigen::Vector3d(-0.02, -0.02, -0.01),
                                   Eigen::Vector3d(0.02, 0.02, 0.02));
  const SensedSpace space({view}, region);  // 5 mm voxels, layers centred at z = -2.5, 2.5, 7.5 mm
  ASSERT_DOUBLE_EQ(space.resolution(), 0.005);
  int above = 0, straddling = 0, below = 0;
  for (int k = 0; k < space.dims().z(); ++k)
    for (int j = 0; j < space.dims().y(); ++j)
      for (int i = 0; i < space.dims().x(); ++i) {
        const Eigen::Vector3d c = space.centre(i, j, k);
        const Sensed s = space.cell(i, j, k);
        if (c.z() > 0.005) {  // above the table
          EXPECT_EQ(s, Sensed::kFree) << "at " << c.transpose();
          ++above;
        } else if (c.z() > 0.0) {  // the table's surface runs through it
          EXPECT_NE(s, Sensed::kFree) << "at " << c.transpose();
          ++straddling;
        } else {
          EXPECT_EQ(s, Sensed::kUnknown) << "at " << c.transpose();
          ++below;
        }
      }
  EXPECT_GT(above, 0);
  EXPECT_GT(straddling, 0);
  EXPECT_GT(below, 0);
}

TEST(SensedSpace, BlockedVoxelsAreTheUnknownOnesAndTheSupportsSurface) {
  const OneView scene;
  const SensedSpace space({scene.view}, scene.region());
  const auto n = space.counts();
  const auto blocked = space.blocked_voxels();
  EXPECT_EQ(static_cast<long>(blocked.size()), n[0]);
  for (const auto& c : blocked) EXPECT_EQ(space.at(c), Sensed::kUnknown);
  // With a support at z = 0.05 (n up), the occupied voxels below it join them.
  const auto with_support = space.blocked_voxels(Eigen::Vector4d(0, 0, 1, -0.05));
  EXPECT_GT(with_support.size(), blocked.size());
  for (const auto& c : with_support)
    EXPECT_TRUE(space.at(c) == Sensed::kUnknown || c.z() <= 0.05 + 0.005 + 1e-9);
}

TEST(SensedSpace, GridIsSnappedAndCoarsenedToItsBudget) {
  const OneView scene;
  SensedSpaceOptions o;
  o.resolution = 0.004;
  o.max_voxels = 20000;
  const SensedSpace space({scene.view}, scene.region(), o);
  EXPECT_GT(space.resolution(), 0.004);
  EXPECT_LE(static_cast<long>(space.dims().prod()), o.max_voxels);
  EXPECT_TRUE(space.region().contains(scene.region().min()));
  EXPECT_TRUE(space.region().contains(scene.region().max()));
  const Eigen::Vector3d lo = space.region().min() / space.resolution();
  EXPECT_NEAR(lo.x(), std::round(lo.x()), 1e-6);
}

// The planner's finer map near a loop: the same views on voxels that divide the coarse ones. It
// finds more free space at the sphere's edge (voxels that the silhouette only partly shadows), and
// every part of a free coarse voxel stays free.
TEST(SensedSpace, AFinerGridNearTheLoopKeepsTheFreeSpaceAndFindsMore) {
  OneView scene;
  scene.view.camera.no_reading_is_free = true;
  const SensedSpace coarse({scene.view}, scene.region());
  // Around the sphere's upper silhouette, beside its shadow.
  const Eigen::AlignedBox3d box(Eigen::Vector3d(0.0, -0.03, 0.09),
                                Eigen::Vector3d(0.1, 0.03, 0.11));
  const SensedSpace fine = coarse.refined(box, 0.0016, 1'000'000);
  ASSERT_FALSE(fine.empty());
  EXPECT_NEAR(fine.resolution(), coarse.resolution() / 3, 1e-12);
  // Snapped to whole coarse voxels that hold the box.
  EXPECT_TRUE(fine.region().contains(box.min()) && fine.region().contains(box.max()));
  const Eigen::Vector3d lo = (fine.region().min() - coarse.region().min()) / coarse.resolution();
  EXPECT_NEAR(lo.x(), std::round(lo.x()), 1e-6);
  EXPECT_NEAR(lo.z(), std::round(lo.z()), 1e-6);
  double free_fine = 0.0, free_coarse = 0.0;
  const Eigen::Vector3i n = fine.dims();
  for (int k = 0; k < n.z(); ++k)
    for (int j = 0; j < n.y(); ++j)
      for (int i = 0; i < n.x(); ++i) {
        const Eigen::Vector3d c = fine.centre(i, j, k);
        const Sensed parent = coarse.at(c);
        if (parent == Sensed::kFree) {
          EXPECT_EQ(fine.cell(i, j, k), Sensed::kFree);
        }
        free_fine += fine.cell(i, j, k) == Sensed::kFree;
        free_coarse += parent == Sensed::kFree;
      }
  EXPECT_GT(free_fine, 1.1 * free_coarse);
  // The budget coarsens the finer grid (halves instead of thirds), then gives up.
  EXPECT_NEAR(coarse.refined(box, 0.0016, n.prod() / 2).resolution(), coarse.resolution() / 2,
              1e-12);
  EXPECT_TRUE(coarse.refined(box, 0.0016, 10).empty());
  EXPECT_TRUE(coarse.refined(box, 0.004, 1'000'000).empty()) << "not finer in two";
  const Eigen::AlignedBox3d away(Eigen::Vector3d::Constant(1.0), Eigen::Vector3d::Constant(1.1));
  EXPECT_TRUE(coarse.refined(away, 0.0016, 1'000'000).empty());
  EXPECT_THROW(coarse.refined(box, 0.0, 1'000'000), std::invalid_argument);
}

// sensed.png shows what the planner used: the finer voxels inside their box, which find more of
// the space around the sphere's silhouette and its shadow free, and keep all that the coarser
// ones found.
TEST(SensedSpace, TheSensedPictureShowsTheFinerVoxels) {
  OneView scene;
  scene.view.camera.no_reading_is_free = true;
  const SensedSpace coarse({scene.view}, scene.region());
  const Eigen::AlignedBox3d box(Eigen::Vector3d(-0.12, -0.12, -0.02),
                                Eigen::Vector3d(0.12, 0.12, 0.02));
  const SensedSpace fine = coarse.refined(box, 0.0016, 1'000'000);
  ASSERT_FALSE(fine.empty());
  test::TempDir dir;
  const auto picture = [&](const SensedSpace* finer) {
    const std::string path = dir.file("sensed.png");
    draw_sensed_space_png(coarse, Eigen::Vector3d::Zero(), {}, "a sphere", path, nullptr, finer);
    return cv::imread(path, cv::IMREAD_COLOR);
  };
  const cv::Mat with = picture(&fine), without = picture(nullptr);
  ASSERT_EQ(with.size(), without.size());
  const cv::Vec3b free(245, 245, 245), outline(130, 130, 130);
  int gained = 0, lost = 0;
  // The title row and the panels, not the caption (which names the finer voxels).
  for (int y = 0; y < SensedPictureLayout::title + SensedPictureLayout::panel; ++y)
    for (int x = 0; x < with.cols; ++x) {
      const cv::Vec3b a = with.at<cv::Vec3b>(y, x), b = without.at<cv::Vec3b>(y, x);
      gained += a == free && b != free;
      lost += b == free && a != free && a != outline;
    }
  EXPECT_GT(gained, 100);
  EXPECT_EQ(lost, 0);
}

TEST(SensedSpace, WithoutViewsEverythingIsUnknownAndBadRegionsThrow) {
  const OneView scene;
  const SensedSpace blind({}, scene.region());
  EXPECT_EQ(blind.counts()[1] + blind.counts()[2], 0);
  EXPECT_TRUE(SensedSpace().empty());
  EXPECT_THROW(SensedSpace({scene.view}, Eigen::AlignedBox3d()), std::invalid_argument);
  SensedSpaceOptions bad;
  bad.resolution = 0.0;
  EXPECT_THROW(SensedSpace({scene.view}, scene.region(), bad), std::invalid_argument);
}

}  // namespace
}  // namespace claspplan::perception
