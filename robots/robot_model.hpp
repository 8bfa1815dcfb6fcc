// The immutable robot model: a URDF kinematic tree (urdfdom) plus a hand description (YAML) that
// names the arm and hand joints, the finger groups and finger curves (paper Sec. IV-B), the
// orientation vectors v_fwd / v_swd, the tool centre point, the open pre-shape and the default
// virtual-linking goal. Per-query results live in RobotData (robots/kinematics.hpp).
//
// Frames: the world frame is the URDF root link (base_link for the built-in robots), REP 103
// (x forward, y left, z up). Units: metres and radians.
//
// The actuated joint vector q: the arm joints first (hand description `arm.joints`, in that order),
// then the hand joints (`hand.joints`, in that order). Mimic joints (URDF <mimic>) follow their
// leader and joints listed under `hand.held` stay at their value; neither is in q, except a mimic
// listed in `hand.joints`: an adaptive joint (Joint::follows) of an underactuated hand.
#pragma once

#include <memory>
#include <string>
#include <utility>
#include <vector>

#include <Eigen/Core>
#include <Eigen/Geometry>

#include "core/input_error.hpp"
#include "core/mesh.hpp"

namespace claspplan::robots {

/// How a URDF joint moves its child link.
enum class JointType { kFixed, kRevolute, kPrismatic };

/// A collision shape of a link (from the URDF <collision> elements). A URDF cylinder with a sphere
/// of its radius centred on each end cap, in the same link, is merged into a capsule. A URDF mesh
/// (robots/mesh_resources.hpp) is a triangle mesh, checked as FCL's bounding-volume tree.
struct CollisionShape {
  enum class Type { kBox, kSphere, kCylinder, kCapsule, kMesh };
  Type type = Type::kBox;
  int link = -1;                  ///< index into RobotModel::links
  Eigen::Isometry3d origin;       ///< shape frame in the link frame (cylinder / capsule axis = z)
  Eigen::Vector3d size{0, 0, 0};  ///< box: full edge lengths
  double radius = 0.0;            ///< sphere, cylinder, capsule
  double length = 0.0;            ///< cylinder: full length; capsule: length of the axis segment
  /// mesh: its triangles in the shape's frame, scaled (shared by the model's copies).
  std::shared_ptr<const TriangleMesh> mesh;
  std::string source;  ///< mesh: the file it was read from
};
/// "box", "sphere", "cylinder", "capsule", "mesh".
const char* shape_type_name(CollisionShape::Type type);
/// The shape's box in its own frame (a mesh's: its vertices' bounds).
Eigen::AlignedBox3d shape_bounds(const CollisionShape& s);
/// The radius of the smallest sphere about the shape frame's origin that holds the shape.
double shape_reach(const CollisionShape& s);

/// A link and the joint that connects it to its parent. Links are stored parents first.
struct Link {
  std::string name;
  int parent = -1;    ///< parent link index, -1 for the root
  std::string joint;  ///< name of the joint from the parent ("" for the root)
  JointType type = JointType::kFixed;
  Eigen::Isometry3d origin = Eigen::Isometry3d::Identity();  ///< child frame in parent at value 0
  Eigen::Vector3d axis{0, 0, 1};                             ///< unit joint axis in the child frame
  /// The joint's value is multiplier * q[q_index] + offset; q_index = -1 means the constant offset
  /// (fixed-at-a-value "held" joints, mimics of held joints). Mimic chains are resolved.
  int q_index = -1;
  double multiplier = 1.0;
  double offset = 0.0;
  /// The entry of q whose Jacobian column this joint's motion is credited to, and its rate: q_index
  /// and multiplier, or for an adaptive joint (Joint::follows) its leader's, since planned motions
  /// move it with its leader.
  int column = -1;
  double column_multiplier = 1.0;
  /// Links on the path from the root to this link (this one included) whose joint depends on q,
  /// root side first: the columns of this link's Jacobians.
  std::vector<int> support;
  std::vector<int> shapes;  ///< indices into RobotModel::shapes
  bool hand = false;        ///< at or below the hand's base link
};

/// One entry of q.
/// The range a continuous joint is given: two turns either way, so that any angle a vendor
/// documents (a home at 4.8 rad, say) lies inside, and a planner still has finite limits.
constexpr double kContinuousRange = 4.0 * 3.14159265358979323846;

struct Joint {
  std::string name;
  double lower = 0.0, upper = 0.0;  ///< limits (continuous joints: +-kContinuousRange / 2)
  double velocity = 0.0;            ///< URDF velocity limit (rad/s or m/s)
  bool hand = false;                ///< a hand joint (else an arm joint)
  int link = -1;                    ///< the child link of this joint
  double open = 0.0;  ///< hand: value in the open pre-shape; arm: value in the home pose
  int closing = 0;    ///< hand: +1 / -1 the direction that closes the finger, 0 none; arm: 0
  /// An adaptive joint (a URDF mimic joint listed in `hand.joints`: an underactuated finger) is an
  /// entry of q that follows the entry `follows` (follow_multiplier × it + follow_offset, within
  /// its own limits) in every planned motion, but stops on its own when the fingers close on the
  /// object. -1 for every other joint.
  int follows = -1;
  double follow_multiplier = 1.0;
  double follow_offset = 0.0;
};

/// A point fixed to a link: `point` in the link's frame.
struct LinkPoint {
  int link = -1;
  Eigen::Vector3d point{0, 0, 0};
};

/// A direction fixed to a link: unit `vector` in the link's frame.
struct LinkVector {
  int link = -1;
  Eigen::Vector3d vector{0, 0, 1};
};

/// A finger curve α (paper Sec. IV-B): an open polyline from a fingertip through that finger's
/// joints, a palm point and the thumb's joints to the thumb tip.
struct FingerCurve {
  std::string name;
  std::vector<LinkPoint> points;
};

/// The joints and links of one finger (the thumb included), so that a planner can close each
/// finger on its own until contact.
struct Finger {
  std::string name;
  bool thumb = false;
  std::vector<int> joints;  ///< q indices
  std::vector<int> links;   ///< link indices
};

/// The robot: kinematic tree, q layout, collision shapes, hand description. Build it with
/// load_robot(); treat it as immutable (share it by const reference).
struct RobotModel {
  std::string name;
  std::string source;  ///< the description it came from (built-in name or file path)

