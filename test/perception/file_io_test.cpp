// Readers and writers: round trips in every format, and every kind of bad file rejected with a
// one-line reason naming the file.
#include "core/file_io.hpp"

#include <cmath>
#include <cstdint>
#include <fstream>

#include <gtest/gtest.h>
#include <opencv2/core.hpp>
#include <opencv2/imgcodecs.hpp>

#include "examples/objects.hpp"
#include "perception/camera.hpp"
#include "test/support/temp_dir.hpp"

namespace claspplan::perception {
namespace {

using test::TempDir;

template <class F>
std::string error_of(F&& f) {
  try {
    f();
  } catch (const std::invalid_argument& e) {
    return e.what();
  }
  return "";
}

// A one-line reason that names the file.
void expect_rejected(const std::string& path, const std::string& fragment = "") {
  const std::string msg = error_of([&] { read_geometry(path); });
  ASSERT_FALSE(msg.empty()) << path << " was accepted";
  EXPECT_EQ(msg.find('\n'), std::string::npos) << msg;
  EXPECT_NE(msg.find(path), std::string::npos) << msg;
  if (!fragment.empty()) {
    EXPECT_NE(msg.find(fragment), std::string::npos) << msg;
  }
}

PointCloud small_cloud() {
  return {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {0, 0, 1}, {0.25, -0.5, 1e-3}};
}

TEST(FileIo, CloudRoundTrips) {
  TempDir dir;
  const PointCloud c = small_cloud();
  write_xyz(c, dir.file("a.xyz"));
  write_pcd(c, dir.file("a.pcd"), false);
  write_pcd(c, dir.file("b.pcd"), true);
  write_ply(c, dir.file("a.ply"), false);
  write_ply(c, dir.file("b.ply"), true);
  for (const char* name : {"a.xyz", "a.pcd", "a.ply", "b.ply"}) {
    const GeometryFile g = read_geometry(dir.file(name));
    EXPECT_FALSE(g.is_mesh) << name;
    ASSERT_EQ(g.cloud.size(), c.size()) << name;
    for (size_t i = 0; i < c.size(); ++i) EXPECT_EQ(g.cloud[i], c[i]) << name;
  }
  const PointCloud f = read_pcd(dir.file("b.pcd"));  // float32 binary
  for (size_t i = 0; i < c.size(); ++i) EXPECT_NEAR((f[i] - c[i]).norm(), 0.0, 1e-7);
}

TEST(FileIo, MeshRoundTrips) {
  TempDir dir;
  const TriangleMesh m = objects::torus_mesh(0.1, 0.03, Eigen::Isometry3d::Identity(), 12, 8);
  write_obj(m, dir.file("t.obj"));
  write_off(m, dir.file("t.off"));
  write_ply(m, dir.file("t.ply"), true);
  write_ply(m, dir.file("ta.ply"), false);
  write_stl(m, dir.file("t.stl"), true);
  write_stl(m, dir.file("ta.stl"), false);
  for (const char* name : {"t.obj", "t.off", "t.ply", "ta.ply", "t.stl", "ta.stl"}) {
    const GeometryFile g = read_geometry(dir.file(name));
    ASSERT_TRUE(g.is_mesh) << name;
    EXPECT_EQ(g.mesh.triangles.size(), m.triangles.size()) << name;
    EXPECT_EQ(g.mesh.vertices.size(), m.vertices.size()) << name;  // STL: equal vertices merged
    EXPECT_TRUE(is_watertight(g.mesh)) << name;
    EXPECT_NEAR(surface_area(g.mesh), surface_area(m), 1e-6) << name;
  }
}

TEST(FileIo, HandWrittenFormats) {
  TempDir dir;
  // OBJ with polygons, slashes, negative indices and comments: a quad fanned into 2 triangles.
  const auto obj = dir.write("q.obj",
                             "# quad\nv 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\nvn 0 0 1\n"
                             "f 1/1/1 2//1 -2 -1\n");
  EXPECT_EQ(read_obj(obj).triangles.size(), 2u);
  // OFF with comments and per-face colours.
  const auto off =
      dir.write("q.off", "OFF # comment\n4 1 0\n0 0 0\n1 0 0\n1 1 0\n0 1 0\n4 0 1 2 3 255 0 0\n");
  EXPECT_EQ(read_off(off).triangles.size(), 2u);
  // XYZ with commas, extra columns and comments.
  const auto xyz = dir.write("p.xyz", "# x y z\n1,2,3\n4 5 6 0.1 0.2 # normal\n\n");
  const PointCloud p = read_xyz(xyz);
  ASSERT_EQ(p.size(), 2u);
  EXPECT_EQ(p[1], Eigen::Vector3d(4, 5, 6));
  // PCD with an extra field and an organized cloud whose NaN points mean "no reading".
  const auto pcd = dir.write("o.pcd",
                             "VERSION 0.7\nFIELDS x y z rgb\nSIZE 4 4 4 4\nTYPE F F F U\n"
                             "COUNT 1 1 1 1\nWIDTH 2\nHEIGHT 2\nVIEWPOINT 0 0 0 1 0 0 0\n"
                             "POINTS 4\nDATA ascii\n0 0 1 0\nnan nan nan 0\n1 0 1 0\n0 1 1 0\n");
  EXPECT_EQ(read_pcd(pcd).size(), 3u);
}

TEST(FileIo, BadFilesAreRejected) {
  TempDir dir;
  const PointCloud c = small_cloud();
  expect_rejected(dir.file("missing.xyz"), "not found");
  expect_rejected(dir.write("empty.ply", ""), "empty");
  expect_rejected(dir.write("empty.xyz", "# only a comment\n"), "no points");
  expect_rejected(dir.write("a.txt", "1 2 3\n"), "unknown file type");
  expect_rejected(dir.write("nan.xyz", "0 0 0\n1 nan 0\n"), "NaN");
  expect_rejected(dir.write("inf.xyz", "0 0 0\n1 inf 0\n"), "NaN or infinite");
  expect_rejected(dir.write("short.xyz", "0 0\n"), "expected");
  expect_rejected(dir.write("garbage.pcd", std::string("\x01\x02garbage\xff", 11)));
  expect_rejected(dir.write("garbage.ply", "not a ply\n"), "not a PLY");
  expect_rejected(dir.write("garbage.off", "OF\n"), "not an OFF");
  expect_rejected(dir.write("garbage.stl", "hello"), "not an STL");
  expect_rejected(dir.write("garbage.obj", "\x01\x02\x03 4 5\n"), "not an OBJ");
  // Absurd declared counts must not allocate or hang (PCL's reader hangs on these).
  expect_rejected(dir.write("huge.ply",
                            "ply\nformat binary_little_endian 1.0\nelement vertex 100000000000\n"
                            "property float x\nproperty float y\nproperty float z\nend_header\n"),
                  "absurd");
  expect_rejected(dir.write("huge2.ply",
                            "ply\nformat binary_little_endian 1.0\nelement vertex 40000000\n"
                            "property float x\nproperty float y\nproperty float z\nend_header\n"
                            "abcdefghijkl"),
                  "truncated");
  expect_rejected(dir.write("huge.pcd",
                            "VERSION 0.7\nFIELDS x y z\nSIZE 4 4 4\nTYPE F F F\nCOUNT 1 1 1\n"
                            "WIDTH 900000000000\nHEIGHT 1\nPOINTS 900000000000\nDATA binary\n"),
                  "absurd");
  expect_rejected(dir.write("huge.off", "OFF\n40000000 40000000 0\n0 0 0\n"), "truncated");
  // Truncated files of every format.
  write_pcd(c, dir.file("t.pcd"), true);
  write_ply(c, dir.file("t.ply"), true);
  write_ply(c, dir.file("ta.ply"), false);
  write_stl(objects::sphere_mesh(1.0, Eigen::Vector3d::Zero(), 8, 4), dir.file("t.stl"), true);
  write_stl(objects::sphere_mesh(1.0, Eigen::Vector3d::Zero(), 8, 4), dir.file("ta.stl"), false);
  write_off(objects::sphere_mesh(1.0, Eigen::Vector3d::Zero(), 8, 4), dir.file("t.off"));
  for (const char* name : {"t.pcd", "t.ply", "ta.ply", "t.stl", "ta.stl", "t.off"}) {
    std::string data = test::slurp(dir.file(name));
    data.resize(data.size() - 20);
    expect_rejected(dir.write(std::string("cut_") + name, data));
  }
  // Face indices out of range.
  expect_rejected(dir.write("bad.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 4\n"), "vertex");
}

TEST(Camera, YamlRoundTripAndValidation) {
  TempDir dir;
  const CameraModel cam = objects::kinect_camera({0.3, -0.7, 0.6}, {0, 0, 0.15});
  write_camera_yaml(cam, dir.file("cam.yaml"));
  const CameraModel back = read_camera_yaml(dir.file("cam.yaml"));
  EXPECT_EQ(back.width, 640);
  EXPECT_DOUBLE_EQ(back.fx, 525.0);
  EXPECT_NEAR((back.T_world_camera.matrix() - cam.T_world_camera.matrix()).norm(), 0.0, 1e-12);
  // The optical frame: a point on the camera's z axis projects to the principal point.
  const Eigen::Vector3d ahead = cam.T_world_camera * Eigen::Vector3d(0, 0, 2.0);
  const Eigen::Vector3d uvz = cam.project(ahead);
  EXPECT_NEAR(uvz.x(), cam.cx, 1e-9);
  EXPECT_NEAR(uvz.y(), cam.cy, 1e-9);
  EXPECT_NEAR(uvz.z(), 2.0, 1e-12);
  EXPECT_NEAR((cam.back_project(uvz.x(), uvz.y(), uvz.z()) - ahead).norm(), 0.0, 1e-12);

  const std::string good = test::slurp(dir.file("cam.yaml"));
  auto with = [&](const std::string& from, const std::string& to) {
    std::string s = good;
    const size_t at = s.find(from);
    EXPECT_NE(at, std::string::npos) << from;
    s.replace(at, from.size(), to);
    return dir.write("bad.yaml", s);
  };
  const std::string fx = error_of([&] { read_camera_yaml(with("fx: 525", "fx: -3")); });
  EXPECT_NE(fx.find("fx must be > 0, got -3"), std::string::npos) << fx;
  EXPECT_NE(error_of([&] { read_camera_yaml(with("width: 640", "width: 0")); }).find("width"),
            std::string::npos);
  EXPECT_NE(error_of([&] {
              read_camera_yaml(with("depth_scale:", "depth_scal:"));
            }).find("unknown key 'depth_scal'"),
            std::string::npos);
  EXPECT_NE(error_of([&] { read_camera_yaml(with("fy: 525", "fy: abc")); }).find("number"),
            std::string::npos);
  EXPECT_NE(error_of([&] {
              read_camera_yaml(dir.write("list.yaml", "T_world_camera: [1, 2]\n"));
            }).find("missing"),
            std::string::npos);
  EXPECT_NE(error_of([&] { read_camera_yaml(dir.write("broken.yaml", "fx: [1,\n")); }).find("YAML"),
            std::string::npos);
  EXPECT_NE(error_of([&] { read_camera_yaml(dir.file("none.yaml")); }).find("not found"),
            std::string::npos);
  CameraModel skew = cam;
  skew.T_world_camera.matrix()(0, 0) *= 1.5;
  EXPECT_NE(error_of([&] { validate_camera(skew, "c"); }).find("orthonormal"), std::string::npos);
}

TEST(Camera, DepthPngRoundTripAndBadImages) {
  TempDir dir;
  CameraModel cam;
  cam.width = 4;
  cam.height = 3;
  cam.depth_scale = 0.001;
  DepthImage img(4, 3);
  img.at(1, 1) = 0.5f;
  img.at(3, 2) = 1.234f;
  img.at(0, 0) = 70.0f;  // beyond 65535 units: written as no reading
  write_depth_png(img, cam, dir.file("d.png"));
  const DepthImage back = read_depth_png(dir.file("d.png"), cam);
  EXPECT_FLOAT_EQ(back.at(1, 1), 0.5f);
  EXPECT_NEAR(back.at(3, 2), 1.234, 1e-6);
  EXPECT_EQ(back.at(0, 0), 0.0f);
  EXPECT_EQ(back.valid_count(), 2);

  auto err = [&](const std::string& path) { return error_of([&] { read_depth_png(path, cam); }); };
  EXPECT_NE(err(dir.file("none.png")).find("not found"), std::string::npos);
  EXPECT_NE(err(dir.write("text.png", "hello")).find("not a PNG"), std::string::npos);
  std::string data = test::slurp(dir.file("d.png"));
  EXPECT_NE(err(dir.write("cut.png", data.substr(0, data.size() / 2))).find("decode"),
            std::string::npos);
  cv::imwrite(dir.file("eight.png"), cv::Mat(3, 4, CV_8UC1, cv::Scalar(7)));
  EXPECT_NE(err(dir.file("eight.png")).find("16-bit"), std::string::npos);
  cv::imwrite(dir.file("big.png"), cv::Mat(5, 4, CV_16UC1, cv::Scalar(7)));
  EXPECT_NE(err(dir.file("big.png")).find("4x3"), std::string::npos);
}

}  // namespace
}  // namespace claspplan::perception
