// The next best view for unseen space (perception/next_view.hpp): the camera it names sees what
// the first camera could not, and it names none when nothing near the points is unknown.
#include "perception/next_view.hpp"

#include <gtest/gtest.h>
#include <opencv2/imgcodecs.hpp>

#include "examples/objects.hpp"
#include "perception/depth_render.hpp"
#include "perception/drawing.hpp"
#include "test/support/temp_dir.hpp"

namespace claspplan::perception {
namespace {

// A 10 cm sphere, the whole scene, seen by one camera 0.6 m away along -x: its shadow (+x) and
// its inside are the only unknown space of the region.
struct Scene {
  TriangleMesh sphere = objects::sphere_mesh(0.1);
  DepthView front = view_from(Eigen::Vector3d(-0.6, 0, 0), Eigen::Vector3d::Zero());
  Eigen::AlignedBox3d region{Eigen::Vector3d::Constant(-0.2), Eigen::Vector3d::Constant(0.2)};

  DepthView view_from(const Eigen::Vector3d& position, const Eigen::Vector3d& target) const {
    DepthView v;
    v.camera = look_at_camera(position, target, 0.3);
    v.camera.no_reading_is_free = true;
    v.image = render_depth(sphere, v.camera);
    return v;
  }
};

TEST(NextView, TheCameraItNamesSeesTheShadowTheRobotRanInto) {
  const Scene scene;
  const SensedSpace one({scene.front}, scene.region);
  const std::vector<Eigen::Vector3d> contacts = {{0.14, 0.0, 0.0}, {0.14, 0.03, 0.02}};
  for (const auto& p : contacts) ASSERT_EQ(one.at(p), Sensed::kUnknown);

  const auto view = view_into_unknown(one, contacts, std::nullopt);
  ASSERT_TRUE(view);
  EXPECT_GT(view->visible, 0.0);
  EXPECT_LE(view->visible, view->unknown);
  EXPECT_GT(view->position.x(), 0.1) << "a camera on the shadow's side, not through the sphere";
  EXPECT_NEAR((view->position - view->target).norm(), ViewOptions{}.distance, 1e-9);

  // Rendered and added, that camera leaves the contacts known.
  const SensedSpace two({scene.front, scene.view_from(view->position, view->target)}, scene.region);
  for (const auto& p : contacts) EXPECT_NE(two.at(p), Sensed::kUnknown) << p.transpose();
  EXPECT_NE(view_text(*view).find("{position: ["), std::string::npos) << view_text(*view);
}

TEST(NextView, NoneWhenNothingNearThePointsIsUnknownOrNothingIsSeen) {
  const Scene scene;
  const SensedSpace space({scene.front}, scene.region);
  // In front of the sphere, in the first camera's free space.
  EXPECT_FALSE(view_into_unknown(space, {{-0.16, 0.0, 0.0}}, std::nullopt));
  EXPECT_FALSE(view_into_unknown(space, {}, std::nullopt));
  EXPECT_FALSE(view_into_unknown(SensedSpace(), {{0.14, 0.0, 0.0}}, std::nullopt));
  // The sphere's centre: unknown, but 10 cm of unseen inside around it in every direction.
  ViewOptions o;
  o.radius = 0.01;
  EXPECT_FALSE(view_into_unknown(space, {Eigen::Vector3d::Zero()}, std::nullopt, o));
}

TEST(NextView, TheCameraStaysAboveTheSupport) {
  const Scene scene;
  const SensedSpace space({scene.front}, scene.region);
  const Eigen::Vector4d table(0, 0, 1, 0.05);  // z = -0.05, n up
  const auto view = view_into_unknown(space, {{0.14, 0.0, 0.0}}, table);
  ASSERT_TRUE(view);
  EXPECT_GE(view->position.z() + 0.05, ViewOptions{}.above - 1e-9);
  // Where the caller allows no camera (the robot, the room): none on the shadow's side, and
  // through the sphere nothing is seen.
  ViewOptions o;
  o.allowed = [](const Eigen::Vector3d& p) { return p.x() < 0.0; };
  EXPECT_FALSE(view_into_unknown(space, {{0.14, 0.0, 0.0}}, table, o));
}

// sensed.png shows the named camera: its line of sight and its target, green, and its entry.
TEST(NextView, TheSensedPictureShowsTheCamera) {
  const Scene scene;
  const SensedSpace space({scene.front}, scene.region);
  const auto view = view_into_unknown(space, {{0.14, 0.0, 0.0}}, std::nullopt);
  ASSERT_TRUE(view);
  test::TempDir dir;
  const auto green_pixels = [&](const ViewSuggestion* shown) {
    const std::string path = dir.file("sensed.png");
    draw_sensed_space_png(space, view->target, {}, "a sphere", path, shown);
    const cv::Mat img = cv::imread(path, cv::IMREAD_COLOR);
    int n = 0;
    for (int y = 0; y < img.rows; ++y)
      for (int x = 0; x < img.cols; ++x) {
        const cv::Vec3b c = img.at<cv::Vec3b>(y, x);  // BGR
        n += c[1] > 100 && c[0] < 80 && c[2] < 80;
      }
    return n;
  };
  EXPECT_EQ(green_pixels(nullptr), 0);
  EXPECT_GT(green_pixels(&*view), 300) << "three lines of sight, three dots and the entry";
}

}  // namespace
}  // namespace claspplan::perception
