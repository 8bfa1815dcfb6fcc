#include "robots/robot_model.hpp"

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <functional>
#include <map>
#include <mutex>
#include <set>
#include <sstream>
#include <stdexcept>

#include <console_bridge/console.h>
#include <urdf_parser/urdf_parser.h>
#include <yaml-cpp/yaml.h>

#include "robots/embedded_models.hpp"

namespace claspplan::robots {

const char* shape_type_name(CollisionShape::Type type) {
  switch (type) {
    case CollisionShape::Type::kBox:
      return "box";
    case CollisionShape::Type::kSphere:
      return "sphere";
    case CollisionShape::Type::kCylinder:
      return "cylinder";
    case CollisionShape::Type::kCapsule:
      return "capsule";
  }
  return "unknown";
}

// ---------------------------------------------------------------------------------------------
// RobotModel members

int RobotModel::find_link(const std::string& link_name) const {
  for (size_t i = 0; i < links.size(); ++i)
    if (links[i].name == link_name) return static_cast<int>(i);
  return -1;
}

int RobotModel::find_joint(const std::string& joint_name) const {
  for (size_t i = 0; i < joints.size(); ++i)
    if (joints[i].name == joint_name) return static_cast<int>(i);
  return -1;
}

int RobotModel::link_index(const std::string& link_name) const {
  const int i = find_link(link_name);
  if (i < 0) throw std::invalid_argument(name + ": no link named '" + link_name + "'");
  return i;
}

int RobotModel::joint_index(const std::string& joint_name) const {
  const int i = find_joint(joint_name);
  if (i < 0) throw std::invalid_argument(name + ": no actuated joint named '" + joint_name + "'");
  return i;
}

Eigen::VectorXd RobotModel::lower() const {
  Eigen::VectorXd v(dof());
  for (int i = 0; i < dof(); ++i) v[i] = joints[i].lower;
  return v;
}

Eigen::VectorXd RobotModel::upper() const {
  Eigen::VectorXd v(dof());
  for (int i = 0; i < dof(); ++i) v[i] = joints[i].upper;
  return v;
}

Eigen::VectorXd RobotModel::clamp(const Eigen::VectorXd& q) const {
  Eigen::VectorXd c = q;
  for (int i = 0; i < dof() && i < q.size(); ++i)
    c[i] = std::min(std::max(q[i], joints[i].lower), joints[i].upper);
  return c;
}

bool RobotModel::within_limits(const Eigen::VectorXd& q, double tolerance) const {
  if (q.size() != dof()) return false;
  for (int i = 0; i < dof(); ++i) {
    if (!std::isfinite(q[i])) return false;
    if (q[i] < joints[i].lower - tolerance || q[i] > joints[i].upper + tolerance) return false;
  }
  return true;
}

Eigen::VectorXd RobotModel::open_hand(const Eigen::VectorXd& q) const {
  Eigen::VectorXd r = q;
  for (int i = arm_dof; i < dof(); ++i) r[i] = joints[i].open;
  return r;
}

Eigen::VectorXd RobotModel::complete_q(const std::vector<double>& prefix) const {
  if (static_cast<int>(prefix.size()) > dof()) {
    throw std::invalid_argument(name + " has " + std::to_string(dof()) + " actuated joints, got " +
                                std::to_string(prefix.size()) + " values");
  }
  Eigen::VectorXd q = home;
  for (size_t i = 0; i < prefix.size(); ++i) {
    const Joint& j = joints[i];
    const double v = prefix[i];
    if (!std::isfinite(v)) {
      throw std::invalid_argument("value " + std::to_string(i + 1) + " (" + j.name +
                                  ") is not a finite number");
    }
    if (v < j.lower - 1e-9 || v > j.upper + 1e-9) {
      std::ostringstream s;
      s << j.name << " = " << v << " is outside its limits [" << j.lower << ", " << j.upper << "]";
      throw std::invalid_argument(s.str());
    }
    q[i] = std::min(std::max(v, j.lower), j.upper);
  }
  return q;
}

namespace {

[[noreturn]] void fail(const std::string& file, const std::string& what) {
  throw std::invalid_argument(file + ": " + what);
}

std::string one_line(std::string s) {
  for (char& c : s)
    if (c == '\n' || c == '\r') c = ' ';
  while (!s.empty() && s.back() == ' ') s.pop_back();
  return s;
}

// ---------------------------------------------------------------------------------------------
// URDF

// urdfdom reports problems through console_bridge; keep the first error for the message and
// keep stderr clean.
class CaptureErrors : public console_bridge::OutputHandler {
 public:
  void log(const std::string& text, console_bridge::LogLevel level, const char*, int) override {
    if (level >= console_bridge::CONSOLE_BRIDGE_LOG_ERROR && first_error.empty()) {
      first_error = one_line(text);
    }
  }
  std::string first_error;
};

std::mutex& urdf_mutex() {
  static std::mutex m;
  return m;
}

Eigen::Isometry3d to_isometry(const urdf::Pose& p) {
  Eigen::Isometry3d t = Eigen::Isometry3d::Identity();
  t.translation() = Eigen::Vector3d(p.position.x, p.position.y, p.position.z);
  t.linear() =
      Eigen::Quaterniond(p.rotation.w, p.rotation.x, p.rotation.y, p.rotation.z).toRotationMatrix();
  return t;
}

bool finite(const Eigen::Isometry3d& t) {
  return t.matrix().allFinite();
}

urdf::ModelInterfaceSharedPtr parse_urdf(const std::string& text, const std::string& file) {
  if (text.find_first_not_of(" \t\r\n") == std::string::npos) fail(file, "the URDF is empty");
  std::lock_guard<std::mutex> lock(urdf_mutex());
  CaptureErrors capture;
  console_bridge::OutputHandler* previous = console_bridge::getOutputHandler();
  console_bridge::useOutputHandler(&capture);
  urdf::ModelInterfaceSharedPtr model;
  try {
    model = urdf::parseURDF(text);
  } catch (const std::exception& e) {
    capture.first_error = one_line(e.what());
  }
  console_bridge::useOutputHandler(previous);
  if (!model) {
    fail(file, "not a valid URDF: " + (capture.first_error.empty() ? std::string("parse failed")
                                                                   : capture.first_error));
  }
  return model;
}

// Converts the URDF <collision> elements of one link; merges cylinder + two end spheres into a
// capsule (URDF has no capsule primitive).
std::vector<CollisionShape> link_shapes(const urdf::Link& link, int index,
                                        const std::string& file) {
  std::vector<CollisionShape> shapes;
  for (const auto& c : link.collision_array) {
    if (!c || !c->geometry) continue;
    CollisionShape s;
    s.link = index;
    s.origin = to_isometry(c->origin);
    if (!finite(s.origin)) fail(file, "link '" + link.name + "': collision origin is not finite");
    switch (c->geometry->type) {
      case urdf::Geometry::BOX: {
        const auto& b = static_cast<const urdf::Box&>(*c->geometry);
        s.type = CollisionShape::Type::kBox;
        s.size = Eigen::Vector3d(b.dim.x, b.dim.y, b.dim.z);
        if (!s.size.allFinite() || (s.size.array() <= 0).any())
          fail(file, "link '" + link.name + "': box sizes must be finite and > 0");
        break;
      }
      case urdf::Geometry::SPHERE: {
        const auto& sp = static_cast<const urdf::Sphere&>(*c->geometry);
        s.type = CollisionShape::Type::kSphere;
        s.radius = sp.radius;
        if (!std::isfinite(s.radius) || s.radius <= 0)
          fail(file, "link '" + link.name + "': sphere radius must be finite and > 0");
        break;
      }
      case urdf::Geometry::CYLINDER: {
        const auto& cy = static_cast<const urdf::Cylinder&>(*c->geometry);
        s.type = CollisionShape::Type::kCylinder;
        s.radius = cy.radius;
        s.length = cy.length;
        if (!std::isfinite(s.radius) || s.radius <= 0 || !std::isfinite(s.length) || s.length <= 0)
          fail(file, "link '" + link.name + "': cylinder radius and length must be finite and > 0");
        break;
      }
      default:
        fail(file,
             "link '" + link.name +
                 "': only box, sphere and cylinder collision geometry is supported (no meshes)");
    }
    shapes.push_back(s);
  }
  // Capsule merge.
  std::vector<bool> used(shapes.size(), false);
  std::vector<CollisionShape> merged;
  for (size_t i = 0; i < shapes.size(); ++i) {
    if (shapes[i].type != CollisionShape::Type::kCylinder || used[i]) continue;
    const CollisionShape& cy = shapes[i];
    const Eigen::Vector3d axis = cy.origin.linear().col(2);
    const Eigen::Vector3d ends[2] = {cy.origin.translation() + 0.5 * cy.length * axis,
                                     cy.origin.translation() - 0.5 * cy.length * axis};
    int found[2] = {-1, -1};
    for (int e = 0; e < 2; ++e) {
      for (size_t j = 0; j < shapes.size(); ++j) {
        if (used[j] || j == i || static_cast<int>(j) == found[0]) continue;
        const CollisionShape& sp = shapes[j];
        if (sp.type == CollisionShape::Type::kSphere && std::abs(sp.radius - cy.radius) < 1e-9 &&
            (sp.origin.translation() - ends[e]).norm() < 1e-6) {
          found[e] = static_cast<int>(j);
          break;
        }
      }
    }
    if (found[0] >= 0 && found[1] >= 0) {
      used[i] = used[found[0]] = used[found[1]] = true;
      CollisionShape cap = cy;
      cap.type = CollisionShape::Type::kCapsule;
      merged.push_back(cap);
    }
  }
  for (size_t i = 0; i < shapes.size(); ++i)
    if (!used[i]) merged.push_back(shapes[i]);
  return merged;
}

// ---------------------------------------------------------------------------------------------
// YAML helpers: every error names the file, the key path and (when known) the line.

struct Yaml {
  std::string file;

