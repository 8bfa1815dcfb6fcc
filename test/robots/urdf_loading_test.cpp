// Public URDFs as they are (issue 35): mesh collision geometry (STL, OBJ, COLLADA) found through
// package://, file:// and relative URIs, and placeholder geometry skipped with a warning. Each
// case edits one collision element of the built-in SDH's URDF and writes the files it names.
#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <random>
#include <string>

#include <gtest/gtest.h>
#include <unistd.h>

#include "core/file_io.hpp"
#include "core/mesh.hpp"
#include "robots/collision_world.hpp"
#include "robots/convex_hull.hpp"
#include "robots/embedded_models.hpp"
#include "robots/hand_size.hpp"
#include "robots/kinematics.hpp"
#include "robots/robot_model.hpp"

namespace claspplan::robots {
namespace {

namespace fs = std::filesystem;

const std::string kPalmBox = "<box size=\"0.113 0.122 0.077\"/>";

std::string replaced(std::string text, const std::string& from, const std::string& to) {
  const size_t at = text.find(from);
  EXPECT_NE(at, std::string::npos) << "test setup: '" << from << "' not found";
  if (at != std::string::npos) text.replace(at, from.size(), to);
  return text;
}

// A unit cube centred at the origin.
TriangleMesh unit_cube() {
  return box_mesh(Eigen::Vector3d::Ones());
}

// The cube stretched to twice its height, as COLLADA in millimetres (<unit meter="0.001">, Z_UP,
// as CAD exports write it).
std::string cube_dae() {
  std::string positions, indices;
  const TriangleMesh c = unit_cube();
  for (const auto& v : c.vertices)
    for (int k = 0; k < 3; ++k)
      positions += std::to_string((k == 2 ? 2000.0 : 1000.0) * v[k]) + " ";
  for (const auto& t : c.triangles)
    for (int k = 0; k < 3; ++k) indices += std::to_string(t[k]) + " ";
  return R"(<?xml version="1.0" encoding="utf-8"?>
<COLLADA xmlns="http://www.collada.org/2005/11/COLLADASchema" version="1.4.1">
  <asset><unit name="millimeter" meter="0.001"/><up_axis>Z_UP</up_axis></asset>
  <library_geometries><geometry id="cube" name="cube"><mesh>
    <source id="cube-pos"><float_array id="cube-pos-array" count="24">)" +
         positions + R"(</float_array>
      <technique_common><accessor source="#cube-pos-array" count="8" stride="3">
        <param name="X" type="float"/><param name="Y" type="float"/><param name="Z" type="float"/>
      </accessor></technique_common></source>
    <vertices id="cube-vtx"><input semantic="POSITION" source="#cube-pos"/></vertices>
    <triangles count="12"><input semantic="VERTEX" source="#cube-vtx" offset="0"/><p>)" +
         indices + R"(</p></triangles>
  </mesh></geometry></library_geometries>
  <library_visual_scenes><visual_scene id="scene"><node id="cube-node">
    <instance_geometry url="#cube"/></node></visual_scene></library_visual_scenes>
  <scene><instance_visual_scene url="#scene"/></scene>
</COLLADA>
)";
}

class Folder {
 public:
  Folder() {
    std::mt19937_64 rng(
        std::hash<std::string>()(::testing::UnitTest::GetInstance()->current_test_info()->name()));
    path_ = fs::temp_directory_path() /
            ("claspplan-urdf-" + std::to_string(rng()) + std::to_string(::getpid()));
    fs::create_directories(path_);
  }
  ~Folder() {
    std::error_code ec;
    fs::remove_all(path_, ec);
  }
  std::string write(const std::string& name, const std::string& text) const {
    const fs::path p = path_ / name;
    fs::create_directories(p.parent_path());
    std::ofstream(p, std::ios::binary) << text;
    return p.string();
  }
  std::string path(const std::string& name) const {
    fs::create_directories((path_ / name).parent_path());
    return (path_ / name).string();
  }

