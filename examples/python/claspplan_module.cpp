// The Python module `claspplan._claspplan` (pybind11): robots, linking, perception from NumPy
// arrays, and whole scenario runs. The package `claspplan` (claspplan/__init__.py) wraps it in
// Python terms. Long calls release the GIL; malformed input raises claspplan.InputError (a
// ValueError) with the one-line reason the command line prints.
#include <chrono>
#include <cmath>
#include <functional>
#include <memory>
#include <utility>

#include <pybind11/eigen.h>
#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>
#include <pybind11/stl.h>

#include "core/input_error.hpp"
#include "core/stopped.hpp"
#include "examples/result_file.hpp"
#include "examples/run_scenario.hpp"
#include "examples/scenario.hpp"
#include "perception/pipeline.hpp"
#include "perception/sensor_cloud.hpp"
#include "robots/collision_world.hpp"
#include "robots/hand_size.hpp"
#include "robots/kinematics.hpp"
#include "robots/robot_model.hpp"
#include "servo/linking.hpp"
#include "tsrrt/clasp_setup.hpp"

namespace py = pybind11;

namespace claspplan::python {
namespace {

using Robot = std::shared_ptr<robots::RobotModel>;  // pybind11 holds no pointer to const
using Matrix = Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, Eigen::RowMajor>;
using DepthArray = py::array_t<float, py::array::c_style | py::array::forcecast>;

// An (n x 3) array as points; `what` names it in the error.
std::vector<Eigen::Vector3d> points_of(const Matrix& a, const std::string& what) {
  if (a.cols() != 3) throw InputError(what + ": expected an (n, 3) array");
  std::vector<Eigen::Vector3d> out(static_cast<size_t>(a.rows()));
  for (Eigen::Index i = 0; i < a.rows(); ++i) out[i] = a.row(i).transpose();
  return out;
}

Matrix array_of(const std::vector<Eigen::Vector3d>& points) {
  Matrix a(static_cast<Eigen::Index>(points.size()), 3);
  for (size_t i = 0; i < points.size(); ++i) a.row(static_cast<Eigen::Index>(i)) = points[i];
  return a;
}

Eigen::VectorXd joint_vector(const robots::RobotModel& m, const Eigen::VectorXd& q) {
  if (q.size() != m.dof())
    throw InputError("q: " + std::to_string(q.size()) + " values for " + std::to_string(m.dof()) +
                     " joints");
  if (!m.within_limits(q, 1e-9)) throw InputError("q: a value is outside its joint's limits");
  return q;
}

Eigen::Isometry3d pose_of(const Eigen::Matrix4d& m, const std::string& what) {
  if (!m.allFinite() || !m.row(3).isApprox(Eigen::RowVector4d(0, 0, 0, 1)))
    throw InputError(what + ": expected a 4 x 4 homogeneous transform");
  Eigen::Isometry3d pose;
  pose.matrix() = m;
  return pose;
}

py::dict forward_kinematics(const Robot& m, const Eigen::VectorXd& q) {
  robots::RobotData data(*m);
  robots::forward_kinematics(*m, joint_vector(*m, q), data);
  py::dict poses;
  for (size_t i = 0; i < m->links.size(); ++i)
    poses[py::str(m->links[i].name)] = Eigen::Matrix4d(data.link_poses[i].matrix());
  return poses;
}

std::vector<Matrix> finger_curves(const Robot& m, const Eigen::VectorXd& q) {
  robots::RobotData data(*m);
  robots::FingerCurvesData curves;
  robots::finger_curves(*m, joint_vector(*m, q), data, curves, false);
  std::vector<Matrix> out;
  for (const auto& c : curves.points) out.push_back(array_of(c));
  return out;
}

std::vector<std::pair<std::string, std::string>> self_collisions(const Robot& m,
                                                                 const Eigen::VectorXd& q) {
  robots::RobotData data(*m);
  robots::forward_kinematics(*m, joint_vector(*m, q), data);
  robots::CollisionWorld world(*m);
  return world.self_contacts(data);
}

// One depth view from an (h x w) depth array in metres (0 or NaN: no reading), the intrinsics and
// the camera's pose in the world (optical frame: z forward, x right, y down).
perception::DepthView depth_view(const DepthArray& depth, const Eigen::Matrix3d& K,
                                 const Eigen::Matrix4d& pose, bool no_reading_is_free) {
  if (depth.ndim() != 2) throw InputError("depth: expected an (h, w) array of metres");
  perception::DepthView v;
  v.camera.height = static_cast<int>(depth.shape(0));
  v.camera.width = static_cast<int>(depth.shape(1));
  v.camera.fx = K(0, 0);
  v.camera.fy = K(1, 1);
  v.camera.cx = K(0, 2);
  v.camera.cy = K(1, 2);
  v.camera.T_world_camera = pose_of(pose, "camera pose");
  v.camera.no_reading_is_free = no_reading_is_free;
  perception::validate_camera(v.camera, "camera");
  v.image = perception::DepthImage(v.camera.width, v.camera.height);
  const float* d = depth.data();
  for (size_t i = 0; i < v.image.depth.size(); ++i) {
    if (std::isinf(d[i]) || d[i] < 0) throw InputError("depth: negative or infinite value");
    v.image.depth[i] = std::isnan(d[i]) ? 0.0f : d[i];
  }
  return v;
}

struct PerceiveArgs {
  std::vector<perception::DepthView> views;
  std::vector<std::pair<Matrix, std::optional<Eigen::Vector3d>>> clouds;
  std::string robot;
  std::optional<Eigen::Matrix<double, 6, 1>> crop;
  int points = 2000;
  double d = 0.0;
  std::uint64_t seed = 1;
};

using DepthInputs = std::vector<std::tuple<DepthArray, Eigen::Matrix3d, Eigen::Matrix4d>>;
using CloudInputs = std::vector<std::pair<Matrix, std::optional<Eigen::Vector3d>>>;
using Crop = std::optional<Eigen::Matrix<double, 6, 1>>;

PerceiveArgs object_args(const DepthInputs& depth, const CloudInputs& clouds, const Crop& crop,
                         int points, double d, std::uint64_t seed, bool no_reading_is_free) {
  PerceiveArgs a;
  for (const auto& [image, K, pose] : depth)
    a.views.push_back(depth_view(image, K, pose, no_reading_is_free));
  a.clouds = clouds;
  a.crop = crop;
  a.points = points;
  a.d = d;
  a.seed = seed;
  return a;
}

// The arrays as the pipeline's inputs: clouds with a sensor origin become depth views of it (the
// sensed-space rules of the command line), those without stay points.
perception::PerceptionInputs inputs_of(const PerceiveArgs& a) {
  perception::PerceptionInputs in;
  in.depth_views = a.views;
  for (const auto& [array, origin] : a.clouds) {
    PointCloud pts;
    for (const auto& p : points_of(array, "points"))
      if (p.allFinite()) pts.push_back(p);
    if (origin)
      in.depth_views.push_back(perception::unorganized_cloud_view(pts, *origin, "points"));
    else
      in.clouds.push_back(std::move(pts));
  }
  return in;
}

perception::PerceptionOptions options_of(const PerceiveArgs& a) {
  perception::PerceptionOptions o;
  o.points = a.points;
  o.d = a.d;
  o.seed = a.seed;
  if (a.crop) o.workspace = Eigen::AlignedBox3d(a.crop->head<3>(), a.crop->tail<3>());
  if (!a.robot.empty()) {
    const robots::HandSize size = robots::hand_size(robots::load_robot(a.robot));
    o.finger_thickness = size.finger_thickness;
    o.closed_aperture = size.closed_aperture;
  }
  return o;
}

py::dict object_dict(const perception::ObjectModel& m) {
  // As in `loops --json`: None where no bar was measured (a wall or body along the loop).
  const auto finite_or_none = [](double v) {
    return std::isfinite(v) ? py::object(py::float_(v)) : py::object(py::none());
  };
  py::list loops;
  for (const auto& l : m.loops) {
    py::dict d;
    d["points"] = array_of(l.points);
    d["rank"] = l.rank;
    d["claspable"] = l.claspable;
    d["verdict"] = perception::verdict_name(l.verdict);
    d["reason"] = l.reason;
    d["length"] = l.length;
    d["hole_width"] = l.hole_width;
    d["bar_thickness"] = finite_or_none(l.bar_thickness);
    d["fit"] = l.fit;
    py::list profile;
    for (double b : l.bar_profile) profile.append(finite_or_none(b));
    d["bar_profile"] = profile;
    d["centre"] = Eigen::Vector3d(l.centre);
    d["normal"] = Eigen::Vector3d(l.normal);
    loops.append(d);
  }
  std::vector<Eigen::Vector3d> target_points, tangents;
  for (const auto& t : m.targets) {
    target_points.push_back(t.point);
    tangents.push_back(t.tangent);
  }
  py::dict out;
  out["beta1"] = m.beta1;
  out["d"] = m.d;
  out["d_rule"] = m.d_rule;
  out["objects"] = m.objects;
  out["cloud"] = array_of(m.cloud);
  out["input_points"] = m.input_points;
  out["loops"] = loops;
  out["targets"] = array_of(target_points);
  out["target_tangents"] = array_of(tangents);
  return out;
}

// Ctrl-C during a long call: perception, the search and the secure-clasp checks poll this (their
// `stop`) on the calling thread; at most every 50 ms it takes the GIL and lets Python run its
// signal handlers. When one raised (KeyboardInterrupt), the call ends and rethrows it.
class Interrupt {
 public:
  std::function<bool()> poll() {
    return [state = state_] {
      if (state->raised) return true;
      const auto now = std::chrono::steady_clock::now();
      if (now < state->next) return false;
      state->next = now + std::chrono::milliseconds(50);
      py::gil_scoped_acquire gil;
      state->raised = PyErr_CheckSignals() != 0;
      return state->raised;
    };
  }
  // With the GIL held, after the call.
  void rethrow() const {
    if (state_->raised) throw py::error_already_set();
  }

