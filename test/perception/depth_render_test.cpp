// The synthetic depth sensor: exact depth of planes, a sphere's profile, noise statistics,
// dropout rate, determinism, near-plane clipping, visible-surface sampling and back-projection.
#include "perception/depth_render.hpp"

#include <cmath>

#include <gtest/gtest.h>

#include "examples/objects.hpp"
#include "perception/camera.hpp"

namespace claspplan::perception {
namespace {

CameraModel camera_at_origin_looking_down_z(int w = 160, int h = 120) {
  CameraModel c;
  c.width = w;
  c.height = h;
  c.fx = c.fy = 100.0;
  c.cx = (w - 1) / 2.0;
  c.cy = (h - 1) / 2.0;
  return c;  // identity pose: the optical frame is the world frame
}

TriangleMesh quad(double z, double half) {
  TriangleMesh m;
  m.vertices = {{-half, -half, z}, {half, -half, z}, {half, half, z}, {-half, half, z}};
  m.triangles = {{0, 1, 2}, {0, 2, 3}};
  return m;
}

TEST(DepthRender, PlaneAtKnownDistanceGivesExactDepth) {
  const CameraModel cam = camera_at_origin_looking_down_z();
  const DepthImage img = render_depth(quad(0.75, 10.0), cam);
  ASSERT_EQ(img.valid_count(), cam.width * cam.height);  // no cracks along the diagonal
  for (float z : img.depth) EXPECT_FLOAT_EQ(z, 0.75f);
  // A tilted plane z = 1 + 0.5 x: perspective-correct depth at every pixel.
  TriangleMesh tilted = quad(0.0, 5.0);
  for (auto& v : tilted.vertices) v.z() = 1.0 + 0.5 * v.x();
  const DepthImage t = render_depth(tilted, cam);
  for (int v = 0; v < cam.height; v += 7)
    for (int u = 0; u < cam.width; u += 5) {
      const double rx = (u - cam.cx) / cam.fx;  // ray (rx, ry, 1): z = 1 + 0.5 z rx
      EXPECT_NEAR(t.at(u, v), 1.0 / (1.0 - 0.5 * rx), 2e-6) << u << "," << v;
    }
}

// Back-projection: each valid pixel once, on its ray at its depth; a second view appends after
// the first; a crop keeps the points inside its box, in the same order.
TEST(DepthRender, BackProjectionPutsEachPixelOnItsRayAndAppendsViews) {
  DepthView a{camera_at_origin_looking_down_z(40, 30), {}};
  a.image = render_depth(quad(0.6, 10.0), a.camera);
  a.image.at(3, 4) = 0.0f;  // a dropout
  DepthView b = a;
  b.camera.T_world_camera.translation() = Eigen::Vector3d(0.0, 0.0, 1.0);
  const auto pa = depth_to_points(a);
  ASSERT_EQ(pa.size(), static_cast<size_t>(40 * 30 - 1));
  EXPECT_NEAR(pa.front().x(), (0 - a.camera.cx) * 0.6 / a.camera.fx, 1e-6);
  EXPECT_NEAR(pa.front().y(), (0 - a.camera.cy) * 0.6 / a.camera.fy, 1e-6);
  for (const auto& p : pa) EXPECT_NEAR(p.z(), 0.6, 1e-6);
  std::vector<Eigen::Vector3d> both = pa;
  append_depth_points(b, both);
  ASSERT_EQ(both.size(), 2 * pa.size());
  for (size_t i = 0; i < pa.size(); ++i) {
    EXPECT_EQ(both[i], pa[i]);
    EXPECT_NEAR((both[pa.size() + i] - pa[i]).z(), 1.0, 1e-12);
  }
  // Into a buffer with a crop box: the points inside it, in pixel order, and every valid pixel
  // counted.
  Eigen::AlignedBox3d left_half(Eigen::Vector3d(-1, -1, 0), Eigen::Vector3d(0, 1, 1));
  std::vector<Eigen::Vector3d> buffer(a.image.valid_count());
  const DepthPixels n = back_project(a, left_half, buffer.data());
  EXPECT_EQ(n.valid, static_cast<int>(pa.size()));
  std::vector<Eigen::Vector3d> inside;
  for (const auto& p : pa)
    if (left_half.contains(p)) inside.push_back(p);
  ASSERT_GT(inside.size(), 0u);
  ASSERT_LT(inside.size(), pa.size());
  buffer.resize(n.kept);
  EXPECT_EQ(buffer, inside);
}

TEST(DepthRender, SphereDepthProfile) {
  const CameraModel cam = camera_at_origin_looking_down_z();
  const double R = 0.2, D = 1.0;
  const TriangleMesh s = objects::sphere_mesh(R, {0, 0, D}, 256, 128);
  const DepthImage img = render_depth(s, cam);
  const double sag = R * (1 - std::cos(3.14159265358979 / 128));  // facet depth below the sphere
  int checked = 0;
  for (int v = 0; v < cam.height; ++v)
    for (int u = 0; u < cam.width; ++u) {
      const Eigen::Vector3d r((u - cam.cx) / cam.fx, (v - cam.cy) / cam.fy, 1.0);
      // |t r - c|^2 = R^2 with c = (0, 0, D): z = t (r.z = 1).
      const double b = r.z() * D, a = r.squaredNorm(), cc = D * D - R * R;
      const double disc = b * b - a * cc;
      if (disc < 0.02 * b * b) {  // outside (or at the rim of) the silhouette
        if (disc < 0) {
          EXPECT_EQ(img.at(u, v), 0.0f) << u << "," << v;
        }
        continue;
      }
      const double z = (b - std::sqrt(disc)) / a;
      EXPECT_GE(img.at(u, v), z - 1e-6);
      EXPECT_LE(img.at(u, v), z + 10 * sag);
      ++checked;
    }
  EXPECT_GT(checked, 500);
}

TEST(DepthRender, NoiseAndDropoutStatisticsAreSeeded) {
  const CameraModel cam = camera_at_origin_looking_down_z(200, 200);
  DepthNoise noise;
  noise.sigma = 0.001;
  noise.dropout = 0.1;
  noise.seed = 42;
  const DepthImage a = render_depth(quad(0.8, 10.0), cam, noise);
  const DepthImage b = render_depth(quad(0.8, 10.0), cam, noise);
  EXPECT_EQ(a.depth, b.depth);  // deterministic
  noise.seed = 43;
  EXPECT_NE(render_depth(quad(0.8, 10.0), cam, noise).depth, a.depth);
  double sum = 0, sum2 = 0;
  int n = 0, dropped = 0;
  for (float z : a.depth) {
    if (z == 0.0f) {
      ++dropped;
      continue;
    }
    sum += z - 0.8;
    sum2 += (z - 0.8) * (z - 0.8);
    ++n;
  }
  const double total = a.depth.size();
  EXPECT_NEAR(dropped / total, 0.1, 0.01);  // 40000 pixels: ~6 sigma
  const double mean = sum / n, sd = std::sqrt(sum2 / n - mean * mean);
  EXPECT_NEAR(mean, 0.0, 5e-5);
  EXPECT_NEAR(sd, 0.001, 5e-5);
}

TEST(DepthRender, ClipsAtTheNearPlaneAndRejectsBadNoise) {
  const CameraModel cam = camera_at_origin_looking_down_z();
  // A floor from behind the camera to far in front: clipped, not dropped.
  TriangleMesh floor;
  floor.vertices = {{-1, 0.3, -1}, {1, 0.3, -1}, {1, 0.3, 5}, {-1, 0.3, 5}};
  floor.triangles = {{0, 1, 2}, {0, 2, 3}};
  const DepthImage img = render_depth(floor, cam);
  EXPECT_GT(img.valid_count(), cam.width * cam.height / 4);
  // Row v sees the floor (y = 0.3) at z = 0.3 fy / (v - cy).
  const int v = cam.height - 1;
  EXPECT_NEAR(img.at(cam.width / 2, v), 0.3 * cam.fy / (v - cam.cy), 1e-5);
  DepthNoise bad;
  bad.dropout = 1.5;
  EXPECT_THROW(render_depth(floor, cam, bad), std::invalid_argument);
}

TEST(DepthRender, VisibleSamplingSeesOnlyTheFrontOfASphere) {
  const TriangleMesh s = objects::sphere_mesh(0.1, Eigen::Vector3d::Zero(), 64, 32);
  const auto views = render_views(s, {{0, 0, 1.0}});  // from above
  ASSERT_EQ(views.size(), 1u);
  const PointCloud pts = sample_visible_surface(s, views, 2000, 7);
  ASSERT_EQ(pts.size(), 2000u);
  for (const auto& p : pts) EXPECT_GT(p.z(), -0.01);  // the lower half is hidden
  int high = 0;
  for (const auto& p : pts) high += p.z() > 0.05;
  // Uniform by area on the visible cap z > r^2/D = 0.01: the part z > 0.05 holds 0.05/0.09 of it.
  EXPECT_NEAR(high / 2000.0, 0.05 / 0.09, 0.04);
  EXPECT_EQ(sample_visible_surface(s, views, 2000, 7), pts);             // seeded
  EXPECT_THROW(render_views(s, {{0, 0, 0.05}}), std::invalid_argument);  // inside the object
}

}  // namespace
}  // namespace claspplan::perception