  // The SDH with its palm's <box> replaced by `geometry`; returns the hand description's path.
  std::string robot(const std::string& geometry, const std::string& folder = "robot") const {
    write(folder + "/kr5_sdh.urdf",
          replaced(embedded_model_file("kr5_sdh.urdf"), kPalmBox, geometry));
    return write(folder + "/kr5_sdh.yaml", embedded_model_file("kr5_sdh.yaml"));
  }

 private:
  fs::path path_;
};

// Sets an environment variable for one scope.
class Env {
 public:
  Env(const char* name, const std::string& value) : name_(name) {
    if (const char* old = std::getenv(name)) old_ = old;
    ::setenv(name, value.c_str(), 1);
  }
  ~Env() {
    if (old_.empty())
      ::unsetenv(name_);
    else
      ::setenv(name_, old_.c_str(), 1);
  }

 private:
  const char* name_;
  std::string old_;
};

std::string load_error(const std::string& path) {
  try {
    load_robot(path);
  } catch (const InputError& e) {
    return e.what();
  }
  return "";
}

const CollisionShape& palm_shape(const RobotModel& m) {
  return m.shapes[m.links[m.link_index("sdh_palm_link")].shapes.at(0)];
}

// A palm given as a scaled unit-cube mesh collides where the palm's box does: against a box
// swept through the hand's workspace, at 400 random configurations.
TEST(UrdfLoading, AMeshCollidesWhereTheSameBoxDoes) {
  Folder dir;
  write_stl(unit_cube(), dir.path("robot/meshes/cube.stl"));
  const RobotModel box = load_robot("kr5_sdh");
  const RobotModel mesh =
      load_robot(dir.robot("<mesh filename=\"meshes/cube.stl\" scale=\"0.113 0.122 0.077\"/>"));
  ASSERT_EQ(palm_shape(mesh).type, CollisionShape::Type::kMesh);
  EXPECT_TRUE(mesh.warnings.empty());
  EXPECT_TRUE(shape_bounds(palm_shape(mesh)).isApprox(shape_bounds(palm_shape(box)), 1e-6));
  EXPECT_EQ(hand_size(mesh).finger_thickness, hand_size(box).finger_thickness);

  CollisionWorld wb(box), wm(mesh);
  wb.set_self_collision(false);
  wm.set_self_collision(false);
  std::mt19937_64 rng(7);
  std::uniform_real_distribution<double> u(0.0, 1.0);
  int hits = 0, agree = 0, n = 400;
  for (int i = 0; i < n; ++i) {
    Eigen::VectorXd q = box.home;
    for (int j = 0; j < box.arm_dof; ++j)
      q[j] = box.joints[j].lower + u(rng) * (box.joints[j].upper - box.joints[j].lower);
    RobotData data(box);
    forward_kinematics(box, q, data);
    // A thin slab through the palm's centre, at a random height offset: half the draws touch.
    const Eigen::Vector3d palm = data.link_poses[box.link_index("sdh_palm_link")].translation();
    Eigen::Isometry3d pose = Eigen::Isometry3d::Identity();
    pose.translation() = palm + Eigen::Vector3d(0, 0, (u(rng) - 0.5) * 0.25);
    wb.clear_environment();
    wm.clear_environment();
    wb.add_box(pose, Eigen::Vector3d(2, 2, 0.01));
    wm.add_box(pose, Eigen::Vector3d(2, 2, 0.01));
    const bool b = wb.in_collision(q), m = wm.in_collision(q);
    hits += b;
    agree += b == m;
  }
  EXPECT_GT(hits, n / 10);
  EXPECT_EQ(agree, n);
}