 private:
  struct State {
    bool raised = false;
    std::chrono::steady_clock::time_point next;
  };
  std::shared_ptr<State> state_ = std::make_shared<State>();
};

// Runs call(stop) without the GIL, `stop` answering Ctrl-C; after a Ctrl-C (perception's Stopped
// included) the call's KeyboardInterrupt is raised.
template <typename Call>
auto interruptible(Call&& call) {
  Interrupt interrupt;
  decltype(call(interrupt.poll())) out{};
  bool stopped = false;
  try {
    py::gil_scoped_release release;
    out = call(interrupt.poll());
  } catch (const Stopped&) {
    stopped = true;
  }
  interrupt.rethrow();
  if (stopped) throw Stopped();  // a stop the interpreter did not ask for: an internal failure
  return out;
}

struct PlanArgs {
  PerceiveArgs object;  // its robot stays empty: the planner sizes the loops for the robot itself
  Eigen::VectorXd start;
  std::vector<std::pair<Eigen::Vector3d, Eigen::Vector3d>> boxes;  // (size, centre)
  int targets = 12;
  std::optional<Eigen::Vector3d> near;
  std::optional<double> goal_linking;
  std::optional<int> pre_expansions, max_cycles;
  std::optional<double> random_probability, time_limit;
  bool controller_only = false;
};

const char* status_name(tsrrt::ClaspStatus s) {
  switch (s) {
    case tsrrt::ClaspStatus::kSuccess:
      return "success";
    case tsrrt::ClaspStatus::kNoClaspableLoop:
      return "no_claspable_loop";
    case tsrrt::ClaspStatus::kNoClasp:
      break;
  }
  return "no_clasp";
}

// tsrrt::plan_clasp on arrays; the result in arrays and the verification as run's JSON text.
py::dict plan(const Robot& robot, const PlanArgs& a) {
  tsrrt::ClaspRequest r;
  r.robot = robot;
  r.start = a.start;
  r.object = inputs_of(a.object);
  r.perception = options_of(a.object);
  r.perception.targets = a.targets;
  for (const auto& [size, centre] : a.boxes) {
    tsrrt::EnvironmentBox box;
    box.size = size;
    box.pose.translation() = centre;
    r.environment.push_back(box);
  }
  r.loop_hint = a.near;
  r.goal_linking = a.goal_linking;
  if (a.controller_only) r.mode = tsrrt::ClaspMode::kControllerOnly;
  if (a.pre_expansions) r.planning.planner.pre_expansions = *a.pre_expansions;
  if (a.random_probability) r.planning.planner.random_probability = *a.random_probability;
  r.seed = a.object.seed;
  r.max_cycles = a.max_cycles;
  r.time_limit = a.time_limit;
  const tsrrt::ClaspResult result = interruptible([&](std::function<bool()> stop) {
    r.stop = std::move(stop);
    return tsrrt::plan_clasp(r);
  });
  py::dict out;
  out["status"] = status_name(result.status);
  out["verified"] = result.verified;
  out["reason"] = result.reason;
  Matrix path(static_cast<Eigen::Index>(result.motion.waypoints.size()), robot->dof());
  for (size_t i = 0; i < result.motion.waypoints.size(); ++i)
    path.row(static_cast<Eigen::Index>(i)) = result.motion.waypoints[i].transpose();
  out["path"] = path;
  out["final_q"] = result.motion.final_q;
  out["start"] = result.start;
  const perception::Loop* loop = result.chosen_loop();
  out["loop"] = loop ? array_of(loop->points) : Matrix(0, 3);
  std::vector<Eigen::Vector3d> targets;
  for (const auto& t : result.targets) targets.push_back(t.point);
  out["targets"] = array_of(targets);
  out["target"] = result.motion.target;
  out["virtual_linking"] = result.final_state.virtual_linking;
  out["verification"] = cli::verification_json(result.verification).dump();
  out["next_best_view"] = py::none();
  if (const auto& v = result.next_view)
    out["next_best_view"] =
        py::dict(py::arg("position") = v->position, py::arg("target") = v->target,
                 py::arg("visible_voxels") = v->visible, py::arg("unknown_voxels") = v->unknown);
  out["object"] = object_dict(result.object);
  const tsrrt::ClaspTimings& t = result.timings;
  out["timings"] =
      py::dict(py::arg("perception") = t.perception, py::arg("scene") = t.scene,
               py::arg("search") = t.search, py::arg("planning") = t.planning,
               py::arg("closing") = t.closing, py::arg("verification") = t.verification,
               py::arg("pruning") = t.pruning);
  out["cycles"] = result.statistics.cycles;
  out["nodes"] = result.statistics.nodes;
  return out;
}

// A scenario file through the command line's pipeline: (exit code, `run --json`'s summary text).
std::pair<int, std::string> run_file(const std::string& path, std::optional<std::uint64_t> seed,
                                     std::optional<int> max_cycles,
                                     std::optional<double> time_limit, const std::string& robot,
                                     const std::string& out, bool pictures, bool controller_only,
                                     int next_views) {
  cli::Scenario s = cli::load_scenario(path);
  if (!robot.empty()) cli::use_robot(s, robot);
  cli::RunOptions o;
  o.out_dir = out;
  o.seed = seed;
  o.max_cycles = max_cycles;
  o.time_limit = time_limit;
  o.pictures = pictures;
  o.controller_only = controller_only;
  o.next_views = next_views;
  o.quiet = true;
  const cli::RunOutcome r = interruptible([&](std::function<bool()> stop) {
    o.stop = std::move(stop);
    return cli::run_scenario(s, o);
  });
  return {r.exit_code, r.summary.dump()};
}

}  // namespace
}  // namespace claspplan::python

