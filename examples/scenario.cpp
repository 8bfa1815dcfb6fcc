#include "examples/scenario.hpp"

#include <cmath>
#include <filesystem>
#include <fstream>
#include <set>
#include <sstream>

#include "core/file_io.hpp"
#include "core/input_error.hpp"
#include "core/yaml_field.hpp"
#include "examples/objects.hpp"
#include "examples/paper_objects.hpp"
#include "examples/scene_render.hpp"
#include "perception/camera.hpp"
#include "robots/kinematics.hpp"

namespace claspplan::cli {
namespace {

namespace fs = std::filesystem;

// Optional keys of a scenario section, each with its default; an absent section reads as all
// defaults. Values are typed and checked by YamlField, which names the file, line and key.
class Reader {
 public:
  explicit Reader(YamlField field) : f_(std::move(field)) {
    if (f_.present() && !f_.is_map()) f_.fail("expected a map of keys");
  }

  [[noreturn]] void fail(const std::string& key, const std::string& what) const {
    (key.empty() ? f_ : f_[key]).fail(what);
  }
  void only(std::initializer_list<const char*> allowed) const { f_.only(allowed); }
  bool has(const std::string& key) const { return f_.has(key); }
  const YamlField& field() const { return f_; }
  Reader child(const std::string& key) const { return Reader(f_[key]); }

  double number(const std::string& key, double fallback, double lo = -INFINITY,
                double hi = INFINITY) const {
    return has(key) ? f_[key].number(lo, hi) : fallback;
  }
  int integer(const std::string& key, int fallback, int lo, int hi) const {
    return has(key) ? static_cast<int>(f_[key].integer(lo, hi)) : fallback;
  }
  bool boolean(const std::string& key, bool fallback) const {
    return has(key) ? f_[key].boolean() : fallback;
  }
  std::string text(const std::string& key, const std::string& fallback = "") const {
    return has(key) ? f_[key].text(false) : fallback;
  }
  std::vector<double> numbers(const std::string& key) const {
    return has(key) ? f_[key].numbers() : std::vector<double>();
  }
  Eigen::Vector3d vector3(const std::string& key, const Eigen::Vector3d& fallback) const {
    return has(key) ? f_[key].vector3() : fallback;
  }

  /// The pose this map gives by `position: [x, y, z]` and `rpy: [roll, pitch, yaw]` (URDF
  /// convention Rz·Ry·Rx).
  Eigen::Isometry3d pose_here() const {
    const Eigen::Vector3d rpy = vector3("rpy", Eigen::Vector3d::Zero());
    Eigen::Isometry3d T = Eigen::Isometry3d::Identity();
    T.linear() = (Eigen::AngleAxisd(rpy.z(), Eigen::Vector3d::UnitZ()) *
                  Eigen::AngleAxisd(rpy.y(), Eigen::Vector3d::UnitY()) *
                  Eigen::AngleAxisd(rpy.x(), Eigen::Vector3d::UnitX()))
                     .toRotationMatrix();
    T.translation() = vector3("position", Eigen::Vector3d::Zero());
    return T;
  }

  /// A list of maps under `key` (`what` describes an entry); with `required` the list must exist
  /// and be non-empty.
  std::vector<Reader> maps(const std::string& key, const std::string& what, bool required) const {
    std::vector<Reader> out;
    if (!has(key)) {
      if (required) fail(key, "expected a list of " + what);
      return out;
    }
    const std::vector<YamlField> items = f_[key].items(what);
    if (required && items.empty()) fail(key, "expected a list of " + what);
    for (const YamlField& item : items) out.emplace_back(item);
    return out;
  }

  /// A list of [x, y, z].
  std::vector<Eigen::Vector3d> vectors(const std::string& key) const {
    std::vector<Eigen::Vector3d> out;
    if (!has(key)) return out;
    for (const YamlField& item : f_[key].items("[x, y, z]")) out.push_back(item.vector3());
    return out;
  }

