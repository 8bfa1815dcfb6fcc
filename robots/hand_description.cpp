// The hand description (YAML) of a robot model, checked against its URDF: the arm and hand joints,
// the home pose, held and mimic joints, fingers, finger curves, tcp / v_fwd / v_swd, the virtual
// linking goal and the allowed collision pairs. build_model() runs the steps in this order.
#include <algorithm>
#include <cmath>
#include <map>
#include <set>
#include <sstream>
#include <stdexcept>
#include <vector>

#include <yaml-cpp/yaml.h>

#include "robots/robot_model_detail.hpp"

namespace claspplan::robots::robot_model_detail {

namespace {

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

// The model under construction and what the steps hand on to each other.
struct ModelBuild {
  const Yaml& y;
  const std::string& urdf_file;
  const std::string& source;
  RobotModel m;
  UrdfJoints urdf;
  std::vector<int> q_links;  // child link of each q entry
  std::vector<YAML::Node> q_nodes;
  std::vector<HandJointSpec> hand_specs;
  std::map<int, int> q_of_link;
  std::map<int, double> held;

  // A link named in the YAML.
  int link_of(const YAML::Node& n, const std::string& path) const {
    const std::string name = y.string(n, path);
    const int i = m.find_link(name);
    if (i < 0) y.error(n, path, "unknown link '" + name + "' (not in " + urdf_file + ")");
    return i;
  }

  // The child link of a movable joint named in the YAML.
  int movable_joint(const YAML::Node& n, const std::string& path) const {
    const std::string name = y.string(n, path);
    auto it = urdf.link_by_joint.find(name);
    if (it == urdf.link_by_joint.end())
      y.error(n, path, "unknown joint '" + name + "' (not in " + urdf_file + ")");
    if (m.links[it->second].type == JointType::kFixed)
      y.error(n, path, "joint '" + name + "' is fixed in the URDF");
    return it->second;
  }

