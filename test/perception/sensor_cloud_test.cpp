// Clouds as sensor data: organized PCDs keep their grid and NaN pixels, VIEWPOINT is the sensor
// pose, NaN is skipped in every format, millimetres are refused, an organized cloud implies its
// camera (fit_pinhole) and becomes a depth view, and an unorganized one becomes a synthetic view.
#include "perception/sensor_cloud.hpp"

#include <cmath>
#include <cstdint>
#include <cstring>
#include <filesystem>
#include <iomanip>
#include <iostream>
#include <limits>
#include <random>
#include <set>

#include <gtest/gtest.h>

#include "core/file_io.hpp"
#include "examples/objects.hpp"
#include "perception/depth_render.hpp"
#include "test/support/temp_dir.hpp"

namespace claspplan::perception {
namespace {

using test::TempDir;
constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();

template <class F>
std::string error_of(F&& f) {
  try {
    f();
  } catch (const InputError& e) {
    return e.what();
  }
  return "";
}

// A 4 x 3 grid with NaN at pixels 1, 6 and 11; values exact in float.
PointCloud small_grid() {
  PointCloud g;
  for (int i = 0; i < 12; ++i) g.emplace_back(0.25 * (i % 4), 0.5 * (i / 4), 1.0 + 0.125 * i);
  for (int i : {1, 6, 11}) g[i] = Eigen::Vector3d::Constant(kNaN);
  return g;
}

// LZF as literal runs only (at most 32 bytes each): valid input for any LZF decoder.
std::string lzf_literals(const std::string& raw) {
  std::string out;
  for (size_t i = 0; i < raw.size(); i += 32) {
    const size_t n = std::min<size_t>(32, raw.size() - i);
    out += static_cast<char>(n - 1);
    out += raw.substr(i, n);
  }
  return out;
}

template <class T>
void append(std::string& s, T v) {
  s.append(reinterpret_cast<const char*>(&v), sizeof v);
}

// An organized PCD with fields x y z rgb (the extra field tests the layouts), as PCL writes it.
std::string organized_pcd(const PointCloud& g, int w, int h, const std::string& kind,
                          const std::string& viewpoint = "0 0 0 1 0 0 0") {
  std::string s = "# .PCD v0.7\nVERSION 0.7\nFIELDS x y z rgb\nSIZE 4 4 4 4\nTYPE F F F U\n";
  s += "COUNT 1 1 1 1\nWIDTH " + std::to_string(w) + "\nHEIGHT " + std::to_string(h) + "\n";
  if (!viewpoint.empty()) s += "VIEWPOINT " + viewpoint + "\n";
  s += "POINTS " + std::to_string(g.size()) + "\nDATA " + kind + "\n";
  if (kind == "ascii") {
    for (const auto& p : g)
      s += std::to_string(p.x()) + " " + std::to_string(p.y()) + " " + std::to_string(p.z()) +
           " 7\n";
  } else if (kind == "binary") {
    for (const auto& p : g) {
      for (int a = 0; a < 3; ++a) append(s, static_cast<float>(p[a]));
      append(s, std::uint32_t{7});
    }
  } else {  // binary_compressed: field-major, then LZF
    std::string raw;
    for (int a = 0; a < 3; ++a)
      for (const auto& p : g) append(raw, static_cast<float>(p[a]));
    for (size_t i = 0; i < g.size(); ++i) append(raw, std::uint32_t{7});
    const std::string packed = lzf_literals(raw);
    append(s, static_cast<std::uint32_t>(packed.size()));
    append(s, static_cast<std::uint32_t>(raw.size()));
    s += packed;
  }
  return s;
}

void expect_same_grid(const PointCloud& got, const PointCloud& want) {
  ASSERT_EQ(got.size(), want.size());
  for (size_t i = 0; i < want.size(); ++i) {
    if (want[i].hasNaN()) {
      EXPECT_TRUE(got[i].hasNaN()) << i;
    } else {
      EXPECT_EQ(got[i], want[i]) << i;
    }
  }
}

TEST(SensorCloud, OrganizedPcdKeepsGridAndNaNPixels) {
  TempDir dir;
  const PointCloud g = small_grid();
  for (const std::string kind : {"ascii", "binary", "binary_compressed"}) {
    SCOPED_TRACE(kind);
    const std::string path = dir.write(kind + ".pcd", organized_pcd(g, 4, 3, kind));
    const SensorCloud c = read_sensor_cloud(path);
    EXPECT_TRUE(c.organized());
    EXPECT_EQ(c.width, 4);
    EXPECT_EQ(c.height, 3);
    expect_same_grid(c.points, g);
    EXPECT_EQ(c.valid_points().size(), 9u);
    ASSERT_TRUE(c.viewpoint.has_value());
    EXPECT_TRUE(c.viewpoint->isApprox(Eigen::Isometry3d::Identity()));
    // The flat reader is unchanged: the valid points only.
    EXPECT_EQ(read_pcd(path).size(), 9u);
  }
}

TEST(SensorCloud, ViewpointIsTheSensorPose) {
  const PointCloud g = small_grid();
  // 90 degrees about z (PCL writes the quaternion with float precision), translated.
  const SensorCloud c = parse_sensor_cloud(
      organized_pcd(g, 4, 3, "ascii", "1 2 3 0.70710677 0 0 0.70710677"), "rotated.pcd");
  ASSERT_TRUE(c.viewpoint.has_value());
  EXPECT_TRUE(c.viewpoint->translation().isApprox(Eigen::Vector3d(1, 2, 3)));
  EXPECT_TRUE(
      (c.viewpoint->linear() * Eigen::Vector3d::UnitX()).isApprox(Eigen::Vector3d::UnitY(), 1e-6));
  EXPECT_NEAR(c.viewpoint->linear().determinant(), 1.0, 1e-12);
  // No VIEWPOINT line: no sensor origin.
  EXPECT_FALSE(parse_sensor_cloud(organized_pcd(g, 4, 3, "ascii", ""), "a.pcd").viewpoint);
  // Malformed ones are one-line input errors naming the file.
  for (const std::string vp :
       {"0 0 0 1 0 0", "0 0 0 2 0 0 0", "0 0 x 1 0 0 0", "0 0 inf 1 0 0 0"}) {
    const std::string msg =
        error_of([&] { parse_sensor_cloud(organized_pcd(g, 4, 3, "ascii", vp), "bad.pcd"); });
    EXPECT_NE(msg.find("bad.pcd: VIEWPOINT"), std::string::npos) << vp << ": " << msg;
  }
  // .ply and .xyz have none.
  EXPECT_FALSE(parse_sensor_cloud("0 0 1\n", "a.xyz").viewpoint);
}

TEST(SensorCloud, NaNIsSkippedInEveryFormat) {
  const std::string xyz = "0 0 1\nnan 0 1\n1 1 1\n";
  const std::string ply =
      "ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\nproperty float y\n"
      "property float z\nend_header\n0 0 1\nnan nan nan\n1 1 1\n";
  const std::string pcd =
      "VERSION 0.7\nFIELDS x y z\nSIZE 4 4 4\nTYPE F F F\nCOUNT 1 1 1\nWIDTH 3\nHEIGHT 1\n"
      "POINTS 3\nDATA ascii\n0 0 1\nnan nan nan\n1 1 1\n";
  for (const auto& [name, data] : {std::pair{"a.xyz", xyz}, {"a.ply", ply}, {"a.pcd", pcd}}) {
    SCOPED_TRACE(name);
    const SensorCloud c = parse_sensor_cloud(data, name);
    EXPECT_FALSE(c.organized());
    ASSERT_EQ(c.points.size(), 2u);
    EXPECT_EQ(c.width, 2);
    EXPECT_EQ(c.points[1], Eigen::Vector3d(1, 1, 1));
  }
  // Infinity is still an error; so is a file of NaN only.
  EXPECT_NE(error_of([] { parse_sensor_cloud("0 0 1\ninf 0 1\n", "inf.xyz"); }).find("infinite"),
            std::string::npos);
  EXPECT_EQ(error_of([] {
              parse_sensor_cloud("nan 0 1\n0 nan 1\n", "nan.xyz");
            }).rfind("nan.xyz: no valid point", 0),
            0u);
  PointCloud all_nan(12, Eigen::Vector3d::Constant(kNaN));
  EXPECT_NE(error_of([&] {
              parse_sensor_cloud(organized_pcd(all_nan, 4, 3, "binary"), "nan.pcd");
            }).find("no valid point"),
            std::string::npos);
  // Other extensions are refused; read_geometry keeps rejecting NaN in a .xyz.
  EXPECT_NE(error_of([] { parse_sensor_cloud("v 0 0 0\n", "a.obj"); }).find("unknown cloud file"),
            std::string::npos);
  EXPECT_NE(error_of([&] { parse_geometry(xyz, "a.xyz"); }).find("NaN"), std::string::npos);
}

TEST(SensorCloud, MillimetresAreRefusedWithAHint) {
  PointCloud table;  // a 1.2 m x 0.8 m table seen from 1 m, in metres
  std::mt19937 rng(3);
  std::uniform_real_distribution<double> uni(-0.5, 0.5);
  for (int i = 0; i < 2000; ++i)
    table.emplace_back(1.2 * uni(rng), 0.8 * uni(rng), 1.0 + 0.1 * uni(rng));
  table.emplace_back(0, 0, 40.0);  // a stray reading far away does not matter
  EXPECT_NO_THROW(check_metric_units(table, "table.pcd"));
  PointCloud mm = table;
  for (auto& p : mm) p *= 1000.0;
  const std::string msg = error_of([&] { check_metric_units(mm, "mm.pcd"); });
  EXPECT_NE(msg.find("mm.pcd: the cloud spans "), std::string::npos) << msg;
  EXPECT_NE(msg.find(" m: it looks like millimetres; scale it to metres (x 0.001)"),
            std::string::npos)
      << msg;
  EXPECT_EQ(error_of([] {
              check_metric_units({{0, 0, 0}, {1234.5, 0, 0}}, "a.xyz");
            }),
            "a.xyz: the cloud spans 1234.5 m: it looks like millimetres; scale it to metres (x "
            "0.001)");
  // A small object in millimetres, 900 mm from the sensor: caught by its distance.
  PointCloud cup;
  for (int i = 0; i < 100; ++i) cup.emplace_back(0.1 * (i % 10), 0.1 * (i / 10), 900.0);
  EXPECT_NE(error_of([&] { check_metric_units(cup, "cup.xyz"); })
                .find("cup.xyz: the points lie a median 900.0 m from the sensor: it looks like "
                      "millimetres"),
            std::string::npos);
}

// A rendered view of a torus over a table with deliberately unequal, off-centre intrinsics, and
// its pixels as an organized cloud in the camera frame.
CameraModel test_camera() {
  CameraModel c = look_at_camera({0.9, -0.4, 0.7}, {0, 0, 0.1}, 0.3, 320, 240);
  c.fx = 310.25;
  c.fy = 287.5;
  c.cx = 163.75;
  c.cy = 114.125;
  return c;
}

SensorCloud camera_frame_grid(const CameraModel& c, const DepthImage& img) {
  SensorCloud s;
  s.width = img.width;
  s.height = img.height;
  for (int v = 0; v < img.height; ++v)
    for (int u = 0; u < img.width; ++u) {
      const double z = img.at(u, v);
      s.points.push_back(z > 0 ? Eigen::Vector3d((u - c.cx) * z / c.fx, (v - c.cy) * z / c.fy, z)
                               : Eigen::Vector3d::Constant(kNaN));
    }
  return s;
}

DepthView rendered_view() {
  TriangleMesh scene = objects::torus_mesh(0.12, 0.04);
  for (auto& p : scene.vertices) p.z() += 0.1;
  const TriangleMesh table = objects::ground_plane(1.0);
  const int offset = static_cast<int>(scene.vertices.size());
  scene.vertices.insert(scene.vertices.end(), table.vertices.begin(), table.vertices.end());
  for (auto t : table.triangles)
    scene.triangles.push_back({t[0] + offset, t[1] + offset, t[2] + offset});
  DepthView view;
  view.camera = test_camera();
  view.image = render_depth(scene, view.camera);
  return view;
}

void expect_relative(double got, double want, double rel, const char* what) {
  EXPECT_NEAR(got, want, rel * std::abs(want)) << what;
}

TEST(SensorCloud, FitPinholeRecoversRenderedIntrinsics) {
  const DepthView view = rendered_view();
  SensorCloud grid = camera_frame_grid(view.camera, view.image);
  ASSERT_GT(view.image.valid_count(), 1000);
  PinholeResiduals r;
  CameraModel fit = fit_pinhole(grid, "render", &r);
  EXPECT_EQ(fit.width, 320);
  EXPECT_EQ(fit.height, 240);
  EXPECT_EQ(r.pixels, view.image.valid_count());
  EXPECT_LT(r.rms_u, 1e-6);
  EXPECT_LT(r.rms_v, 1e-6);
  const auto expect_intrinsics = [](const CameraModel& fit) {
    expect_relative(fit.fx, 310.25, 1e-6, "fx");
    expect_relative(fit.fy, 287.5, 1e-6, "fy");
    expect_relative(fit.cx, 163.75, 1e-6, "cx");
    expect_relative(fit.cy, 114.125, 1e-6, "cy");
  };
  expect_intrinsics(fit);
  EXPECT_TRUE(fit.T_world_camera.isApprox(Eigen::Isometry3d::Identity()));
  // The same grid in a frame where the sensor sits at a rotated VIEWPOINT: same camera, there.
  Eigen::Isometry3d vp = Eigen::Isometry3d::Identity();
  vp.linear() = Eigen::AngleAxisd(0.7, Eigen::Vector3d(1, 2, -1).normalized()).toRotationMatrix();
  vp.translation() = Eigen::Vector3d(0.3, -2.0, 1.0);
  SensorCloud moved = grid;
  for (auto& p : moved.points) p = vp * p;
  moved.viewpoint = vp;
  fit = fit_pinhole(moved, "render");
  expect_intrinsics(fit);
  EXPECT_TRUE(fit.T_world_camera.isApprox(vp));
  // Points in the sensor frame under a VIEWPOINT that turns the sensor away from them (as in
  // PCL's table_scene_mug_stereo_textured.pcd): the VIEWPOINT is not the sensor pose.
  SensorCloud flipped = grid;
  flipped.viewpoint = Eigen::Isometry3d(Eigen::AngleAxisd(EIGEN_PI, Eigen::Vector3d::UnitX()));
  fit = fit_pinhole(flipped, "flipped");
  expect_intrinsics(fit);
  EXPECT_TRUE(fit.T_world_camera.isApprox(Eigen::Isometry3d::Identity()));
  const DepthView plain = organized_cloud_view(grid, Eigen::Isometry3d::Identity(), "g");
  EXPECT_EQ(organized_cloud_view(flipped, Eigen::Isometry3d::Identity(), "f").image.depth,
            plain.image.depth);
  // Points turned 180 degrees about x (y up, z backwards) under an identity VIEWPOINT (as in
  // milk_cartoon_all_small_clorox.pcd): the camera is that turn.
  SensorCloud turned = grid;
  const Eigen::Isometry3d turn(Eigen::AngleAxisd(EIGEN_PI, Eigen::Vector3d::UnitX()));
  for (auto& p : turned.points) p = turn * p;
  turned.viewpoint = Eigen::Isometry3d::Identity();
  fit = fit_pinhole(turned, "turned");
  expect_intrinsics(fit);
  EXPECT_TRUE(fit.T_world_camera.isApprox(turn));
  EXPECT_EQ(organized_cloud_view(turned, Eigen::Isometry3d::Identity(), "t").image.depth,
            plain.image.depth);
}

TEST(SensorCloud, FitPinholeRefusesWhatIsNoPinholeGrid) {
  const DepthView view = rendered_view();
  const SensorCloud grid = camera_frame_grid(view.camera, view.image);
  // Moved into another frame without saying so (no VIEWPOINT): not a projection of its grid.
  SensorCloud moved = grid;
  for (auto& p : moved.points)
    p = Eigen::AngleAxisd(0.5, Eigen::Vector3d::UnitY()) * p + Eigen::Vector3d(0.2, 0, 0.5);
  std::string msg = error_of([&] { fit_pinhole(moved, "moved.pcd"); });
  EXPECT_NE(msg.find("moved.pcd: the points are not a pinhole projection"), std::string::npos)
      << msg;
  EXPECT_NE(msg.find("must be in the sensor frame"), std::string::npos) << msg;
  // Mirrored x: a perfect fit with fx < 0.
  SensorCloud mirrored = grid;
  for (auto& p : mirrored.points) p.x() = -p.x();
  EXPECT_NE(error_of([&] { fit_pinhole(mirrored, "m"); }).find("not positive"), std::string::npos);
  // Too few pixels; no grid.
  SensorCloud sparse = grid;
  int kept = 0;
  for (auto& p : sparse.points)
    if (!p.hasNaN() && ++kept > 50) p = Eigen::Vector3d::Constant(kNaN);
  EXPECT_NE(error_of([&] { fit_pinhole(sparse, "s"); }).find("only 50 valid pixels"),
            std::string::npos);
  SensorCloud flat;
  flat.points = grid.valid_points();
  flat.width = static_cast<int>(flat.points.size());
  EXPECT_NE(error_of([&] { fit_pinhole(flat, "f"); }).find("not an organized cloud"),
            std::string::npos);
  SensorCloud mismatched = grid;
  mismatched.points.pop_back();
  EXPECT_NE(error_of([&] { fit_pinhole(mismatched, "x"); }).find("does not match"),
            std::string::npos);
}

TEST(SensorCloud, OrganizedCloudViewBackProjectsToTheWorldPoints) {
  const DepthView rendered = rendered_view();
  SensorCloud grid = camera_frame_grid(rendered.camera, rendered.image);
  Eigen::Isometry3d vp = Eigen::Isometry3d::Identity();
  vp.linear() =
      Eigen::AngleAxisd(-1.1, Eigen::Vector3d(0.3, 1, 0.2).normalized()).toRotationMatrix();
  vp.translation() = Eigen::Vector3d(-0.4, 0.1, 0.25);
  for (auto& p : grid.points) p = vp * p;
  grid.viewpoint = vp;
  Eigen::Isometry3d world = Eigen::Isometry3d::Identity();
  world.linear() = Eigen::AngleAxisd(2.0, Eigen::Vector3d::UnitZ()).toRotationMatrix();
  world.translation() = Eigen::Vector3d(1.5, 0.5, 0.8);

  const DepthView view = organized_cloud_view(grid, world, "grid");
  EXPECT_TRUE(view.camera.T_world_camera.isApprox(world * vp));
  EXPECT_EQ(view.image.valid_count(), rendered.image.valid_count());
  const PointCloud back = depth_to_points(view);
  const PointCloud want = grid.valid_points();
  ASSERT_EQ(back.size(), want.size());
  for (size_t i = 0; i < want.size(); ++i) {
    const Eigen::Vector3d w = world * want[i];
    ASSERT_LE((back[i] - w).norm(), 1e-6 * w.norm()) << i;
  }
}

// Random points on a box's faces and a sphere, in front of a sensor at `origin`.
PointCloud random_scene(int n, std::uint32_t seed) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> uni(-1.0, 1.0);
  PointCloud pts;
  for (int i = 0; i < n; ++i) {
    Eigen::Vector3d p(uni(rng), uni(rng), uni(rng));
    if (i % 2) {
      p = Eigen::Vector3d(2.0, 0.5, 0.3) + 0.2 * p.normalized();  // a sphere
    } else {
      p = Eigen::Vector3d(2.5 + 0.3 * p.x(), 0.8 * p.y(), 0.5 * p.z());  // a slab behind it
    }
    pts.push_back(p);
  }
  return pts;
}

TEST(SensorCloud, UnorganizedCloudViewSplatsTheNearestPoints) {
  const Eigen::Vector3d origin(0.1, -0.2, 0.6);
  const PointCloud pts = random_scene(20000, 5);
  const DepthView view = unorganized_cloud_view(pts, origin, "scene.xyz");
  const CameraModel& c = view.camera;
  EXPECT_EQ(c.width * 3, c.height * 4);
  EXPECT_NEAR(c.width * c.height, 20000, 0.1 * 20000);
  EXPECT_TRUE(c.position().isApprox(origin));
  EXPECT_DOUBLE_EQ(c.fx, c.fy);
  int nearest = 0;
  for (const auto& p : pts) {
    const Eigen::Vector3d uvz = c.project(p);
    const int u = static_cast<int>(std::lround(uvz.x())),
              v = static_cast<int>(std::lround(uvz.y()));
    ASSERT_TRUE(u >= 0 && u < c.width && v >= 0 && v < c.height) << uvz.transpose();
    const float z = view.image.at(u, v);
    ASSERT_GT(z, 0.0f);
    EXPECT_LE(z, static_cast<float>(uvz.z()));  // a z-buffer: nothing nearer is hidden
    if (z != static_cast<float>(uvz.z())) continue;
    ++nearest;
    // Back-projected at its pixel centre, within half a pixel's footprint in u and v.
    const double footprint = uvz.z() / c.fx;
    EXPECT_LE((c.back_project(u, v, z) - p).norm(), 0.5 * std::sqrt(2.0) * footprint + 1e-6);
  }
  EXPECT_EQ(nearest, view.image.valid_count());  // every written pixel is some point's
  EXPECT_GT(nearest, 5000);
  // Deterministic.
  EXPECT_EQ(unorganized_cloud_view(pts, origin, "scene.xyz").image.depth, view.image.depth);
}

TEST(SensorCloud, UnorganizedCloudViewSizeAndRefusals) {
  const Eigen::Vector3d origin = Eigen::Vector3d::Zero();
  const DepthView few = unorganized_cloud_view(random_scene(10, 1), origin, "few");
  EXPECT_EQ(few.camera.width, 64);
  EXPECT_EQ(few.camera.height, 48);
  const DepthView many = unorganized_cloud_view(random_scene(1'500'000, 2), origin, "many");
  EXPECT_EQ(many.camera.width, 1280);
  EXPECT_EQ(many.camera.height, 960);
  // The sensor inside the cloud: points behind it.
  EXPECT_NE(error_of([&] {
              unorganized_cloud_view(random_scene(100, 3), {2.0, 0.5, 0.3}, "in");
            }).find("in: point"),
            std::string::npos);
  // All points at one spot, or on one ray from the sensor.
  const PointCloud spot(5, Eigen::Vector3d(1, 2, 3));
  EXPECT_NE(error_of([&] { unorganized_cloud_view(spot, origin, "spot"); }).find("one spot"),
            std::string::npos);
  const PointCloud ray = {{1, 2, 3}, {2, 4, 6}, {3, 6, 9}};
  EXPECT_NE(error_of([&] { unorganized_cloud_view(ray, origin, "ray"); }).find("one spot"),
            std::string::npos);
  EXPECT_NE(error_of([&] { unorganized_cloud_view({}, origin, "none"); }).find("no points"),
            std::string::npos);
}

// The real captures shipped in examples/clouds/ (README there): each implies its camera.
TEST(SensorCloud, RealOrganizedCloudsFitAPinholeCamera) {
  int files = 0;
  std::set<std::filesystem::path> paths;
  for (const auto& entry : std::filesystem::directory_iterator(CLASPPLAN_EXAMPLE_CLOUDS))
    if (entry.path().extension() == ".pcd") paths.insert(entry.path());
  for (const auto& path : paths) {
    SCOPED_TRACE(path.string());
    const SensorCloud cloud = read_sensor_cloud(path.string());
    EXPECT_EQ(cloud.width, 640);
    EXPECT_EQ(cloud.height, 480);
    ASSERT_TRUE(cloud.viewpoint.has_value());
    EXPECT_TRUE(cloud.viewpoint->translation().isZero());
    EXPECT_NO_THROW(check_metric_units(cloud.valid_points(), path.string()));
    PinholeResiduals r;
    const CameraModel cam = fit_pinhole(cloud, path.string(), &r);
    // The sensor's frame: identity, or 180 degrees about x where the VIEWPOINT is wrong.
    const Eigen::Matrix3d R = cam.T_world_camera.linear();
    EXPECT_TRUE(R.isApprox(Eigen::Matrix3d::Identity()) ||
                R.isApprox(Eigen::Vector3d(1, -1, -1).asDiagonal().toDenseMatrix()))
        << R;
    std::cout << std::setprecision(9) << path.filename().string() << ": fx " << cam.fx << " fy "
              << cam.fy << " cx " << cam.cx << " cy " << cam.cy << " rms_u " << r.rms_u << " rms_v "
              << r.rms_v << " px, " << r.pixels << " valid pixels, camera turned "
              << (R(1, 1) < 0 ? "180 degrees about x" : "no") << "\n";
    EXPECT_LT(r.rms_u, 1.0);
    EXPECT_LT(r.rms_v, 1.0);
    EXPECT_GT(r.pixels, 100000);
    EXPECT_TRUE(cam.fx > 400 && cam.fx < 1200) << cam.fx;
    EXPECT_TRUE(cam.fy > 400 && cam.fy < 1200) << cam.fy;
    ++files;
  }
  EXPECT_EQ(files, 11);
}

TEST(SensorCloud, RealMugSceneBecomesADepthView) {
  const std::string path =
      std::string(CLASPPLAN_EXAMPLE_CLOUDS) + "/table_scene_mug_stereo_textured.pcd";
  const SensorCloud cloud = read_sensor_cloud(path);
  const DepthView view = organized_cloud_view(cloud, Eigen::Isometry3d::Identity(), path);
  const PointCloud want = cloud.valid_points();
  const PointCloud back = depth_to_points(view);
  ASSERT_EQ(back.size(), want.size());
  double worst = 0.0;  // the file's float32 points are a pinhole grid up to float rounding
  for (size_t i = 0; i < want.size(); ++i)
    worst = std::max(worst, (back[i] - want[i]).norm() / want[i].norm());
  EXPECT_LT(worst, 1e-4);
}

}  // namespace
}  // namespace claspplan::perception