  std::vector<Link> links;    ///< parents before children; links[0] is the root (world frame)
  std::vector<Joint> joints;  ///< the actuated joints, in q order (arm, then hand)
  int arm_dof = 0;
  int hand_dof = 0;
  int dof() const { return static_cast<int>(joints.size()); }

  std::vector<CollisionShape> shapes;
  /// What loading skipped, one line each (placeholder geometry: a zero-size box, sphere,
  /// cylinder or mesh scale in the URDF is no shape).
  std::vector<std::string> warnings;
  /// Link pairs (i < j) excluded from self-collision checks besides adjacent links (hand
  /// description `collision.allowed_pairs`).
  std::vector<std::pair<int, int>> allowed_pairs;

  // Hand description.
  int tool_link = -1;       ///< the arm's tool frame (tool0)
  int hand_base_link = -1;  ///< the hand's root link
  std::vector<Finger> fingers;
  std::vector<FingerCurve> curves;
  LinkPoint tcp;
  LinkVector v_fwd;  ///< approach direction (tool0 +z for the built-in hands)
  LinkVector v_swd;  ///< sideways: the closing plane's normal = desired loop tangent direction
  double vlink_goal = 0.8;  ///< default virtual-linking goal (paper Sec. V)
  Eigen::VectorXd home;     ///< default start: arm home pose and the hand's open pre-shape

  /// Index of a link / actuated joint by name; throws InputError when unknown.
  int link_index(const std::string& link_name) const;
  int joint_index(const std::string& joint_name) const;
  /// -1 when unknown.
  int find_link(const std::string& link_name) const;
  int find_joint(const std::string& joint_name) const;

  /// The limits as vectors (dof).
  Eigen::VectorXd lower() const;
  Eigen::VectorXd upper() const;
  /// q with every entry clamped into its limits.
  Eigen::VectorXd clamp(const Eigen::VectorXd& q) const;
  /// True when q has dof() finite entries within the limits (+ tolerance).
  bool within_limits(const Eigen::VectorXd& q, double tolerance = 1e-9) const;
  /// q with every adaptive joint set from its leader (Joint::follows): the hand of a planned
  /// motion. The identity for a robot without adaptive joints.
  Eigen::VectorXd couple(const Eigen::VectorXd& q) const;
  /// q with its hand part replaced by the open pre-shape.
  Eigen::VectorXd open_hand(const Eigen::VectorXd& q) const;
  /// Joint values for `q` given as a shorter prefix: the rest from `home`. Throws
  /// InputError for too many values, NaN/Inf or values outside the limits (naming the
  /// joint and its limits).
  Eigen::VectorXd complete_q(const std::vector<double>& prefix) const;
};

/// The built-in robots: kr5_sdh, kr5_dlr, kr5_icub, kr5_armar3.
std::vector<std::string> builtin_robots();

/// Loads a robot: a built-in name (its URDF and hand description are embedded in the library,
/// so it works from any directory) or the path of a hand-description YAML file, whose `urdf` key
/// names the URDF file (relative to the YAML file's folder). Any problem -> InputError
/// with a one-line reason naming the file ("kr5.yaml: hand.curves[0]: unknown link 'x'").
RobotModel load_robot(const std::string& name_or_path);

/// Builds a robot from the texts of its hand description and URDF; `yaml_name` and `urdf_name`
/// only label error messages. `urdf_text` is used instead of reading the YAML's `urdf` file.
RobotModel load_robot_from_text(const std::string& yaml_text, const std::string& urdf_text,
                                const std::string& yaml_name = "robot.yaml",
                                const std::string& urdf_name = "robot.urdf");

}  // namespace claspplan::robots
