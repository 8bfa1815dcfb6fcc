// Scenario files (YAML): a robot, an object seen by depth cameras (or given as a cloud or mesh), a
// static environment, a start configuration, which loop to clasp, and the parameters of
// perception, controller and planner. The format is documented in the README ("Scenario files");
// paths inside a scenario are relative to the scenario file.
#pragma once

#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include <Eigen/Geometry>

#include "core/input_error.hpp"
#include "examples/objects.hpp"
#include "perception/depth_render.hpp"
#include "perception/pipeline.hpp"
#include "robots/robot_model.hpp"
#include "servo/clasp_controller.hpp"
#include "servo/controller_run.hpp"
#include "tsrrt/clasp_scene.hpp"
#include "tsrrt/clasp_setup.hpp"

namespace claspplan::cli {

/// A procedural object of examples/objects.hpp with its parameters.
struct ShapeSpec {
  /// torus, purse, sphere, holed_plate, container, or a paper object without parameters (bag,
  /// travelbag, lawnmower, chair: examples/paper_objects.hpp)
  std::string type;
  double major_radius = 0.1, minor_radius = 0.012;  ///< torus
  double radius = 0.1;                              ///< sphere
  int holes = 2;                                    ///< holed_plate
  objects::Purse purse;                             ///< purse: body, handle_radius, handle_tube
  objects::Container container;  ///< container: radius, height, wall, handle_radius (0: none), ...
};

struct ObjectSpec {
  std::vector<std::pair<std::string, std::string>> depth;  ///< (png, camera yaml) pairs
  /// .pcd/.ply/.xyz files with their frames in the world and sensor origins (perception::add_cloud)
  std::vector<perception::CloudFile> clouds;
  std::vector<bool> cloud_pose_given;  ///< per cloud: placed by its own `pose` (not the object's)
  std::string mesh;                    ///< a mesh file (.obj/.ply/.stl/.off)
  std::optional<ShapeSpec> shape;      ///< or a procedural object
  Eigen::Isometry3d pose = Eigen::Isometry3d::Identity();  ///< of a mesh, shape or clouds' frame
  /// Or place a mesh or shape's frame this far (m) in front of the hand at the start: at the tcp
  /// plus this times v_fwd, its z axis along v_fwd x v_swd and its x axis back toward the hand
  /// (place_in_front_of_hand()). A torus's near strand is then major_radius closer, along v_swd.
  std::optional<double> in_front_of_hand;
  /// Sample a mesh or shape only where visible from these camera positions (empty: whole surface).
  std::vector<Eigen::Vector3d> views;
  /// Or see it through synthetic depth cameras: the mesh and the environment boxes are rendered
  /// into depth images (z-buffer, with `noise`), which then go through the depth pipeline.
  std::vector<std::pair<Eigen::Vector3d, Eigen::Vector3d>> cameras;  ///< (position, target)
  perception::DepthNoise noise;
  /// Other objects beside it (boxes), rendered by the synthetic cameras but not given to the
  /// planner as environment: it learns of them from the depth images alone.
  std::vector<tsrrt::EnvironmentBox> clutter;
};

using EnvironmentBox = tsrrt::EnvironmentBox;  ///< pose (centre) and size

struct Scenario {
  std::string path;  ///< the file, as given
  std::string name;
  std::string robot;          ///< built-in name or resolved hand-description path
  std::vector<double> start;  ///< q prefix (arm, then hand); the rest from the robot's home
  ObjectSpec object;
  std::vector<EnvironmentBox> boxes;
  std::optional<Eigen::Vector3d> loop_hint;  ///< clasp the claspable loop nearest this point
  std::uint64_t seed = 1;
  perception::PerceptionOptions perception;
  servo::ControllerParameters controller;
  servo::ControllerRunOptions controller_run;
  tsrrt::ClaspPlanningOptions planning;
  std::optional<double> goal_linking;  ///< planner.goal_linking; none: the robot's own
};

/// The secure-clasp check's budget: sequences x motions at most this many motions (20 times the
/// paper's 10 x 500), so that a check ends even without a time limit (about 20 times the default
/// check's time, which is 2 s for the demo).
constexpr long kMaxVerificationMotions = 100000;

/// Throws InputError (naming the options `sequences` and `motions`) when a check would exceed
/// kMaxVerificationMotions.
void check_verification_budget(const tsrrt::SecureClaspOptions& check, const std::string& sequences,
                               const std::string& motions);

/// Reads and validates a scenario. Throws InputError with the file and key for missing
/// files, malformed YAML, unknown keys, wrong types and out-of-range values.
/// Sets scenario.object.pose from object.in_front_of_hand (nothing without it) for this robot at
/// the scenario's start: the same placement works for any hand.
void place_in_front_of_hand(Scenario& scenario, const robots::RobotModel& robot);

Scenario load_scenario(const std::string& path);

/// Sets the scenario's robot: a built-in name, or a hand-description file relative to `base_dir`
/// (recorded by its absolute path). `run --robot` and `bench --robot` try a scenario with another
/// robot whose arm its start fits.
void use_robot(Scenario& scenario, const std::string& robot, const std::string& base_dir = ".");

/// The same from a scenario's text; `path` names it in messages, `base_dir` resolves its paths.
Scenario load_scenario_text(const std::string& text, const std::string& path,
                            const std::string& base_dir);

/// The boxes as one triangle mesh (what depth cameras see of the environment).
TriangleMesh boxes_mesh(const std::vector<EnvironmentBox>& boxes);

/// What a scenario's synthetic depth cameras see (object: cameras): its mesh or shape at its
/// pose, the environment boxes and the clutter, in the world frame. The truth a planned path can
/// be checked against; none for depth files and clouds, whose truth is unknown.
std::optional<TriangleMesh> rendered_scene(const Scenario& scenario);

/// Builds the perception inputs the scenario's object describes (files read, shapes meshed,
/// synthetic depth images rendered).
perception::PerceptionInputs scenario_inputs(const Scenario& scenario);

}  // namespace claspplan::cli