// A mesh link meets the object (in both of its collision trees: FCL collides two meshes only in
// one kind of bounding volume), unseen-space voxels and the object's clearance test. A mesh is a
// surface: what lies wholly inside it is not met (as in every mesh-based checker), so the test's
// object crosses the palm's face.
TEST(UrdfLoading, AMeshMeetsTheObjectInBothTreesAndTheVoxels) {
  Folder dir;
  write_stl(unit_cube(), dir.path("robot/meshes/cube.stl"));
  const RobotModel m =
      load_robot(dir.robot("<mesh filename=\"meshes/cube.stl\" scale=\"0.113 0.122 0.077\"/>"));
  const int palm = m.link_index("sdh_palm_link");
  RobotData data(m);
  forward_kinematics(m, m.home, data);
  const Eigen::Isometry3d pose = data.link_poses[palm] * palm_shape(m).origin;
  // A 1 cm cube of the object across the palm's face, then 2 cm outside it.
  const TriangleMesh small = transformed(unit_cube(), Eigen::Isometry3d(Eigen::Scaling(0.01)));
  for (const bool exact : {false, true}) {
    for (const double offset : {0.0385, 0.0385 + 0.02}) {
      CollisionWorld world(m);
      world.set_self_collision(false);
      world.set_exact_round_shapes(exact);
      world.set_object(transformed(small, pose * Eigen::Translation3d(0, 0, offset)).vertices,
                       small.triangles);
      const bool inside = offset < 0.04;
      EXPECT_EQ(world.in_collision(m.home), inside) << "exact " << exact << " offset " << offset;
      EXPECT_TRUE(world.link_near_object(data, palm, 0.03)) << exact;
      EXPECT_EQ(world.link_near_object(data, palm, 0.001), inside) << exact;
    }
  }
  CollisionWorld world(m);
  world.set_self_collision(false);
  const Eigen::Vector3d face = pose * Eigen::Vector3d(0, 0, 0.0385);
  std::vector<Eigen::Vector3d> voxels;  // 3 x 3 x 3 voxels of 5 mm around a point on the face
  for (int i = -1; i <= 1; ++i)
    for (int j = -1; j <= 1; ++j)
      for (int k = -1; k <= 1; ++k)
        voxels.push_back(((face / 0.005).array().round().matrix() + Eigen::Vector3d(i, j, k)) *
                         0.005);
  world.add_voxels(voxels, 0.005);
  EXPECT_TRUE(world.in_collision(m.home));
}

// package:// found beside the URDF's folders (a description package's own layout) and through
// CLASPPLAN_PACKAGE_PATH (a workspace's src/<group>/<package>); COLLADA in millimetres.
TEST(UrdfLoading, PackageUrisAreFoundThroughTheSearchPath) {
  Folder dir;
  dir.write("sdh_description/meshes/palm.dae", cube_dae());
  const RobotModel beside = load_robot(dir.robot(
      "<mesh filename=\"package://sdh_description/meshes/palm.dae\" scale=\"0.113 0.122 0.077\"/>",
      "sdh_description/urdf"));
  const Eigen::AlignedBox3d b = shape_bounds(palm_shape(beside));
  EXPECT_NEAR(b.sizes().x(), 0.113, 1e-6) << "the file's unit (mm) and the URDF's scale";
  EXPECT_NEAR(b.sizes().z(), 2 * 0.077, 1e-6) << "Z up as written, not turned to Y up";
  // package:///PACKAGE/PATH, as Talos' URDF writes it, names the same file.
  const RobotModel triple = load_robot(dir.robot(
      "<mesh filename=\"package:///sdh_description/meshes/palm.dae\" scale=\"0.113 0.122 0.077\"/>",
      "sdh_description/urdf"));
  EXPECT_NEAR(shape_bounds(palm_shape(triple)).sizes().x(), 0.113, 1e-6);

  write_obj(unit_cube(), dir.path("ws/src/hands/sdh_meshes/collision/palm.obj"));
  const std::string yaml = dir.robot(
      "<mesh filename=\"package://sdh_meshes/collision/palm.obj\" scale=\"0.1 0.1 0.1\"/>");
  const std::string missing = load_error(yaml);
  EXPECT_NE(missing.find("package://sdh_meshes/collision/palm.obj' not found"), std::string::npos)
      << missing;
  EXPECT_NE(missing.find("CLASPPLAN_PACKAGE_PATH"), std::string::npos) << missing;
  EXPECT_EQ(missing.find('\n'), std::string::npos);
  {
    Env path("CLASPPLAN_PACKAGE_PATH", "/nonexistent:" + dir.path("ws"));
    const RobotModel m = load_robot(yaml);
    EXPECT_NEAR(shape_bounds(palm_shape(m)).sizes().y(), 0.1, 1e-9);
  }
  // file:// and an absolute path.
  const std::string stl = dir.path("elsewhere/palm.stl");
  write_stl(unit_cube(), stl);
  EXPECT_EQ(palm_shape(load_robot(dir.robot("<mesh filename=\"file://" + stl + "\"/>"))).type,
            CollisionShape::Type::kMesh);
  EXPECT_NE(load_error(dir.robot("<mesh filename=\"http://example.com/palm.stl\"/>"))
                .find("only package://, file:// and file paths"),
            std::string::npos);
}