  const urdf::Joint& urdf_joint(int link) const {
    return *urdf.joint_of_link.at(m.links[link].name);
  }
};

// arm: its joints (the first entries of q) and the tool link.
void read_arm(ModelBuild& b, const YAML::Node& arm) {
  const Yaml& y = b.y;
  y.allowed_keys(arm, "arm", {"joints", "home", "tool_link"});
  const YAML::Node arm_joints = y.sequence(y.required(arm, "joints", "arm"), "arm.joints");
  for (size_t i = 0; i < arm_joints.size(); ++i) {
    b.q_links.push_back(b.movable_joint(arm_joints[i], "arm.joints[" + std::to_string(i) + "]"));
    b.q_nodes.push_back(arm_joints[i]);
  }
  b.m.arm_dof = static_cast<int>(b.q_links.size());
  b.m.tool_link = b.link_of(y.required(arm, "tool_link", "arm"), "arm.tool_link");
}

// hand: the base link and the hand joints (the last entries of q) with their open values and
// closing directions.
void read_hand_joints(ModelBuild& b, const YAML::Node& hand) {
  const Yaml& y = b.y;
  y.allowed_keys(
      hand, "hand",
      {"base_link", "joints", "held", "fingers", "curves", "tcp", "v_fwd", "v_swd", "vlink_goal"});
  b.m.hand_base_link = b.link_of(y.required(hand, "base_link", "hand"), "hand.base_link");
  const YAML::Node hand_joints = y.sequence(y.required(hand, "joints", "hand"), "hand.joints");
  if (hand_joints.size() == 0) y.error(hand_joints, "hand.joints", "the list is empty");
  for (size_t i = 0; i < hand_joints.size(); ++i) {
    const std::string path = "hand.joints[" + std::to_string(i) + "]";
    const YAML::Node n = hand_joints[i];
    y.allowed_keys(n, path, {"name", "open", "closing"});
    HandJointSpec s;
    s.node = n;
    s.name = y.string(y.required(n, "name", path), path + ".name");
    b.q_links.push_back(b.movable_joint(n["name"], path + ".name"));
    b.q_nodes.push_back(n["name"]);
    if (n["open"]) s.open = y.number(n["open"], path + ".open");
    if (n["closing"]) {
      const double c = y.number(n["closing"], path + ".closing");
      if (c != 1.0 && c != -1.0 && c != 0.0)
        y.error(n["closing"], path, "closing must be 1, -1 or 0");
      s.closing = static_cast<int>(c);
    }
    b.hand_specs.push_back(s);
  }
  b.m.hand_dof = static_cast<int>(b.hand_specs.size());
}

// The actuated joints (q) with their URDF limits; no joint twice; open values within the limits.
void add_actuated_joints(ModelBuild& b) {
  RobotModel& m = b.m;
  for (size_t i = 0; i < b.q_links.size(); ++i) {
    const int li = b.q_links[i];
    if (b.q_of_link.count(li))
      b.y.error(b.q_nodes[i], "joints", "joint '" + m.links[li].joint + "' is listed twice");
    b.q_of_link[li] = static_cast<int>(i);
    const urdf::Joint& uj = b.urdf_joint(li);
    if (uj.mimic)
      b.y.error(b.q_nodes[i], "joints",
                "joint '" + uj.name + "' is a mimic joint and cannot be in q");
    Joint j;
    j.name = uj.name;
    j.link = li;
    j.hand = static_cast<int>(i) >= m.arm_dof;
    if (uj.type == urdf::Joint::CONTINUOUS) {
      j.lower = -M_PI;  // one turn: a planner needs finite limits
      j.upper = M_PI;
    } else {
      if (!uj.limits) fail(b.urdf_file, "joint '" + uj.name + "' has no <limit>");
      j.lower = uj.limits->lower;
      j.upper = uj.limits->upper;
      if (!std::isfinite(j.lower) || !std::isfinite(j.upper) || j.lower > j.upper) {
        fail(b.urdf_file, "joint '" + uj.name + "': limits must be finite with lower <= upper");
      }
    }
    if (uj.limits) j.velocity = uj.limits->velocity;
    m.joints.push_back(j);
    Link& l = m.links[li];
    l.q_index = static_cast<int>(i);
  }
  for (int i = 0; i < m.hand_dof; ++i) {
    Joint& j = m.joints[m.arm_dof + i];
    j.open = b.hand_specs[i].open;
    j.closing = b.hand_specs[i].closing;
    if (j.open < j.lower - 1e-9 || j.open > j.upper + 1e-9) {
      std::ostringstream s;
      s << "open value " << j.open << " of '" << j.name << "' is outside its limits [" << j.lower
        << ", " << j.upper << "]";
      b.y.error(b.hand_specs[i].node, "hand.joints[" + std::to_string(i) + "]", s.str());
    }
  }
}

// Home: the arm's home pose (default 0, clamped into the limits) and the open hand.
void read_home(ModelBuild& b, const YAML::Node& arm) {
  RobotModel& m = b.m;
  m.home = Eigen::VectorXd::Zero(m.dof());
  if (arm["home"]) {
    const YAML::Node h = b.y.sequence(arm["home"], "arm.home");
    if (static_cast<int>(h.size()) != m.arm_dof)
      b.y.error(h, "arm.home", "expected " + std::to_string(m.arm_dof) + " values");
    for (int i = 0; i < m.arm_dof; ++i) {
      const double v = b.y.number(h[i], "arm.home[" + std::to_string(i) + "]");
      const Joint& j = m.joints[i];
      if (v < j.lower - 1e-9 || v > j.upper + 1e-9)
        b.y.error(h[i], "arm.home", "value for '" + j.name + "' is outside its limits");
      m.home[i] = v;
    }
  } else {
    m.home = m.clamp(m.home);
  }
  for (int i = 0; i < m.arm_dof; ++i) m.joints[i].open = m.home[i];
  for (int i = m.arm_dof; i < m.dof(); ++i) m.home[i] = m.joints[i].open;
}

// Held joints: constant values.
void read_held(ModelBuild& b, const YAML::Node& hand) {
  const Yaml& y = b.y;
  if (!hand["held"] || hand["held"].IsNull()) return;
  const YAML::Node h = hand["held"];
  if (!h.IsMap()) y.error(h, "hand.held", "expected a mapping joint: value");
  for (const auto& kv : h) {
    const std::string path = "hand.held." + kv.first.Scalar();
    const int li = b.movable_joint(kv.first, path);
    if (b.q_of_link.count(li)) y.error(kv.first, path, "a held joint cannot also be in q");
    const urdf::Joint& uj = b.urdf_joint(li);
    if (uj.mimic) y.error(kv.first, path, "joint '" + uj.name + "' is a mimic joint");
    const double v = y.number(kv.second, path);
    if (uj.limits && uj.type != urdf::Joint::CONTINUOUS &&
        (v < uj.limits->lower - 1e-9 || v > uj.limits->upper + 1e-9))
      y.error(kv.second, path, "value is outside the joint's limits");
    b.held[li] = v;
  }
}

// How the joint of link li moves: in q, held, or a mimic (resolved to its root leader).
// state: 0 unvisited, 1 in progress, 2 done.
void resolve_joint(ModelBuild& b, int li, std::map<int, int>& state) {
  RobotModel& m = b.m;
  Link& l = m.links[li];
  if (l.type == JointType::kFixed || state[li] == 2) return;
  if (state[li] == 1) fail(b.urdf_file, "mimic joints form a cycle at '" + l.joint + "'");
  state[li] = 1;
  const urdf::Joint& uj = b.urdf_joint(li);
  if (b.q_of_link.count(li)) {
    l.q_index = b.q_of_link[li];
    l.multiplier = 1.0;
    l.offset = 0.0;
  } else if (b.held.count(li)) {
    l.q_index = -1;
    l.offset = b.held[li];
  } else if (uj.mimic) {
    auto it = b.urdf.link_by_joint.find(uj.mimic->joint_name);
    if (it == b.urdf.link_by_joint.end())
      fail(b.urdf_file,
           "joint '" + uj.name + "' mimics unknown joint '" + uj.mimic->joint_name + "'");
    if (!std::isfinite(uj.mimic->multiplier) || !std::isfinite(uj.mimic->offset))
      fail(b.urdf_file, "joint '" + uj.name + "': mimic multiplier and offset must be finite");
    const int leader = it->second;
    if (m.links[leader].type == JointType::kFixed)
      fail(b.urdf_file,
           "joint '" + uj.name + "' mimics the fixed joint '" + uj.mimic->joint_name + "'");
    resolve_joint(b, leader, state);
    const Link& ld = m.links[leader];
    l.q_index = ld.q_index;
    l.multiplier = uj.mimic->multiplier * ld.multiplier;
    l.offset = uj.mimic->multiplier * ld.offset + uj.mimic->offset;
    if (l.q_index < 0) l.multiplier = 1.0;
  } else {
    fail(b.source, "joint '" + uj.name +
                       "' moves but is not listed in arm.joints, hand.joints or hand.held, and is "
                       "not a mimic joint");
  }
  state[li] = 2;
}

// Every movable joint: in q, held, or a mimic.
void resolve_joints(ModelBuild& b) {
  std::map<int, int> state;
  for (size_t i = 1; i < b.m.links.size(); ++i) resolve_joint(b, static_cast<int>(i), state);
}

// Jacobian support and the hand flag.
void mark_support_and_hand(ModelBuild& b) {
  RobotModel& m = b.m;
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
      fail(b.source, "joint '" + m.joints[i].name + "' is " +
                         (m.joints[i].hand ? "a hand joint but not below hand.base_link"
                                           : "an arm joint but below hand.base_link"));
    }
  }
}