  [[noreturn]] void error(const YAML::Node& node, const std::string& path,
                          const std::string& what) const {
    std::string where = path;
    if (node.IsDefined() && node.Mark().line >= 0)
      where = "line " + std::to_string(node.Mark().line + 1) + ": " + path;
    fail(file, where + ": " + what);
  }

  YAML::Node required(const YAML::Node& map, const std::string& key,
                      const std::string& path) const {
    if (!map.IsMap()) error(map, path, "expected a mapping");
    YAML::Node n = map[key];
    if (!n.IsDefined() || n.IsNull()) error(map, path, "missing key '" + key + "'");
    return n;
  }

  void allowed_keys(const YAML::Node& map, const std::string& path,
                    const std::set<std::string>& keys) const {
    if (!map.IsMap()) error(map, path, "expected a mapping");
    for (const auto& kv : map) {
      const std::string k = kv.first.as<std::string>();
      if (!keys.count(k)) error(kv.first, path, "unknown key '" + k + "'");
    }
  }

  double number(const YAML::Node& n, const std::string& path) const {
    if (!n.IsScalar()) error(n, path, "expected a number");
    double v = 0.0;
    try {
      v = n.as<double>();
    } catch (const YAML::Exception&) {
      error(n, path, "expected a number, got '" + n.Scalar() + "'");
    }
    if (!std::isfinite(v)) error(n, path, "must be finite, got '" + n.Scalar() + "'");
    return v;
  }