// Placeholder geometry (zero sizes, a mesh without a file) is skipped with a warning naming the
// link; a negative or non-finite size and a corrupt mesh file are errors.
TEST(UrdfLoading, PlaceholderGeometryIsSkippedWithAWarning) {
  Folder dir;
  for (const std::string& placeholder :
       {std::string("<sphere radius=\"0\"/>"), std::string("<box size=\"0 0 0\"/>"),
        std::string("<cylinder radius=\"0.01\" length=\"0\"/>"),
        std::string("<mesh filename=\"\"/>")}) {
    const RobotModel m = load_robot(dir.robot(placeholder));
    EXPECT_TRUE(m.links[m.link_index("sdh_palm_link")].shapes.empty()) << placeholder;
    ASSERT_EQ(m.warnings.size(), 1u) << placeholder;
    EXPECT_NE(m.warnings[0].find("link 'sdh_palm_link'"), std::string::npos) << m.warnings[0];
    EXPECT_NE(m.warnings[0].find("placeholder geometry, skipped"), std::string::npos);
  }
  EXPECT_NE(load_error(dir.robot("<sphere radius=\"-0.1\"/>")).find("must be finite and > 0"),
            std::string::npos);
  dir.write("robot/bad.stl", "solid x\nfacet normal 0 0 1\nouter loop\nvertex 0 0\n");
  const std::string corrupt = load_error(dir.robot("<mesh filename=\"bad.stl\"/>"));
  EXPECT_NE(corrupt.find("bad.stl"), std::string::npos) << corrupt;
  EXPECT_EQ(corrupt.find('\n'), std::string::npos) << corrupt;
  dir.write("robot/bad.dae", "<COLLADA><library_geometries>");
  EXPECT_NE(load_error(dir.robot("<mesh filename=\"bad.dae\"/>")).find("bad.dae"),
            std::string::npos);
}