// Fingers.
void read_fingers(ModelBuild& b, const YAML::Node& hand) {
  const Yaml& y = b.y;
  RobotModel& m = b.m;
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
    if (f.joints.empty()) y.error(fj, path + ".joints", "a finger needs at least one joint");
    const YAML::Node fl = y.sequence(y.required(n, "links", path), path + ".links");
    bool has_geometry = false;
    for (size_t k = 0; k < fl.size(); ++k) {
      f.links.push_back(b.link_of(fl[k], path + ".links[" + std::to_string(k) + "]"));
      has_geometry = has_geometry || !m.links[f.links.back()].shapes.empty();
    }
    // Closing a finger stops at contact: without collision geometry it would check nothing.
    if (!has_geometry) y.error(fl, path + ".links", "no link of the finger has collision geometry");
    m.fingers.push_back(f);
  }
  if (!has_thumb) y.error(fingers, "hand.fingers", "no finger is marked 'thumb: true'");
}

LinkPoint read_link_point(const ModelBuild& b, const YAML::Node& n, const std::string& path) {
  b.y.allowed_keys(n, path, {"link", "xyz"});
  LinkPoint p;
  p.link = b.link_of(b.y.required(n, "link", path), path + ".link");
  if (n["xyz"]) p.point = b.y.vec3(n["xyz"], path + ".xyz");
  return p;
}

LinkVector read_link_vector(const ModelBuild& b, const YAML::Node& n, const std::string& path) {
  b.y.allowed_keys(n, path, {"link", "vector"});
  LinkVector v;
  v.link = b.link_of(b.y.required(n, "link", path), path + ".link");
  v.vector = b.y.vec3(b.y.required(n, "vector", path), path + ".vector");
  if (v.vector.norm() < 1e-9) b.y.error(n, path, "the vector must not be zero");
  v.vector.normalize();
  return v;
}