  std::string string(const YAML::Node& n, const std::string& path) const {
    if (!n.IsScalar() || n.Scalar().empty()) error(n, path, "expected a non-empty name");
    return n.Scalar();
  }

  bool boolean(const YAML::Node& n, const std::string& path) const {
    if (!n.IsScalar()) error(n, path, "expected true or false");
    try {
      return n.as<bool>();
    } catch (const YAML::Exception&) {
      error(n, path, "expected true or false, got '" + n.Scalar() + "'");
    }
  }

  std::vector<std::string> strings(const YAML::Node& n, const std::string& path) const {
    if (!n.IsSequence()) error(n, path, "expected a list of names");
    std::vector<std::string> out;
    for (size_t i = 0; i < n.size(); ++i)
      out.push_back(string(n[i], path + "[" + std::to_string(i) + "]"));
    return out;
  }

  Eigen::Vector3d vec3(const YAML::Node& n, const std::string& path) const {
    if (!n.IsSequence() || n.size() != 3) error(n, path, "expected a list of 3 numbers");
    return Eigen::Vector3d(number(n[0], path + "[0]"), number(n[1], path + "[1]"),
                           number(n[2], path + "[2]"));
  }

  YAML::Node sequence(const YAML::Node& n, const std::string& path) const {
    if (!n.IsSequence()) error(n, path, "expected a list");
    return n;
  }
};

// What the YAML says, before it is checked against the URDF.
struct HandJointSpec {
  std::string name;
  double open = 0.0;
  int closing = 0;
  YAML::Node node;
};

// ---------------------------------------------------------------------------------------------

RobotModel build_model(const YAML::Node& root, const Yaml& y, const urdf::ModelInterface& urdf,
                       const std::string& urdf_file, const std::string& source) {
  RobotModel m;
  m.source = source;
  y.allowed_keys(root, "(top level)", {"name", "urdf", "arm", "hand", "collision"});
  m.name = y.string(y.required(root, "name", "(top level)"), "name");

  // --- Links, parents first (depth-first; urdfdom orders children by joint name).
  const auto urdf_root = urdf.getRoot();
  if (!urdf_root) fail(urdf_file, "the URDF has no root link");
  std::map<std::string, const urdf::Joint*> joint_of_link;
  std::function<void(const urdf::Link&, int)> visit = [&](const urdf::Link& l, int parent) {
    Link link;
    link.name = l.name;
    link.parent = parent;
    if (l.parent_joint) {
      const urdf::Joint& j = *l.parent_joint;
      link.joint = j.name;
      link.origin = to_isometry(j.parent_to_joint_origin_transform);
      if (!finite(link.origin)) fail(urdf_file, "joint '" + j.name + "': origin is not finite");
      switch (j.type) {
        case urdf::Joint::FIXED:
          link.type = JointType::kFixed;
          break;
        case urdf::Joint::REVOLUTE:
        case urdf::Joint::CONTINUOUS:
          link.type = JointType::kRevolute;
          break;
        case urdf::Joint::PRISMATIC:
          link.type = JointType::kPrismatic;
          break;
        default:
          fail(urdf_file,
               "joint '" + j.name +
                   "': only fixed, revolute, continuous and prismatic joints are supported");
      }
      if (link.type != JointType::kFixed) {
        link.axis = Eigen::Vector3d(j.axis.x, j.axis.y, j.axis.z);
        if (!link.axis.allFinite() || link.axis.norm() < 1e-9)
          fail(urdf_file, "joint '" + j.name + "': axis must be a finite non-zero vector");
        link.axis.normalize();
      }
      joint_of_link[l.name] = &j;
    }
    const int index = static_cast<int>(m.links.size());
    m.links.push_back(link);
    for (const auto& s : link_shapes(l, index, urdf_file)) {
      m.links[index].shapes.push_back(static_cast<int>(m.shapes.size()));
      m.shapes.push_back(s);
    }
    for (const auto& child : l.child_links) visit(*child, index);
  };
  visit(*urdf_root, -1);
  std::map<std::string, int> link_by_joint;
  for (size_t i = 1; i < m.links.size(); ++i) link_by_joint[m.links[i].joint] = static_cast<int>(i);

  auto link_of = [&](const YAML::Node& n, const std::string& path) {
    const std::string name = y.string(n, path);
    const int i = m.find_link(name);
    if (i < 0) y.error(n, path, "unknown link '" + name + "' (not in " + urdf_file + ")");
    return i;
  };
  auto movable_joint = [&](const YAML::Node& n, const std::string& path) {
    const std::string name = y.string(n, path);
    auto it = link_by_joint.find(name);
    if (it == link_by_joint.end())
      y.error(n, path, "unknown joint '" + name + "' (not in " + urdf_file + ")");
    if (m.links[it->second].type == JointType::kFixed)
      y.error(n, path, "joint '" + name + "' is fixed in the URDF");
    return it->second;
  };

  // --- arm
  const YAML::Node arm = y.required(root, "arm", "(top level)");
  y.allowed_keys(arm, "arm", {"joints", "home", "tool_link"});
  const YAML::Node arm_joints = y.sequence(y.required(arm, "joints", "arm"), "arm.joints");
  std::vector<int> q_links;  // child link of each q entry
  std::vector<YAML::Node> q_nodes;
  for (size_t i = 0; i < arm_joints.size(); ++i) {
    q_links.push_back(movable_joint(arm_joints[i], "arm.joints[" + std::to_string(i) + "]"));
    q_nodes.push_back(arm_joints[i]);
  }
  m.arm_dof = static_cast<int>(q_links.size());
  m.tool_link = link_of(y.required(arm, "tool_link", "arm"), "arm.tool_link");

  // --- hand
  const YAML::Node hand = y.required(root, "hand", "(top level)");
  y.allowed_keys(
      hand, "hand",
      {"base_link", "joints", "held", "fingers", "curves", "tcp", "v_fwd", "v_swd", "vlink_goal"});
  m.hand_base_link = link_of(y.required(hand, "base_link", "hand"), "hand.base_link");
  const YAML::Node hand_joints = y.sequence(y.required(hand, "joints", "hand"), "hand.joints");
  if (hand_joints.size() == 0) y.error(hand_joints, "hand.joints", "the list is empty");
  std::vector<HandJointSpec> hand_specs;
  for (size_t i = 0; i < hand_joints.size(); ++i) {
    const std::string path = "hand.joints[" + std::to_string(i) + "]";
    const YAML::Node n = hand_joints[i];
    y.allowed_keys(n, path, {"name", "open", "closing"});
    HandJointSpec s;
    s.node = n;
    s.name = y.string(y.required(n, "name", path), path + ".name");
    q_links.push_back(movable_joint(n["name"], path + ".name"));
    q_nodes.push_back(n["name"]);
    if (n["open"]) s.open = y.number(n["open"], path + ".open");
    if (n["closing"]) {
      const double c = y.number(n["closing"], path + ".closing");
      if (c != 1.0 && c != -1.0 && c != 0.0)
        y.error(n["closing"], path, "closing must be 1, -1 or 0");
      s.closing = static_cast<int>(c);
    }
    hand_specs.push_back(s);
  }
  m.hand_dof = static_cast<int>(hand_specs.size());

  // Actuated joints; no joint twice.
  std::map<int, int> q_of_link;
  for (size_t i = 0; i < q_links.size(); ++i) {
    const int li = q_links[i];
    if (q_of_link.count(li))
      y.error(q_nodes[i], "joints", "joint '" + m.links[li].joint + "' is listed twice");
    q_of_link[li] = static_cast<int>(i);
    const urdf::Joint& uj = *joint_of_link.at(m.links[li].name);
    if (uj.mimic)
      y.error(q_nodes[i], "joints", "joint '" + uj.name + "' is a mimic joint and cannot be in q");
    Joint j;
    j.name = uj.name;
    j.link = li;
    j.hand = static_cast<int>(i) >= m.arm_dof;
    if (uj.type == urdf::Joint::CONTINUOUS) {
      j.lower = -M_PI;  // one turn: a planner needs finite limits
      j.upper = M_PI;
    } else {
      if (!uj.limits) fail(urdf_file, "joint '" + uj.name + "' has no <limit>");
      j.lower = uj.limits->lower;
      j.upper = uj.limits->upper;
      if (!std::isfinite(j.lower) || !std::isfinite(j.upper) || j.lower > j.upper) {
        fail(urdf_file, "joint '" + uj.name + "': limits must be finite with lower <= upper");
      }
    }
    if (uj.limits) j.velocity = uj.limits->velocity;
    m.joints.push_back(j);
    Link& l = m.links[li];
    l.q_index = static_cast<int>(i);
  }
  for (int i = 0; i < m.hand_dof; ++i) {
    Joint& j = m.joints[m.arm_dof + i];
    j.open = hand_specs[i].open;
    j.closing = hand_specs[i].closing;
    if (j.open < j.lower - 1e-9 || j.open > j.upper + 1e-9) {
      std::ostringstream s;
      s << "open value " << j.open << " of '" << j.name << "' is outside its limits [" << j.lower
        << ", " << j.upper << "]";
      y.error(hand_specs[i].node, "hand.joints[" + std::to_string(i) + "]", s.str());
    }
  }

  // Home: the arm's home pose (default 0, clamped into the limits) and the open hand.
  m.home = Eigen::VectorXd::Zero(m.dof());
  if (arm["home"]) {
    const YAML::Node h = y.sequence(arm["home"], "arm.home");
    if (static_cast<int>(h.size()) != m.arm_dof)
      y.error(h, "arm.home", "expected " + std::to_string(m.arm_dof) + " values");
    for (int i = 0; i < m.arm_dof; ++i) {
      const double v = y.number(h[i], "arm.home[" + std::to_string(i) + "]");
      const Joint& j = m.joints[i];
      if (v < j.lower - 1e-9 || v > j.upper + 1e-9)
        y.error(h[i], "arm.home", "value for '" + j.name + "' is outside its limits");
      m.home[i] = v;
    }
  } else {
    m.home = m.clamp(m.home);
  }
  for (int i = 0; i < m.arm_dof; ++i) m.joints[i].open = m.home[i];
  for (int i = m.arm_dof; i < m.dof(); ++i) m.home[i] = m.joints[i].open;

  // Held joints: constant values.
  std::map<int, double> held;
  if (hand["held"] && !hand["held"].IsNull()) {
    const YAML::Node h = hand["held"];
    if (!h.IsMap()) y.error(h, "hand.held", "expected a mapping joint: value");
    for (const auto& kv : h) {
      const std::string path = "hand.held." + kv.first.Scalar();
      const int li = movable_joint(kv.first, path);
      if (q_of_link.count(li)) y.error(kv.first, path, "a held joint cannot also be in q");
      const urdf::Joint& uj = *joint_of_link.at(m.links[li].name);
      if (uj.mimic) y.error(kv.first, path, "joint '" + uj.name + "' is a mimic joint");
      const double v = y.number(kv.second, path);
      if (uj.limits && uj.type != urdf::Joint::CONTINUOUS &&
          (v < uj.limits->lower - 1e-9 || v > uj.limits->upper + 1e-9))
        y.error(kv.second, path, "value is outside the joint's limits");
      held[li] = v;
    }
  }

  // Every movable joint: in q, held, or a mimic (resolved to its root leader).
  std::map<int, int> state;  // 0 unvisited, 1 in progress, 2 done
  std::function<void(int)> resolve = [&](int li) {
    Link& l = m.links[li];
    if (l.type == JointType::kFixed || state[li] == 2) return;
    if (state[li] == 1) fail(urdf_file, "mimic joints form a cycle at '" + l.joint + "'");
    state[li] = 1;
    const urdf::Joint& uj = *joint_of_link.at(l.name);
    if (q_of_link.count(li)) {
      l.q_index = q_of_link[li];
      l.multiplier = 1.0;
      l.offset = 0.0;
    } else if (held.count(li)) {
      l.q_index = -1;
      l.offset = held[li];
    } else if (uj.mimic) {
      auto it = link_by_joint.find(uj.mimic->joint_name);
      if (it == link_by_joint.end())
        fail(urdf_file,
             "joint '" + uj.name + "' mimics unknown joint '" + uj.mimic->joint_name + "'");
      if (!std::isfinite(uj.mimic->multiplier) || !std::isfinite(uj.mimic->offset))
        fail(urdf_file, "joint '" + uj.name + "': mimic multiplier and offset must be finite");
      const int leader = it->second;
      if (m.links[leader].type == JointType::kFixed)
        fail(urdf_file,
             "joint '" + uj.name + "' mimics the fixed joint '" + uj.mimic->joint_name + "'");
      resolve(leader);
      const Link& ld = m.links[leader];
      l.q_index = ld.q_index;
      l.multiplier = uj.mimic->multiplier * ld.multiplier;
      l.offset = uj.mimic->multiplier * ld.offset + uj.mimic->offset;
      if (l.q_index < 0) l.multiplier = 1.0;
    } else {
      fail(source, "joint '" + uj.name +
                       "' moves but is not listed in arm.joints, hand.joints or hand.held, and is "
                       "not a mimic joint");
    }
    state[li] = 2;
  };
  for (size_t i = 1; i < m.links.size(); ++i) resolve(static_cast<int>(i));

  // Jacobian support and the hand flag.
  for (size_t i = 0; i < m.links.size(); ++i) {
    Link& l = m.links[i];
    if (l.parent >= 0) {
      l.support = m.links[l.parent].support;
      l.hand = m.links[l.parent].hand;
    }
    if (static_cast<int>(i) == m.hand_base_link) l.hand = true;
    if (l.type != JointType::kFixed && l.q_index >= 0) l.support.push_back(static_cast<int>(i));
  }
  for (int i = 0; i < m.dof(); ++i) {
    if (m.joints[i].hand != m.links[m.joints[i].link].hand) {
      fail(source, "joint '" + m.joints[i].name + "' is " +
                       (m.joints[i].hand ? "a hand joint but not below hand.base_link"
                                         : "an arm joint but below hand.base_link"));
    }
  }

  // Fingers.
  const YAML::Node fingers = y.sequence(y.required(hand, "fingers", "hand"), "hand.fingers");
  bool has_thumb = false;
  for (size_t i = 0; i < fingers.size(); ++i) {
    const std::string path = "hand.fingers[" + std::to_string(i) + "]";
    const YAML::Node n = fingers[i];
    y.allowed_keys(n, path, {"name", "thumb", "joints", "links"});
    Finger f;
    f.name = y.string(y.required(n, "name", path), path + ".name");
    if (n["thumb"]) f.thumb = y.boolean(n["thumb"], path + ".thumb");
    has_thumb = has_thumb || f.thumb;
    const YAML::Node fj = y.sequence(y.required(n, "joints", path), path + ".joints");
    for (size_t k = 0; k < fj.size(); ++k) {
      const std::string jp = path + ".joints[" + std::to_string(k) + "]";
      const std::string jn = y.string(fj[k], jp);
      const int qi = m.find_joint(jn);
      if (qi < 0 || !m.joints[qi].hand) y.error(fj[k], jp, "'" + jn + "' is not a hand joint");
      f.joints.push_back(qi);
    }
    const YAML::Node fl = y.sequence(y.required(n, "links", path), path + ".links");
    for (size_t k = 0; k < fl.size(); ++k)
      f.links.push_back(link_of(fl[k], path + ".links[" + std::to_string(k) + "]"));
    m.fingers.push_back(f);
  }
  if (!has_thumb) y.error(fingers, "hand.fingers", "no finger is marked 'thumb: true'");

  auto link_point = [&](const YAML::Node& n, const std::string& path) {
    y.allowed_keys(n, path, {"link", "xyz"});
    LinkPoint p;
    p.link = link_of(y.required(n, "link", path), path + ".link");
    if (n["xyz"]) p.point = y.vec3(n["xyz"], path + ".xyz");
    return p;
  };
  auto link_vector = [&](const YAML::Node& n, const std::string& path) {
    y.allowed_keys(n, path, {"link", "vector"});
    LinkVector v;
    v.link = link_of(y.required(n, "link", path), path + ".link");
    v.vector = y.vec3(y.required(n, "vector", path), path + ".vector");
    if (v.vector.norm() < 1e-9) y.error(n, path, "the vector must not be zero");
    v.vector.normalize();
    return v;
  };

  // Curves.
  const YAML::Node curves = y.sequence(y.required(hand, "curves", "hand"), "hand.curves");
  if (curves.size() == 0) y.error(curves, "hand.curves", "the list is empty");
  for (size_t i = 0; i < curves.size(); ++i) {
    const std::string path = "hand.curves[" + std::to_string(i) + "]";
    const YAML::Node n = curves[i];
    y.allowed_keys(n, path, {"name", "points"});
    FingerCurve c;
    c.name = n["name"] ? y.string(n["name"], path + ".name") : "curve_" + std::to_string(i);
    const YAML::Node pts = y.sequence(y.required(n, "points", path), path + ".points");
    if (pts.size() < 2) y.error(pts, path + ".points", "a finger curve needs at least 2 points");
    for (size_t k = 0; k < pts.size(); ++k)
      c.points.push_back(link_point(pts[k], path + ".points[" + std::to_string(k) + "]"));
    m.curves.push_back(c);
  }

  m.tcp = link_point(y.required(hand, "tcp", "hand"), "hand.tcp");
  m.v_fwd = link_vector(y.required(hand, "v_fwd", "hand"), "hand.v_fwd");
  m.v_swd = link_vector(y.required(hand, "v_swd", "hand"), "hand.v_swd");
  if (m.v_fwd.link == m.v_swd.link && std::abs(m.v_fwd.vector.dot(m.v_swd.vector)) > 1e-6)
    y.error(hand["v_swd"], "hand.v_swd", "v_fwd and v_swd must be orthogonal");
  if (hand["vlink_goal"]) {
    m.vlink_goal = y.number(hand["vlink_goal"], "hand.vlink_goal");
    if (m.vlink_goal <= 0.0 || m.vlink_goal >= 1.0)
      y.error(hand["vlink_goal"], "hand.vlink_goal", "must be in (0, 1)");
  }

  // Allowed collision pairs.
  if (root["collision"]) {
    const YAML::Node col = root["collision"];
    y.allowed_keys(col, "collision", {"allowed_pairs"});
    if (col["allowed_pairs"]) {
      const YAML::Node pairs = y.sequence(col["allowed_pairs"], "collision.allowed_pairs");
      for (size_t i = 0; i < pairs.size(); ++i) {
        const std::string path = "collision.allowed_pairs[" + std::to_string(i) + "]";
        if (!pairs[i].IsSequence() || pairs[i].size() != 2)
          y.error(pairs[i], path, "expected a pair [link_a, link_b]");
        int a = link_of(pairs[i][0], path + "[0]"), b = link_of(pairs[i][1], path + "[1]");
        if (a == b) y.error(pairs[i], path, "a link paired with itself");
        m.allowed_pairs.emplace_back(std::min(a, b), std::max(a, b));
      }
      std::sort(m.allowed_pairs.begin(), m.allowed_pairs.end());
      m.allowed_pairs.erase(std::unique(m.allowed_pairs.begin(), m.allowed_pairs.end()),
                            m.allowed_pairs.end());
    }
  }
  return m;
}

std::string where(const YAML::Exception& e) {
  return e.mark.is_null() ? "" : "line " + std::to_string(e.mark.line + 1) + ": ";
}

YAML::Node parse_yaml(const std::string& text, const std::string& file) {
  if (text.find('\0') != std::string::npos) fail(file, "not a YAML text file (contains NUL bytes)");
  YAML::Node root;
  try {
    root = YAML::Load(text);
  } catch (const YAML::Exception& e) {
    fail(file, "malformed YAML: " + where(e) + one_line(e.msg));
  }
  if (!root.IsMap()) fail(file, "expected a YAML mapping with keys name, urdf, arm, hand");
  return root;
}

RobotModel build(
    const std::string& yaml_text, const std::string& yaml_file,
    const std::function<std::pair<std::string, std::string>(const std::string&)>& read_urdf,
    const std::string& source) {
  const YAML::Node root = parse_yaml(yaml_text, yaml_file);
  const Yaml y{yaml_file};
  try {
    const YAML::Node u = y.required(root, "urdf", "(top level)");
    const std::pair<std::string, std::string> urdf = read_urdf(y.string(u, "urdf"));
    const auto model = parse_urdf(urdf.second, urdf.first);
    return build_model(root, y, *model, urdf.first, source);
  } catch (const YAML::Exception& e) {
    fail(yaml_file, where(e) + one_line(e.msg));
  }
}

std::string read_text_file(const std::filesystem::path& path, const std::string& what) {
  std::error_code ec;
  if (!std::filesystem::is_regular_file(path, ec))
    throw std::invalid_argument(path.string() + ": " + what + " not found or not a regular file");
  const auto size = std::filesystem::file_size(path, ec);
  if (ec) throw std::invalid_argument(path.string() + ": cannot read the " + what);
  if (size > 64u * 1024u * 1024u)
    throw std::invalid_argument(path.string() + ": the " + what + " is larger than 64 MB");
  std::ifstream in(path, std::ios::binary);
  if (!in) throw std::invalid_argument(path.string() + ": cannot open the " + what);
  std::stringstream ss;
  ss << in.rdbuf();
  return ss.str();
}

}  // namespace

std::vector<std::string> builtin_robots() {
  return {"kr5_sdh", "kr5_dlr", "kr5_icub", "kr5_armar3"};
}

RobotModel load_robot(const std::string& name_or_path) {
  const auto names = builtin_robots();
  if (std::find(names.begin(), names.end(), name_or_path) != names.end()) {
    const std::string yaml_name = name_or_path + ".yaml";
    const char* yaml = embedded_model_file(yaml_name);
    if (!yaml) throw std::logic_error("built-in robot file " + yaml_name + " is not embedded");
    return build(
        yaml, yaml_name,
        [](const std::string& urdf_name) {
          const char* text = embedded_model_file(urdf_name);
          if (!text)
            throw std::invalid_argument(urdf_name + ": not one of the built-in model files");
          return std::make_pair(urdf_name, std::string(text));
        },
        name_or_path);
  }
  const std::filesystem::path path(name_or_path);
  std::error_code ec;
  if (!std::filesystem::exists(path, ec)) {
    std::string list;
    for (const auto& n : names) list += (list.empty() ? "" : ", ") + n;
    throw std::invalid_argument("robot '" + name_or_path + "' is neither a built-in robot (" +
                                list + ") nor an existing hand-description file");
  }
  const std::string yaml = read_text_file(path, "hand description");
  return build(
      yaml, path.string(),
      [&](const std::string& urdf_name) {
        const std::filesystem::path urdf_path = path.parent_path() / urdf_name;
        return std::make_pair(urdf_path.string(), read_text_file(urdf_path, "URDF file"));
      },
      path.string());
}

RobotModel load_robot_from_text(const std::string& yaml_text, const std::string& urdf_text,
                                const std::string& yaml_name, const std::string& urdf_name) {
  return build(
      yaml_text, yaml_name,
      [&](const std::string&) { return std::make_pair(urdf_name, urdf_text); }, yaml_name);
}

}  // namespace claspplan::robots