// An arm and a hand from two URDFs (as public descriptions come): the built-in SDH robot split
// into the KR5's URDF and the hand's, joined by hand_urdf, is the same robot.
TEST(UrdfLoading, AHandFromItsOwnUrdfIsMountedOnAnArmLink) {
  Folder dir;
  const std::string urdf = embedded_model_file("kr5_sdh.urdf");
  const std::size_t split = urdf.find("  <!-- Schunk SDH");
  const std::size_t mount = urdf.find("  <joint name=\"tool0-sdh_base\"");
  const std::size_t mount_end = urdf.find("</joint>", mount) + 9;
  ASSERT_NE(split, std::string::npos);
  ASSERT_NE(mount, std::string::npos);
  dir.write("r/kr5.urdf", urdf.substr(0, split) + "</robot>\n");
  dir.write("r/hands/sdh.urdf",
            "<robot name=\"sdh\">\n" + urdf.substr(split, mount - split) + urdf.substr(mount_end));
  std::string yaml = embedded_model_file("kr5_sdh.yaml");
  yaml.replace(yaml.find("urdf: kr5_sdh.urdf"), 18,
               "urdf: kr5.urdf\nhand_urdf: {file: hands/sdh.urdf, parent: tool0, rpy: [0, 0, 0]}");
  const RobotModel two = load_robot(dir.write("r/two.yaml", yaml));
  const RobotModel one = load_robot("kr5_sdh");
  ASSERT_EQ(two.dof(), one.dof());
  EXPECT_EQ(two.links[two.link_index("sdh_base")].joint, "tool0_to_sdh_base");
  RobotData d1(one), d2(two);
  FingerCurvesData c1, c2;
  finger_curves(one, one.home, d1, c1, false);
  finger_curves(two, two.home, d2, c2, false);
  ASSERT_EQ(c1.points.size(), c2.points.size());
  for (std::size_t c = 0; c < c1.points.size(); ++c)
    for (std::size_t i = 0; i < c1.points[c].size(); ++i)
      EXPECT_LT((c1.points[c][i] - c2.points[c][i]).norm(), 1e-12);
  // The arm's own gripper left out (`replaces`): here the KR5's flange and what hangs below it, so
  // the hand's mount on tool0 has nothing to hold it; a link not in the arm's URDF is an error.
  std::string replaces = yaml;
  replaces.replace(replaces.find("rpy: [0, 0, 0]}"), 15, "replaces: [nope]}");
  EXPECT_NE(load_error(dir.write("r/replaces.yaml", replaces))
                .find("hand_urdf.replaces: 'nope' is not a link below the URDF's root"),
            std::string::npos);
  replaces = yaml;
  replaces.replace(replaces.find("rpy: [0, 0, 0]}"), 15, "replaces: flange}");
  EXPECT_NE(load_error(dir.write("r/flange.yaml", replaces)).find("unknown link 'tool0'"),
            std::string::npos);
  // Mounted twice, every link name repeats: an error naming it.
  yaml.replace(yaml.find("urdf: kr5.urdf"), 14, "urdf: kr5_sdh.urdf");
  dir.write("r/kr5_sdh.urdf", urdf);
  const std::string twice = load_error(dir.write("r/twice.yaml", yaml));
  EXPECT_NE(twice.find("is also in the arm's URDF"), std::string::npos) << twice;
}

// collision.mesh_hulls: a mesh link checked as its convex hull (Qhull), facing out; points that
// span no volume are an error.
TEST(UrdfLoading, MeshHullsReplaceMeshesByTheirConvexHulls) {
  std::vector<Eigen::Vector3d> points = unit_cube().vertices;
  for (int i = 0; i < 50; ++i)  // inside: not on the hull
    points.emplace_back(0.4 * std::sin(i), 0.4 * std::cos(3 * i), 0.4 * std::sin(7 * i));
  const TriangleMesh hull = convex_hull(points, "cube");
  EXPECT_EQ(hull.vertices.size(), 8u);
  EXPECT_EQ(hull.triangles.size(), 12u);
  EXPECT_TRUE(is_watertight(hull));
  for (const auto& t : hull.triangles) {
    const Eigen::Vector3d a = hull.vertices[t[0]], b = hull.vertices[t[1]], c = hull.vertices[t[2]];
    EXPECT_GT((b - a).cross(c - a).dot((a + b + c) / 3.0), 0.0) << "facing out";
  }
  EXPECT_THROW(convex_hull({{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {1, 1, 0}}, "flat"), InputError);

  Folder dir;
  TriangleMesh dense = unit_cube();
  for (const auto& p : points) dense.vertices.push_back(p);  // unused vertices: the hull drops them
  write_obj(dense, dir.path("robot/meshes/cube.obj"));
  std::string yaml = embedded_model_file("kr5_sdh.yaml");
  yaml += "  mesh_hulls: true\n";  // appended to the collision section, the file's last
  dir.robot("<mesh filename=\"meshes/cube.obj\" scale=\"0.113 0.122 0.077\"/>");
  const RobotModel m = load_robot(dir.write("robot/hulls.yaml", yaml));
  EXPECT_EQ(palm_shape(m).mesh->triangles.size(), 12u);
  EXPECT_EQ(palm_shape(m).mesh->vertices.size(), 8u);
}

}  // namespace
}  // namespace claspplan::robots