// Finger curves.
void read_curves(ModelBuild& b, const YAML::Node& hand) {
  const Yaml& y = b.y;
  const YAML::Node curves = y.sequence(y.required(hand, "curves", "hand"), "hand.curves");
  if (curves.size() == 0) y.error(curves, "hand.curves", "the list is empty");
  for (size_t i = 0; i < curves.size(); ++i) {
    const std::string path = "hand.curves[" + std::to_string(i) + "]";
    const YAML::Node n = curves[i];
    y.allowed_keys(n, path, {"name", "points"});
    FingerCurve c;
    c.name = n["name"] ? y.string(n["name"], path + ".name") : "curve_" + std::to_string(i);
    const YAML::Node pts = y.sequence(y.required(n, "points", path), path + ".points");
    // Closed by its cord, a 2-point curve has no area: its virtual linking is always 0.
    if (pts.size() < 3) y.error(pts, path + ".points", "a finger curve needs at least 3 points");
    for (size_t k = 0; k < pts.size(); ++k)
      c.points.push_back(read_link_point(b, pts[k], path + ".points[" + std::to_string(k) + "]"));
    b.m.curves.push_back(c);
  }
}

// The tool centre point, v_fwd, v_swd and the virtual-linking goal.
void read_hand_frame(ModelBuild& b, const YAML::Node& hand) {
  const Yaml& y = b.y;
  RobotModel& m = b.m;
  m.tcp = read_link_point(b, y.required(hand, "tcp", "hand"), "hand.tcp");
  m.v_fwd = read_link_vector(b, y.required(hand, "v_fwd", "hand"), "hand.v_fwd");
  m.v_swd = read_link_vector(b, y.required(hand, "v_swd", "hand"), "hand.v_swd");
  if (m.v_fwd.link == m.v_swd.link && std::abs(m.v_fwd.vector.dot(m.v_swd.vector)) > 1e-6)
    y.error(hand["v_swd"], "hand.v_swd", "v_fwd and v_swd must be orthogonal");
  if (hand["vlink_goal"]) {
    m.vlink_goal = y.number(hand["vlink_goal"], "hand.vlink_goal");
    if (m.vlink_goal <= 0.0 || m.vlink_goal >= 1.0)
      y.error(hand["vlink_goal"], "hand.vlink_goal", "must be in (0, 1)");
  }
}

// Allowed collision pairs.
void read_allowed_pairs(ModelBuild& b, const YAML::Node& root) {
  const Yaml& y = b.y;
  RobotModel& m = b.m;
  if (!root["collision"]) return;
  const YAML::Node col = root["collision"];
  y.allowed_keys(col, "collision", {"allowed_pairs"});
  if (!col["allowed_pairs"]) return;
  const YAML::Node pairs = y.sequence(col["allowed_pairs"], "collision.allowed_pairs");
  for (size_t i = 0; i < pairs.size(); ++i) {
    const std::string path = "collision.allowed_pairs[" + std::to_string(i) + "]";
    if (!pairs[i].IsSequence() || pairs[i].size() != 2)
      y.error(pairs[i], path, "expected a pair [link_a, link_b]");
    int a = b.link_of(pairs[i][0], path + "[0]"), c = b.link_of(pairs[i][1], path + "[1]");
    if (a == c) y.error(pairs[i], path, "a link paired with itself");
    m.allowed_pairs.emplace_back(std::min(a, c), std::max(a, c));
  }
  std::sort(m.allowed_pairs.begin(), m.allowed_pairs.end());
  m.allowed_pairs.erase(std::unique(m.allowed_pairs.begin(), m.allowed_pairs.end()),
                        m.allowed_pairs.end());
}

RobotModel build_model(const YAML::Node& root, const Yaml& y, const urdf::ModelInterface& urdf,
                       const std::string& urdf_file, const std::string& source) {
  ModelBuild b{y, urdf_file, source, {}, {}, {}, {}, {}, {}, {}};
  b.m.source = source;
  y.allowed_keys(root, "(top level)", {"name", "urdf", "arm", "hand", "collision"});
  b.m.name = y.string(y.required(root, "name", "(top level)"), "name");
  b.urdf = read_urdf_tree(urdf, urdf_file, b.m);

  const YAML::Node arm = y.required(root, "arm", "(top level)");
  read_arm(b, arm);
  const YAML::Node hand = y.required(root, "hand", "(top level)");
  read_hand_joints(b, hand);
  add_actuated_joints(b);
  read_home(b, arm);
  read_held(b, hand);
  resolve_joints(b);
  mark_support_and_hand(b);
  read_fingers(b, hand);
  read_curves(b, hand);
  read_hand_frame(b, hand);
  read_allowed_pairs(b, root);
  return b.m;
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
}  // namespace

RobotModel build_robot(const std::string& yaml_text, const std::string& yaml_file,
                       const UrdfReader& read_urdf, const std::string& source) {
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

}  // namespace claspplan::robots::robot_model_detail