PYBIND11_MODULE(_claspplan, m) {
  using namespace claspplan;
  using namespace claspplan::python;
  m.doc() = "claspplan's C++ core; use the package `claspplan`.";
  static py::exception<InputError> input_error(m, "InputError", PyExc_ValueError);
  py::register_exception_translator([](std::exception_ptr p) {
    try {
      if (p) std::rethrow_exception(p);
    } catch (const InputError& e) {
      PyErr_SetString(input_error.ptr(), e.what());
    }
  });

  py::class_<robots::RobotModel, Robot>(m, "Robot")
      .def(py::init([](const std::string& name) {
             return std::make_shared<robots::RobotModel>(robots::load_robot(name));
           }),
           py::arg("name"))
      .def_property_readonly("name", [](const Robot& r) { return r->name; })
      .def_property_readonly("source", [](const Robot& r) { return r->source; })
      .def_property_readonly("dof", [](const Robot& r) { return r->dof(); })
      .def_property_readonly("arm_dof", [](const Robot& r) { return r->arm_dof; })
      .def_property_readonly("hand_dof", [](const Robot& r) { return r->hand_dof; })
      .def_property_readonly("joint_names",
                             [](const Robot& r) {
                               std::vector<std::string> names;
                               for (const auto& j : r->joints) names.push_back(j.name);
                               return names;
                             })
      .def_property_readonly("lower", [](const Robot& r) { return r->lower(); })
      .def_property_readonly("upper", [](const Robot& r) { return r->upper(); })
      .def_property_readonly("home", [](const Robot& r) { return r->home; })
      .def_property_readonly("vlink_goal", [](const Robot& r) { return r->vlink_goal; })
      .def_property_readonly("warnings", [](const Robot& r) { return r->warnings; })
      .def("forward_kinematics", &forward_kinematics, py::arg("q"))
      .def("finger_curves", &finger_curves, py::arg("q"))
      .def("self_collisions", &self_collisions, py::arg("q"))
      .def("hand_size", [](const Robot& r) {
        const robots::HandSize s = robots::hand_size(*r);
        py::dict d;
        d["finger_thickness"] = s.finger_thickness;
        d["closed_aperture"] = s.closed_aperture;
        d["closed_q"] = s.closed_q;
        return d;
      });

  m.def(
      "linking_number",
      [](const Matrix& a, const Matrix& b) {
        return servo::linking_number(points_of(a, "a"), points_of(b, "b"));
      },
      py::arg("a"), py::arg("b"));
  m.def(
      "gauss_linking",
      [](const Matrix& a, bool a_closed, const Matrix& b, bool b_closed) {
        return servo::gauss_linking(points_of(a, "a"), a_closed, points_of(b, "b"), b_closed);
      },
      py::arg("a"), py::arg("a_closed"), py::arg("b"), py::arg("b_closed"));
  m.def(
      "virtual_linking",
      [](const Matrix& loop, const Matrix& finger) {
        return servo::virtual_linking(points_of(loop, "loop"), points_of(finger, "finger")).value;
      },
      py::arg("loop"), py::arg("finger"));

  m.def(
      "perceive",
      [](const DepthInputs& depth, const CloudInputs& clouds, const std::string& robot,
         const Crop& crop, int points, double d, std::uint64_t seed, bool no_reading_is_free) {
        PerceiveArgs a = object_args(depth, clouds, crop, points, d, seed, no_reading_is_free);
        a.robot = robot;
        perception::PerceptionOptions options = options_of(a);
        return object_dict(interruptible([&](std::function<bool()> stop) {
          options.stop = std::move(stop);
          return perception::build_object_model(inputs_of(a), options);
        }));
      },
      py::arg("depth"), py::arg("clouds"), py::arg("robot"), py::arg("crop"), py::arg("points"),
      py::arg("d"), py::arg("seed"), py::arg("no_reading_is_free"));
  m.def(
      "read_depth",
      [](const std::string& png, const std::string& camera) {
        const perception::CameraModel c = perception::read_camera_yaml(camera);
        const perception::DepthImage image = perception::read_depth_png(png, c);
        py::array_t<float> depth({image.height, image.width});
        std::copy(image.depth.begin(), image.depth.end(), depth.mutable_data());
        Eigen::Matrix3d K;
        K << c.fx, 0, c.cx, 0, c.fy, c.cy, 0, 0, 1;
        return py::make_tuple(depth, K, Eigen::Matrix4d(c.T_world_camera.matrix()),
                              c.no_reading_is_free);
      },
      py::arg("png"), py::arg("camera"));
  m.def(
      "read_cloud",
      [](const std::string& path) {
        const perception::SensorCloud c = perception::read_sensor_cloud(path);
        std::optional<Eigen::Matrix4d> viewpoint;
        if (c.viewpoint) viewpoint = c.viewpoint->matrix();
        return py::make_tuple(array_of(c.points), c.width, c.height, viewpoint);
      },
      py::arg("path"));
  m.def(
      "plan",
      [](const Robot& robot, const Eigen::VectorXd& start, const DepthInputs& depth,
         const CloudInputs& clouds,
         const std::vector<std::pair<Eigen::Vector3d, Eigen::Vector3d>>& boxes, const Crop& crop,
         int points, double d, int targets, std::optional<Eigen::Vector3d> near,
         std::optional<double> goal_linking, std::optional<int> pre_expansions,
         std::optional<double> random_probability, std::uint64_t seed,
         std::optional<int> max_cycles, std::optional<double> time_limit, bool no_reading_is_free,
         bool controller_only) {
        PlanArgs a;
        a.object = object_args(depth, clouds, crop, points, d, seed, no_reading_is_free);
        a.start = start;
        a.boxes = boxes;
        a.targets = targets;
        a.near = near;
        a.goal_linking = goal_linking;
        a.pre_expansions = pre_expansions;
        a.random_probability = random_probability;
        a.max_cycles = max_cycles;
        a.time_limit = time_limit;
        a.controller_only = controller_only;
        return plan(robot, a);
      },
      py::arg("robot"), py::arg("start"), py::arg("depth"), py::arg("clouds"), py::arg("boxes"),
      py::arg("crop"), py::arg("points"), py::arg("d"), py::arg("targets"), py::arg("near"),
      py::arg("goal_linking"), py::arg("pre_expansions"), py::arg("random_probability"),
      py::arg("seed"), py::arg("max_cycles"), py::arg("time_limit"), py::arg("no_reading_is_free"),
      py::arg("controller_only"));
  m.def(
      "verify_file",
      [](const std::string& path, std::optional<std::uint64_t> seed) {
        const cli::ResultFile r = cli::read_result_file(path);
        tsrrt::SecureClaspOptions check;
        if (seed) {
          check.seed = *seed;
        } else if (r.seed) {
          check.seed = *r.seed;
        }
        const tsrrt::SecureClaspReport v = interruptible([&](std::function<bool()> stop) {
          check.stop = std::move(stop);
          return tsrrt::check_secure_clasp(r.model, r.object_vertices, r.object_triangles,
                                           r.final_q, r.loop, check);
        });
        return cli::verification_json(v).dump();
      },
      py::arg("path"), py::arg("seed"));
  m.def(
      "run_file",
      [](const std::string& path, std::optional<std::uint64_t> seed, std::optional<int> max_cycles,
         std::optional<double> time_limit, const std::string& robot, const std::string& out,
         bool pictures, bool controller_only, int next_views) {
        return run_file(path, seed, max_cycles, time_limit, robot, out, pictures, controller_only,
                        next_views);
      },
      py::arg("path"), py::arg("seed"), py::arg("max_cycles"), py::arg("time_limit"),
      py::arg("robot"), py::arg("out"), py::arg("pictures"), py::arg("controller_only"),
      py::arg("next_views"));
}
