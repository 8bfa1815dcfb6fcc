#include "examples/paper_scenes.hpp"

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <stdexcept>

#include <nlohmann/json.hpp>

#include "core/file_io.hpp"
#include "examples/scenario.hpp"
#include "perception/depth_render.hpp"
#include "perception/sensed_space.hpp"

namespace claspplan::cli {
namespace {

using Eigen::Vector3d;
constexpr double kPi = 3.14159265358979323846;

// Where an object stands: bounding-box centre (x, y) on a support `table` metres high (0: the
// floor), turned by URDF rpy (roll about the object's x first).
struct Placement {
  double x, y, yaw, pitch, roll, table;
};

// Poses 1-3 per object: upright facing the robot (-x), turned (on a 20 cm table for the small
// objects), tipped over. Loops stay within the KR5's reach (~0.85 m from the shoulder at 0.335 m)
// and clear of the start hand (tool0 at (0.48, 0, 0.71), pointing down).
Placement placement(const std::string& object, int pose) {
  const bool small = object == "purse" || object == "bag" || object == "travelbag";
  if (small) {
    const Placement p[3] = {{0.55, 0, 0, 0, 0, 0},
                            {0.55, 0, kPi / 2, 0, 0, 0.20},
                            {0.55, 0, 0, -kPi / 2, 0, 0}};  // on its side, handle to the robot
    return p[pose - 1];
  }
  if (object == "lawnmower") {  // handle towards the robot
    const Placement p[3] = {
        {1.0, 0, kPi, 0, 0, 0}, {0.95, 0.1, 0.75 * kPi, 0, 0, 0}, {0.85, 0, kPi, 0, kPi / 2, 0}};
    return p[pose - 1];
  }
  const Placement p[3] = {{0.90, 0, kPi, 0, 0, 0},  // chair: backrest towards the robot
                          {0.85, 0, kPi / 2, 0, 0, 0},
                          {0.80, 0, kPi, 0, kPi / 2, 0}};
  return p[pose - 1];
}

// A QVGA Kinect (320 x 240, f = 262.5) cropped to the pixels where `region` projects: small
// images, the same rays as the full sensor there.
perception::CameraModel cropped_camera(const Vector3d& position, const Vector3d& target,
                                       const Eigen::AlignedBox3d& region) {
  perception::CameraModel c = objects::kinect_camera(position, target);
  c.width = 320, c.height = 240, c.fx = c.fy = 262.5, c.cx = 159.5, c.cy = 119.5;
  double u0 = c.width, v0 = c.height, u1 = 0, v1 = 0;
  for (int i = 0; i < 8; ++i) {
    const Vector3d uvz = c.project(region.corner(static_cast<Eigen::AlignedBox3d::CornerType>(i)));
    u0 = std::min(u0, uvz.x()), u1 = std::max(u1, uvz.x());
    v0 = std::min(v0, uvz.y()), v1 = std::max(v1, uvz.y());
  }
  const int left = std::clamp(static_cast<int>(std::floor(u0)), 0, c.width - 1);
  const int top = std::clamp(static_cast<int>(std::floor(v0)), 0, c.height - 1);
  const int right = std::clamp(static_cast<int>(std::ceil(u1)) + 1, left + 1, c.width);
  const int bottom = std::clamp(static_cast<int>(std::ceil(v1)) + 1, top + 1, c.height);
  c.width = right - left, c.height = bottom - top;
  c.cx -= left, c.cy -= top;
  return c;
}

// Rounded to 0.1 mm: readable scene files.
nlohmann::json vec(const Vector3d& p) {
  auto r = [](double x) { return std::round(x * 1e4) / 1e4; };
  return {r(p.x()), r(p.y()), r(p.z())};
}

}  // namespace

std::vector<std::string> paper_scene_names() {
  std::vector<std::string> names;
  for (const auto& o : objects::paper_object_names())
    for (int pose = 1; pose <= 3; ++pose) names.push_back(o + "_" + std::to_string(pose));
  names.push_back("chair_obstructed");
  return names;
}

PaperScene paper_scene(const std::string& name) {
  const auto cut = name.rfind('_');
  if (cut == std::string::npos) throw std::invalid_argument("unknown paper scene '" + name + "'");
  const std::string object = name.substr(0, cut), tail = name.substr(cut + 1);
  const bool obstructed = name == "chair_obstructed";
  if (!obstructed && (tail.size() != 1 || tail[0] < '1' || tail[0] > '3'))
    throw std::invalid_argument("unknown paper scene '" + name + "' (pose 1, 2 or 3)");
  objects::PaperObject o = objects::paper_object(object);
  // The obstructed chair faces the robot, its seat under the start hand and the front loop
  // under the seat (Fig. 7).
  const Placement at =
      obstructed ? Placement{0.50, 0, 0, 0, 0, 0} : placement(object, tail[0] - '0');

  Eigen::Isometry3d pose = Eigen::Isometry3d::Identity();
  pose.linear() = (Eigen::AngleAxisd(at.yaw, Vector3d::UnitZ()) *
                   Eigen::AngleAxisd(at.pitch, Vector3d::UnitY()) *
                   Eigen::AngleAxisd(at.roll, Vector3d::UnitX()))
                      .toRotationMatrix();
  std::vector<Vector3d> turned;
  for (const auto& v : o.mesh.vertices) turned.push_back(pose.linear() * v);
  const Eigen::AlignedBox3d b = bounds(turned);
  pose.translation() =
      Vector3d(at.x - b.center().x(), at.y - b.center().y(), at.table - b.min().z());

  PaperScene s;
  s.name = name;
  s.object = object;
  s.mesh = transformed(o.mesh, pose);
  s.near = pose * (obstructed ? o.hidden : o.clasp);
  s.loops = o.loops;
  s.targets = o.targets;
  tsrrt::EnvironmentBox floor;
  floor.size = {2.5, 2.5, 0.05};
  floor.pose.translation() = Vector3d(0.5, 0, -0.025);
  s.boxes.push_back(floor);
  if (at.table > 0) {
    tsrrt::EnvironmentBox table;
    table.size = {0.6, 0.6, at.table};
    table.pose.translation() = Vector3d(at.x, at.y, at.table / 2);
    s.boxes.push_back(table);
  }
  const Eigen::AlignedBox3d object_box = bounds(s.mesh.vertices);
  s.workspace = Eigen::AlignedBox3d(object_box.min() - Vector3d(0.03, 0.03, 0),
                                    object_box.max() + Vector3d::Constant(0.03));
  s.workspace.min().z() = at.table + 0.004;  // above the support's plane
  // Two views from the robot's side, far enough to see the whole object. The upright chair's
  // from low down, so that all four loops under its seat show between legs and stretchers (from
  // 0.35, one of them stayed hidden); the chair on its side from halfway up, over its legs.
  const Vector3d target = object_box.center();
  double elevation = 0.7;
  if (object == "chair") elevation = at.pitch != 0.0 || at.roll != 0.0 ? 0.6 : 0.3;
  const double distance = std::max(1.0, 2.6 * object_box.sizes().norm() / 2);
  // The images cover the workspace and the space around it where the hand moves near the object
  // (the sensed space's region, perception::SensedSpaceOptions::margin, and 2 cm more).
  Eigen::AlignedBox3d seen = s.workspace;
  const Vector3d around = Vector3d::Constant(perception::SensedSpaceOptions().margin + 0.02);
  seen.min() -= around, seen.max() += around;
  for (double side : {-1.0, 1.0}) {
    const Vector3d dir = Vector3d(-0.35, 0.6 * side, elevation).normalized();
    s.cameras.push_back(cropped_camera(target + distance * dir, target, seen));
  }
  // A third from behind, as high as the others: the two in front leave the space behind every bar
  // that runs across their view unseen (a fin of shadow where the fingertips come out), and the
  // planner moves the hand only through space a camera saw free (issue 33).
  const Vector3d behind = Vector3d(0.7, 0.0, elevation).normalized();
  s.cameras.push_back(cropped_camera(target + distance * behind, target, seen));
  // The obstructed chair's loop under the seat (Fig. 7) opens into the space below the seat, which
  // the seat shades from the three above: a fourth camera looks in from the side, below the seat.
  if (obstructed) {
    const Vector3d side = Vector3d(0.0, 1.0, 0.05).normalized();
    const Vector3d under(target.x(), target.y(), at.table + 0.5 * (s.near.z() - at.table));
    s.cameras.push_back(cropped_camera(under + distance * side, under, seen));
  }
  return s;
}

std::vector<std::string> write_paper_scene(const PaperScene& s, const std::string& dir,
                                           double sigma, double dropout) {
  namespace fs = std::filesystem;
  fs::create_directories(dir);
  TriangleMesh scene = s.mesh;
  append_mesh(scene, boxes_mesh(s.boxes));
  const auto names = paper_scene_names();
  const auto index = std::find(names.begin(), names.end(), s.name) - names.begin();
  std::vector<std::string> files;
  nlohmann::json views = nlohmann::json::array();
  for (std::size_t i = 0; i < s.cameras.size(); ++i) {
    perception::DepthNoise noise;
    noise.sigma = sigma, noise.dropout = dropout;
    noise.seed = static_cast<std::uint64_t>(100 * (index + 1) + i);
    const auto image = perception::render_depth(scene, s.cameras[i], noise);
    const std::string stem = "view_" + std::to_string(i);
    perception::write_depth_png(image, s.cameras[i], (fs::path(dir) / (stem + ".png")).string());
    perception::write_camera_yaml(s.cameras[i], (fs::path(dir) / (stem + ".yaml")).string());
    files.push_back((fs::path(dir) / (stem + ".png")).string());
    files.push_back((fs::path(dir) / (stem + ".yaml")).string());
    views.push_back({{"image", stem + ".png"}, {"camera", stem + ".yaml"}});
  }
  nlohmann::json boxes = nlohmann::json::array();
  for (const auto& b : s.boxes)
    boxes.push_back({{"size", vec(b.size)}, {"position", vec(b.pose.translation())}});
  const nlohmann::json out = {
      {"name", s.name},
      {"object", s.object},
      {"near", vec(s.near)},
      {"loops", s.loops},
      {"targets", s.targets},
      {"boxes", boxes},
      {"workspace", {{"min", vec(s.workspace.min())}, {"max", vec(s.workspace.max())}}},
      {"views", views}};
  const std::string json = (fs::path(dir) / "scene.json").string();
  std::ofstream(json) << out.dump(1) << "\n";
  files.push_back(json);
  return files;
}

}  // namespace claspplan::cli