 private:
  YamlField f_;
};

std::string resolve(const fs::path& dir, const std::string& file) {
  const fs::path p(file);
  return (p.is_absolute() ? p : dir / p).lexically_normal().string();
}

// The keys of the torus, purse, sphere and holed_plate shapes.
void read_shape_parameters(const Reader& s, ShapeSpec& shape) {
  shape.major_radius = s.number("major_radius", shape.major_radius, 1e-3, 10.0);
  shape.minor_radius = s.number("minor_radius", shape.minor_radius, 1e-4, 10.0);
  if (shape.minor_radius >= shape.major_radius)
    s.fail("minor_radius", "must be below major_radius");
  shape.radius = s.number("radius", shape.radius, 1e-3, 10.0);
  shape.holes = s.integer("holes", shape.holes, 0, 8);
  shape.purse.body = s.vector3("body", shape.purse.body);
  if ((shape.purse.body.array() <= 0.0).any()) s.fail("body", "needs three positive lengths");
  shape.purse.handle_radius = s.number("handle_radius", shape.purse.handle_radius, 0.01, 2.0);
  shape.purse.handle_tube = s.number("handle_tube", shape.purse.handle_tube, 0.002, 0.5);
  if (shape.purse.handle_tube >= shape.purse.handle_radius) {
    s.fail("handle_tube", "must be below handle_radius");
  }
}

// A cup, mug or jug: an open container, with a side handle when handle_radius > 0.
void read_container_parameters(const Reader& s, objects::Container& c) {
  c.radius = s.number("radius", c.radius, 0.01, 1.0);
  c.height = s.number("height", c.height, 0.01, 2.0);
  c.wall = s.number("wall", c.wall, 0.002, 0.1);
  c.handle_radius = s.number("handle_radius", 0.0, 0.0, 1.0);
  c.handle_tube = s.number("handle_tube", c.handle_tube, 0.002, 0.2);
  c.handle_height = s.number("handle_height", c.handle_height, 0.1, 0.9);
  if (!(c.radius > 2 * c.wall) || !(c.height > 2 * c.wall))
    s.fail("wall", "must be below half the radius and half the height");
  if (c.handle_radius > 0 && !(c.handle_radius > c.handle_tube))
    s.fail("handle_tube", "must be below handle_radius");
  if (c.handle_radius + c.handle_tube >= c.height / 2)
    s.fail("handle_radius", "the handle must fit on the wall (below half the height)");
}

// A box: {size, position, rpy}.
EnvironmentBox read_box(const Reader& b) {
  b.only({"size", "position", "rpy"});
  EnvironmentBox box;
  box.size = b.vector3("size", Eigen::Vector3d::Zero());
  if ((box.size.array() <= 0.0).any()) b.fail("size", "needs three positive lengths");
  box.pose = b.pose_here();
  return box;
}

void read_object(const Reader& r, const fs::path& dir, ObjectSpec& o) {
  r.only({"depth", "cloud", "mesh", "shape", "pose", "in_front_of_hand", "views", "cameras",
          "noise", "clutter"});
  int sources = 0;
  if (r.has("depth")) {
    ++sources;
    for (const Reader& v : r.maps("depth", "{image, camera}", true)) {
      v.only({"image", "camera"});
      if (!v.has("image") || !v.has("camera")) v.fail("", "needs both image and camera");
      o.depth.emplace_back(resolve(dir, v.text("image")), resolve(dir, v.text("camera")));
    }
  }
  if (r.has("cloud")) {
    ++sources;
    // One file, or a list of files and {file, pose, viewpoint} maps.
    const YamlField& field = r.field()["cloud"];
    const std::vector<YamlField> items =
        field.is_list() ? field.items("file or {file, pose, viewpoint}") : std::vector{field};
    if (items.empty()) r.fail("cloud", "expected a file or a list of files");
    for (const YamlField& item : items) {
      perception::CloudFile file;
      bool own_pose = false;
      if (!item.is_map()) {
        file.path = resolve(dir, item.text(false));
      } else {
        const Reader c(item);
        c.only({"file", "pose", "viewpoint"});
        if (!c.has("file")) c.fail("", "needs file");
        file.path = resolve(dir, c.text("file"));
        if (c.has("pose")) {
          c.child("pose").only({"position", "rpy"});
          file.pose = c.child("pose").pose_here();
          own_pose = true;
        }
        if (c.has("viewpoint")) {
          c.child("viewpoint").only({"position", "rpy"});
          file.viewpoint = c.child("viewpoint").pose_here();
        }
      }
      o.cloud_pose_given.push_back(own_pose);
      o.clouds.push_back(file);
    }
  }
  if (r.has("mesh")) ++sources, o.mesh = resolve(dir, r.text("mesh"));
  if (r.has("shape")) {
    ++sources;
    const Reader s = r.child("shape");
    s.only({"type", "major_radius", "minor_radius", "radius", "holes", "body", "handle_radius",
            "handle_tube", "height", "wall", "handle_height"});
    ShapeSpec shape;
    shape.type = s.text("type");
    const std::set<std::string> known = {"torus",       "purse",     "sphere",
                                         "holed_plate", "container", "bag",
                                         "travelbag",   "lawnmower", "chair"};
    if (!known.count(shape.type)) {
      s.fail("type", "unknown shape '" + shape.type +
                         "' (torus, purse, sphere, holed_plate, container, bag, travelbag, "
                         "lawnmower, chair)");
    }
    const std::set<std::string> fixed = {"bag", "travelbag", "lawnmower", "chair"};
    if (fixed.count(shape.type) && s.has("type") && r.field()["shape"].node().size() > 1)
      s.fail("type", "the paper objects (bag, travelbag, lawnmower, chair) take no parameters");
    if (shape.type == "container")
      read_container_parameters(s, shape.container);
    else
      read_shape_parameters(s, shape);
    o.shape = shape;
  }
  if (sources != 1) r.fail("", "give exactly one of depth, cloud, mesh or shape");
  if (r.has("pose")) {
    const Reader pose = r.child("pose");
    pose.only({"position", "rpy"});
    o.pose = pose.pose_here();
    // For clouds: the frame of every file that gives no pose of its own.
    for (std::size_t i = 0; i < o.clouds.size(); ++i)
      if (!o.cloud_pose_given[i]) o.clouds[i].pose = o.pose;
  }
  if (r.has("in_front_of_hand")) {
    if (r.has("pose")) r.fail("in_front_of_hand", "give pose or in_front_of_hand, not both");
    if (o.mesh.empty() && !o.shape) r.fail("in_front_of_hand", "places a mesh or shape only");
    o.in_front_of_hand = r.number("in_front_of_hand", 0.0, 0.0, 2.0);
  }
  if (!o.depth.empty() && r.has("pose"))
    r.fail("pose", "depth images are placed by their camera files' T_world_camera");
  o.views = r.vectors("views");
  if (r.has("cameras")) {
    if (!o.mesh.empty() || o.shape) {
      for (const Reader& c : r.maps("cameras", "{position, target}", true)) {
        c.only({"position", "target"});
        if (!c.has("position") || !c.has("target")) c.fail("", "needs position and target");
        const Eigen::Vector3d position = c.vector3("position", Eigen::Vector3d::Zero());
        const Eigen::Vector3d target = c.vector3("target", Eigen::Vector3d::Zero());
        if ((position - target).norm() < 1e-3) c.fail("target", "must differ from the position");
        o.cameras.emplace_back(position, target);
      }
    } else {
      r.fail("cameras", "synthetic cameras render a mesh or shape");
    }
    if (!o.views.empty()) r.fail("views", "give views or cameras, not both");
  }
  for (const Reader& b : r.maps("clutter", "{size, position, rpy}", false))
    o.clutter.push_back(read_box(b));
  if (!o.clutter.empty() && o.cameras.empty())
    r.fail("clutter", "other objects are seen by synthetic cameras: give cameras");
  if (r.has("noise")) {
    const Reader n = r.child("noise");
    n.only({"sigma", "dropout"});
    o.noise.sigma = n.number("sigma", 0.0, 0.0, 0.1);
    o.noise.dropout = n.number("dropout", 0.0, 0.0, 0.99);
  }
}

}  // namespace

void check_verification_budget(const tsrrt::SecureClaspOptions& check, const std::string& sequences,
                               const std::string& motions) {
  if (static_cast<long>(check.sequences) * check.motions > kMaxVerificationMotions) {
    throw InputError(sequences + " x " + motions + " must be at most " +
                     std::to_string(kMaxVerificationMotions) + " motions, got " +
                     std::to_string(check.sequences) + " x " + std::to_string(check.motions));
  }
}

void place_in_front_of_hand(Scenario& s, const robots::RobotModel& robot) {
  if (!s.object.in_front_of_hand) return;
  robots::RobotData data(robot);
  robots::forward_kinematics(robot, robot.complete_q(s.start), data);
  const Eigen::Vector3d fwd = robots::vector_direction(data, robot.v_fwd).normalized();
  const Eigen::Vector3d swd = robots::vector_direction(data, robot.v_swd).normalized();
  Eigen::Matrix3d axes;
  axes.col(2) = fwd.cross(swd).normalized();
  axes.col(0) = -fwd;
  axes.col(1) = axes.col(2).cross(axes.col(0));
  Eigen::Isometry3d& pose = s.object.pose;
  pose.linear() = axes;
  pose.translation() = robots::point_position(data, robot.tcp) + *s.object.in_front_of_hand * fwd;
}

void use_robot(Scenario& s, const std::string& robot, const std::string& base_dir) {
  const std::vector<std::string> builtin = robots::builtin_robots();
  // A description file by its absolute path: result.json records it, and `verify` reads it back
  // from any directory.
  s.robot = std::find(builtin.begin(), builtin.end(), robot) != builtin.end()
                ? robot
                : fs::absolute(resolve(base_dir, robot)).lexically_normal().string();
}

Scenario load_scenario(const std::string& path) {
  if (!fs::is_regular_file(path)) throw InputError(path + ": no such scenario file");
  std::ifstream in(path);
  std::stringstream text;
  text << in.rdbuf();
  return load_scenario_text(text.str(), path, fs::path(path).parent_path().string());
}

namespace {

// The `perception` section (its seed defaults to the scenario's).
void read_perception(const Reader& per, Scenario& s) {
  per.only({"points", "d", "d_factor", "min_hole", "seed", "workspace", "remove_plane"});
  auto& po = s.perception;
  po.points = per.integer("points", po.points, 10, perception::kMaxPoints);
  po.d = per.number("d", po.d, 0.0, 10.0);
  po.d_factor = per.number("d_factor", po.d_factor, 0.5, 50.0);
  po.min_hole = per.number("min_hole", po.min_hole, 0.0, 10.0);
  po.seed =
      static_cast<std::uint64_t>(per.integer("seed", static_cast<int>(s.seed), 0, 2147483647));
  po.remove_plane = per.boolean("remove_plane", po.remove_plane);
  if (per.has("workspace")) {
    const Reader w = per.child("workspace");
    w.only({"min", "max"});
    po.workspace = Eigen::AlignedBox3d(w.vector3("min", Eigen::Vector3d::Constant(-1e9)),
                                       w.vector3("max", Eigen::Vector3d::Constant(1e9)));
  }
}

// The `controller` section: the controller's gains and the controller-only run's limits.
void read_controller(const Reader& ctl, Scenario& s) {
  ctl.only({"gain_distance", "gain_width", "dt", "max_step", "damping", "singular_threshold",
            "hold_distance", "max_position_error", "pose_bias_gain", "hand_in_arm_tasks",
            "arm_in_hand_task", "max_steps", "stall_steps"});
  auto& pp = s.controller.priority;
  pp.gain_distance = ctl.number("gain_distance", pp.gain_distance, 0.0, 10.0);
  pp.gain_width = ctl.number("gain_width", pp.gain_width, 1e-6, 10.0);
  pp.dt = ctl.number("dt", pp.dt, 1e-6, 10.0);
  pp.max_step = ctl.number("max_step", pp.max_step, 1e-6, 1.0);
  pp.damping = ctl.number("damping", pp.damping, 0.0, 10.0);
  pp.singular_threshold = ctl.number("singular_threshold", pp.singular_threshold, 1e-9, 10.0);
  auto& c = s.controller;
  c.hold_distance = ctl.number("hold_distance", c.hold_distance, 0.0, 1.0);
  c.max_position_error = ctl.number("max_position_error", c.max_position_error, 0.0, 10.0);
  c.pose_bias_gain = ctl.number("pose_bias_gain", c.pose_bias_gain, 0.0, 10.0);
  c.hand_in_arm_tasks = ctl.number("hand_in_arm_tasks", c.hand_in_arm_tasks, 0.0, 1.0);
  c.arm_in_hand_task = ctl.number("arm_in_hand_task", c.arm_in_hand_task, 0.0, 1.0);
  s.controller_run.max_steps = ctl.integer("max_steps", s.controller_run.max_steps, 1, 1000000);
  s.controller_run.stall_steps =
      ctl.integer("stall_steps", s.controller_run.stall_steps, 1, 1000000);
}

// The `planner` section: TS-RRT, the linking goal, closing and verification (their seeds are the
// scenario's).
void read_planner(const Reader& pl, const std::string& path, Scenario& s) {
  pl.only({"random_probability",   "pre_expansions",    "max_cycles",         "time_limit",
           "extend_steps",         "connect_steps",     "stall_steps",        "linking_scale",
           "sample_min",           "sample_max",        "goal_linking",       "position_tolerance",
           "collision_resolution", "collision_travel",  "approach_clearance", "prune_attempts",
           "closing_step",         "closing_clearance", "verify_sequences",   "verify_motions",
           "verify_in_search",     "backoff_steps",     "detour_steps",       "closable_linking",
           "sample_probability",   "sample_after",      "joint_step",         "restart_cycles"});
  auto& o = s.planning;
  auto& tp = o.planner;
  tp.random_probability = pl.number("random_probability", tp.random_probability, 0.0, 1.0);
  tp.pre_expansions = pl.integer("pre_expansions", tp.pre_expansions, 0, 1000000);
  tp.max_cycles = pl.integer("max_cycles", tp.max_cycles, 1, 100000000);
  tp.time_limit = pl.number("time_limit", tp.time_limit, 0.0, 1e6);
  tp.extend_steps = pl.integer("extend_steps", tp.extend_steps, 1, 10000);
  tp.connect_steps = pl.integer("connect_steps", tp.connect_steps, 1, 1000000);
  tp.stall_steps = pl.integer("stall_steps", tp.stall_steps, 1, 1000000);
  tp.backoff_steps = pl.integer("backoff_steps", tp.backoff_steps, 0, 1000000);
  tp.detour_steps = pl.integer("detour_steps", tp.detour_steps, 0, 1000000);
  tp.sample_probability = pl.number("sample_probability", tp.sample_probability, 0.0, 1.0);
  tp.sample_after = pl.integer("sample_after", tp.sample_after, 0, 1000000);
  tp.joint_step = pl.number("joint_step", tp.joint_step, 1e-4, 10.0);
  tp.restart_cycles = pl.integer("restart_cycles", tp.restart_cycles, 0, 100000000);
  tp.linking_scale = pl.number("linking_scale", tp.linking_scale, 0.0, 100.0);
  if (pl.has("sample_min") != pl.has("sample_max")) {
    pl.fail("sample_min", "give both sample_min and sample_max, or neither");
  }
  if (pl.has("sample_min")) {
    o.sample_box_given = true;
    tp.sample_min = pl.vector3("sample_min", tp.sample_min);
    tp.sample_max = pl.vector3("sample_max", tp.sample_max);
    if ((tp.sample_max.array() <= tp.sample_min.array()).any()) {
      pl.fail("sample_max", "must exceed sample_min in every coordinate");
    }
  }
  tp.seed = s.seed;
  if (pl.has("goal_linking")) s.goal_linking = pl.number("goal_linking", 0.0, 1e-6, 1.0);
  o.closable_linking = pl.number("closable_linking", o.closable_linking, 0.0, 1.0);
  o.position_tolerance = pl.number("position_tolerance", o.position_tolerance, 0.0, 10.0);
  o.collision_resolution = pl.number("collision_resolution", o.collision_resolution, 1e-4, 1.0);
  o.collision_travel = pl.number("collision_travel", o.collision_travel, 0.0, 1.0);
  o.approach.clearance = pl.number("approach_clearance", o.approach.clearance, 0.0, 0.05);
  o.prune_attempts = pl.integer("prune_attempts", o.prune_attempts, 0, 1000000);
  o.closing.step = pl.number("closing_step", o.closing.step, 1e-4, 0.5);
  o.closing.clearance = pl.number("closing_clearance", o.closing.clearance, 0.0, 0.1);
  o.secure.sequences = pl.integer("verify_sequences", o.secure.sequences, 1, 1000);
  o.secure.motions = pl.integer("verify_motions", o.secure.motions, 1, 100000);
  check_verification_budget(o.secure, path + ": planner.verify_sequences",
                            "planner.verify_motions");
  o.secure.seed = s.seed;
  o.verify_in_search = pl.boolean("verify_in_search", o.verify_in_search);
}

Scenario read_scenario(const YamlField& root, const std::string& path,
                       const std::string& base_dir) {
  const Reader r(root);
  r.only({"name", "robot", "start", "object", "environment", "clasp", "seed", "perception",
          "controller", "planner"});
  const fs::path dir(base_dir);

  Scenario s;
  s.path = path;
  s.name = r.text("name", fs::path(path).stem().string());
  if (!r.has("robot"))
    r.fail("robot", "missing (a built-in robot name or a hand-description file)");
  use_robot(s, r.text("robot"), dir);
  s.start = r.numbers("start");
  s.seed = static_cast<std::uint64_t>(r.integer("seed", 1, 0, 2147483647));

  if (!r.has("object")) r.fail("object", "missing");
  read_object(r.child("object"), dir, s.object);

  if (r.has("environment")) {
    const Reader env = r.child("environment");
    env.only({"boxes"});
    for (const Reader& b : env.maps("boxes", "{size, position, rpy}", false))
      s.boxes.push_back(read_box(b));
  }

  const Reader clasp = r.child("clasp");
  clasp.only({"near", "targets"});
  if (clasp.has("near")) s.loop_hint = clasp.vector3("near", Eigen::Vector3d::Zero());
  s.perception.targets = clasp.integer("targets", s.perception.targets, 1, 200);

  read_perception(r.child("perception"), s);
  read_controller(r.child("controller"), s);
  read_planner(r.child("planner"), path, s);
  return s;
}

// A mesh or shape object at its pose, in the world frame.
TriangleMesh object_mesh(const ObjectSpec& o) {
  TriangleMesh mesh;
  if (!o.mesh.empty()) {
    const perception::PerceptionInputs file = perception::load_inputs({o.mesh}, {});
    if (file.meshes.empty()) throw InputError(o.mesh + ": not a mesh");
    mesh = file.meshes.front();
  } else if (o.shape->type == "torus") {
    mesh = objects::torus_mesh(o.shape->major_radius, o.shape->minor_radius);
  } else if (o.shape->type == "purse") {
    mesh = objects::purse(o.shape->purse);
  } else if (o.shape->type == "sphere") {
    mesh = objects::sphere_mesh(o.shape->radius);
  } else if (o.shape->type == "container") {
    mesh = objects::container(o.shape->container);
  } else if (o.shape->type != "holed_plate") {
    mesh = objects::paper_object(o.shape->type).mesh;
  } else {  // holed_plate
    objects::HoledPlate plate;
    plate.holes = o.shape->holes;
    mesh = objects::holed_plate(plate);
  }
  mesh = transformed(mesh, o.pose);
  return mesh;
}

perception::PerceptionInputs build_inputs(const Scenario& s) {
  const ObjectSpec& o = s.object;
  perception::PerceptionInputs in;
  if (!o.depth.empty()) {
    std::vector<std::string> images, cameras;
    for (const auto& [png, camera] : o.depth) images.push_back(png), cameras.push_back(camera);
    return perception::load_inputs(images, cameras);
  }
  if (!o.clouds.empty()) {
    for (const auto& file : o.clouds) perception::add_cloud(in, file);
    return in;
  }
  if (o.cameras.empty()) {
    in.meshes.push_back(object_mesh(o));
    in.view_positions = o.views;
    return in;
  }
  const TriangleMesh mesh = *rendered_scene(s);
  for (std::size_t i = 0; i < o.cameras.size(); ++i) {
    perception::DepthView view;
    view.camera = objects::kinect_camera(o.cameras[i].first, o.cameras[i].second);
    perception::DepthNoise noise = o.noise;
    noise.seed = s.seed * 7919 + i;
    view.image = perception::render_depth(mesh, view.camera, noise);
    view.camera.no_reading_is_free = true;  // a complete synthetic scene: no reading, nothing there
    in.depth_views.push_back(view);
  }
  return in;
}

}  // namespace

Scenario load_scenario_text(const std::string& text, const std::string& path,
                            const std::string& base_dir) {
  // Whatever check the scenario fails, in the robot's or a file's reader too, is about the input.
  return as_input_error([&] {
    const YamlField root = YamlField::parse_map(text, path, "(a scenario)");
    try {
      return read_scenario(root, path, base_dir);
    } catch (const YAML::Exception& e) {  // a conversion no check foresaw: still the file's fault
      throw InputError(path + ": " + YamlField::line_of(e.mark) + one_line(e.msg));
    }
  });
}

TriangleMesh boxes_mesh(const std::vector<EnvironmentBox>& boxes) {
  TriangleMesh out;
  for (const auto& b : boxes) {
    const TriangleMesh box = box_mesh(b.size);
    TriangleMesh m;
    m.vertices = box.vertices;
    for (const auto& t : box.triangles) m.triangles.push_back({t[0], t[1], t[2]});
    append_mesh(out, transformed(m, b.pose));
  }
  return out;
}

std::optional<TriangleMesh> rendered_scene(const Scenario& s) {
  if (s.object.cameras.empty() || !s.object.depth.empty() || !s.object.clouds.empty()) return {};
  return as_input_error([&] {
    TriangleMesh mesh = object_mesh(s.object);
    append_mesh(mesh, boxes_mesh(s.boxes));
    append_mesh(mesh, boxes_mesh(s.object.clutter));  // seen, but not told to the planner
    return mesh;
  });
}

perception::PerceptionInputs scenario_inputs(const Scenario& s) {
  // The inputs are the scenario's own files and shapes.
  return as_input_error([&] { return build_inputs(s); });
}

}  // namespace claspplan::cli
