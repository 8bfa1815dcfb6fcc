// The hand description (YAML) of a robot model, checked against its URDF (and the hand's own URDF,
// mounted on an arm link, when it comes apart): the arm and hand joints,
// the home pose, held and mimic joints, fingers, finger curves, tcp / v_fwd / v_swd, the virtual
// linking goal and the allowed collision pairs. build_model() runs the steps in this order.
#include <algorithm>
#include <cmath>
#include <functional>
#include <map>
#include <memory>
#include <sstream>
#include <stdexcept>
#include <vector>

#include "core/yaml_field.hpp"
#include "robots/convex_hull.hpp"
#include "robots/robot_model_detail.hpp"

namespace claspplan::robots::robot_model_detail {

namespace {

// What the YAML says, before it is checked against the URDF.
struct HandJointSpec {
  std::string name;
  double open = 0.0;
  int closing = 0;
  YamlField node;
};

// The model under construction and what the steps hand on to each other.
struct ModelBuild {
  const std::string& urdf_file;
  const std::string& source;
  RobotModel m;
  UrdfJoints urdf;
  std::vector<int> q_links;  // child link of each q entry
  std::vector<YamlField> q_nodes;
  std::vector<HandJointSpec> hand_specs;
  std::map<int, int> q_of_link;
  std::map<int, double> held;

  // A link named in the YAML.
  int link_of(const YamlField& n) const {
    const std::string name = n.text();
    const int i = m.find_link(name);
    if (i < 0) n.fail("unknown link '" + name + "' (not in " + urdf_file + ")");
    return i;
  }

  // The child link of a movable joint named in the YAML.
  int movable_joint(const YamlField& n) const {
    const std::string name = n.text();
    auto it = urdf.link_by_joint.find(name);
    if (it == urdf.link_by_joint.end())
      n.fail("unknown joint '" + name + "' (not in " + urdf_file + ")");
    if (m.links[it->second].type == JointType::kFixed)
      n.fail("joint '" + name + "' is fixed in the URDF");
    return it->second;
  }

  const urdf::Joint& urdf_joint(int link) const {
    return *urdf.joint_of_link.at(m.links[link].name);
  }
};

// arm: its joints (the first entries of q) and the tool link.
void read_arm(ModelBuild& b, const YamlField& arm) {
  arm.only({"joints", "home", "tool_link"});
  for (const YamlField& j : arm.required("joints").items("joint names")) {
    b.q_links.push_back(b.movable_joint(j));
    b.q_nodes.push_back(j);
  }
  b.m.arm_dof = static_cast<int>(b.q_links.size());
  b.m.tool_link = b.link_of(arm.required("tool_link"));
}

// hand: the base link and the hand joints (the last entries of q) with their open values and
// closing directions.
void read_hand_joints(ModelBuild& b, const YamlField& hand) {
  hand.only(
      {"base_link", "joints", "held", "fingers", "curves", "tcp", "v_fwd", "v_swd", "vlink_goal"});
  b.m.hand_base_link = b.link_of(hand.required("base_link"));
  const YamlField hand_joints = hand.required("joints");
  const std::vector<YamlField> entries = hand_joints.items("hand joints");
  if (entries.empty()) hand_joints.fail("the list is empty");
  for (const YamlField& n : entries) {
    n.only({"name", "open", "closing"});
    HandJointSpec s{n.required("name").text(), 0.0, 0, n};
    b.q_links.push_back(b.movable_joint(n["name"]));
    b.q_nodes.push_back(n["name"]);
    if (n.has("open")) s.open = n["open"].number();
    if (n.has("closing")) {
      const double c = n["closing"].number();
      if (c != 1.0 && c != -1.0 && c != 0.0) n["closing"].fail("closing must be 1, -1 or 0");
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
      b.q_nodes[i].fail("joint '" + m.links[li].joint + "' is listed twice");
    b.q_of_link[li] = static_cast<int>(i);
    const urdf::Joint& uj = b.urdf_joint(li);
    Joint j;
    j.name = uj.name;
    j.link = li;
    j.hand = static_cast<int>(i) >= m.arm_dof;
    // A mimic joint in q is an adaptive finger joint (resolve_adaptive_joints): only in the hand.
    if (uj.mimic && !j.hand)
      b.q_nodes[i].fail("joint '" + uj.name + "' is a mimic joint and cannot be an arm joint");
    if (uj.mimic && b.hand_specs[i - m.arm_dof].node.has("open"))
      b.hand_specs[i - m.arm_dof].node["open"].fail(
          "'" + uj.name + "' is a mimic joint (an adaptive joint): it opens with its leader");
    if (uj.type == urdf::Joint::CONTINUOUS) {
      j.lower = -0.5 * kContinuousRange;
      j.upper = 0.5 * kContinuousRange;
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
    if (b.urdf_joint(j.link).mimic) continue;  // opens with its leader
    if (j.open < j.lower - 1e-9 || j.open > j.upper + 1e-9) {
      std::ostringstream s;
      s << "open value " << j.open << " of '" << j.name << "' is outside its limits [" << j.lower
        << ", " << j.upper << "]";
      b.hand_specs[i].node.fail(s.str());
    }
  }
}

// Home: the arm's home pose (default 0, clamped into the limits) and the open hand.
void read_home(ModelBuild& b, const YamlField& arm) {
  RobotModel& m = b.m;
  m.home = Eigen::VectorXd::Zero(m.dof());
  if (arm.has("home")) {
    const std::vector<YamlField> h = arm["home"].items("joint values");
    if (static_cast<int>(h.size()) != m.arm_dof)
      arm["home"].fail("expected " + std::to_string(m.arm_dof) + " values");
    for (int i = 0; i < m.arm_dof; ++i) {
      const Joint& j = m.joints[i];
      m.home[i] = h[i].number();
      if (m.home[i] < j.lower - 1e-9 || m.home[i] > j.upper + 1e-9) {
        std::ostringstream s;
        s << "value " << m.home[i] << " for '" << j.name << "' is outside its limits [" << j.lower
          << ", " << j.upper << "]";
        h[i].fail(s.str());
      }
    }
  } else {
    m.home = m.clamp(m.home);
  }
  for (int i = 0; i < m.arm_dof; ++i) m.joints[i].open = m.home[i];
  for (int i = m.arm_dof; i < m.dof(); ++i) m.home[i] = m.joints[i].open;
}

// Held joints: constant values.
void read_held(ModelBuild& b, const YamlField& hand) {
  if (!hand.has("held")) return;
  const YamlField h = hand["held"];
  if (!h.is_map()) h.fail("expected a mapping joint: value");
  for (const auto& [key, value] : h.entries()) {
    const int li = b.movable_joint(key);
    if (b.q_of_link.count(li)) key.fail("a held joint cannot also be in q");
    const urdf::Joint& uj = b.urdf_joint(li);
    if (uj.mimic) key.fail("joint '" + uj.name + "' is a mimic joint");
    const double v = value.number();
    if (uj.limits && uj.type != urdf::Joint::CONTINUOUS &&
        (v < uj.limits->lower - 1e-9 || v > uj.limits->upper + 1e-9)) {
      std::ostringstream s;
      s << "value " << v << " is outside the joint's limits [" << uj.limits->lower << ", "
        << uj.limits->upper << "]";
      value.fail(s.str());
    }
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

// Adaptive joints (mimic joints listed in hand.joints): each follows the root of its mimic chain
// that is not adaptive itself, and opens with it.
void resolve_adaptive_joints(ModelBuild& b) {
  RobotModel& m = b.m;
  std::map<int, int> state;  // q index: 1 in progress, 2 done
  const std::function<void(int)> resolve = [&](int i) {
    Joint& j = m.joints[i];
    const urdf::Joint& uj = b.urdf_joint(j.link);
    if (!uj.mimic || state[i] == 2) return;
    const YamlField& node = b.q_nodes[i];
    if (state[i] == 1) node.fail("adaptive joints mimic each other in a cycle at '" + j.name + "'");
    state[i] = 1;
    const Link& leader = m.links[b.urdf.link_by_joint.at(uj.mimic->joint_name)];
    if (leader.q_index < 0 || !m.joints[leader.q_index].hand)
      node.fail("'" + j.name + "' (an adaptive joint) must follow a hand joint in q, not '" +
                uj.mimic->joint_name + "'");
    // value = M (multiplier q[lead] + offset) + O, with q[lead] itself adaptive in turn.
    int lead = leader.q_index;
    double a = uj.mimic->multiplier * leader.multiplier;
    double c = uj.mimic->multiplier * leader.offset + uj.mimic->offset;
    resolve(lead);
    if (m.joints[lead].follows >= 0) {
      c += a * m.joints[lead].follow_offset;
      a *= m.joints[lead].follow_multiplier;
      lead = m.joints[lead].follows;
    }
    j.follows = lead;
    j.follow_multiplier = a;
    j.follow_offset = c;
    j.open = a * m.joints[lead].open + c;
    if (j.open < j.lower - 1e-9 || j.open > j.upper + 1e-9) {
      std::ostringstream s;
      s << "'" << j.name << "' (an adaptive joint) opens with '" << m.joints[lead].name << "' at "
        << j.open << ", outside its limits [" << j.lower << ", " << j.upper << "]";
      node.fail(s.str());
    }
    m.home[i] = j.open;
    state[i] = 2;
  };
  for (int i = m.arm_dof; i < m.dof(); ++i) resolve(i);
}

// Jacobian support, Jacobian columns and the hand flag.
void mark_support_and_hand(ModelBuild& b) {
  RobotModel& m = b.m;
  for (size_t i = 0; i < m.links.size(); ++i) {
    Link& l = m.links[i];
    if (l.q_index >= 0) {
      const Joint& j = m.joints[l.q_index];
      l.column = j.follows >= 0 ? j.follows : l.q_index;
      l.column_multiplier = l.multiplier * (j.follows >= 0 ? j.follow_multiplier : 1.0);
    }
    if (l.parent >= 0) {
      l.support = m.links[l.parent].support;
      l.hand = m.links[l.parent].hand;
    }
    if (static_cast<int>(i) == m.hand_base_link) l.hand = true;
    if (l.type != JointType::kFixed && l.q_index >= 0) l.support.push_back(static_cast<int>(i));
  }
  // The joint into the hand's base link moves the whole hand: an arm joint (fingers that hang
  // directly off the arm's last link name that link as the hand's base).
  for (int i = 0; i < m.dof(); ++i) {
    const int link = m.joints[i].link;
    if (m.joints[i].hand != (m.links[link].hand && link != m.hand_base_link)) {
      fail(b.source,
           "joint '" + m.joints[i].name + "' is " +
               (m.joints[i].hand ? "a hand joint but not below hand.base_link (its child link '" +
                                       m.links[link].name + "')"
                                 : "an arm joint but below hand.base_link"));
    }
  }
}

// Fingers.
void read_fingers(ModelBuild& b, const YamlField& hand) {
  RobotModel& m = b.m;
  const YamlField fingers = hand.required("fingers");
  bool has_thumb = false;
  for (const YamlField& n : fingers.items("fingers")) {
    n.only({"name", "thumb", "joints", "links"});
    Finger f;
    f.name = n.required("name").text();
    if (n.has("thumb")) f.thumb = n["thumb"].boolean();
    has_thumb = has_thumb || f.thumb;
    const YamlField fj = n.required("joints");
    for (const YamlField& j : fj.items("joint names")) {
      const std::string jn = j.text();
      const int qi = m.find_joint(jn);
      if (qi < 0 || !m.joints[qi].hand) j.fail("'" + jn + "' is not a hand joint");
      f.joints.push_back(qi);
    }
    if (f.joints.empty()) fj.fail("a finger needs at least one joint");
    const YamlField fl = n.required("links");
    bool has_geometry = false;
    for (const YamlField& l : fl.items("link names")) {
      f.links.push_back(b.link_of(l));
      has_geometry = has_geometry || !m.links[f.links.back()].shapes.empty();
    }
    // Closing a finger stops at contact: without collision geometry it would check nothing.
    if (!has_geometry) fl.fail("no link of the finger has collision geometry");
    m.fingers.push_back(f);
  }
  if (!has_thumb) fingers.fail("no finger is marked 'thumb: true'");
}

LinkPoint read_link_point(const ModelBuild& b, const YamlField& n) {
  n.only({"link", "xyz"});
  LinkPoint p;
  p.link = b.link_of(n.required("link"));
  if (n.has("xyz")) p.point = n["xyz"].vector3();
  return p;
}

LinkVector read_link_vector(const ModelBuild& b, const YamlField& n) {
  n.only({"link", "vector"});
  LinkVector v;
  v.link = b.link_of(n.required("link"));
  v.vector = n.required("vector").vector3();
  if (v.vector.norm() < 1e-9) n.fail("the vector must not be zero");
  v.vector.normalize();
  return v;
}

// Finger curves.
void read_curves(ModelBuild& b, const YamlField& hand) {
  const YamlField curves = hand.required("curves");
  const std::vector<YamlField> entries = curves.items("finger curves");
  if (entries.empty()) curves.fail("the list is empty");
  for (size_t i = 0; i < entries.size(); ++i) {
    const YamlField& n = entries[i];
    n.only({"name", "points"});
    FingerCurve c;
    c.name = n.has("name") ? n["name"].text() : "curve_" + std::to_string(i);
    const YamlField pts = n.required("points");
    const std::vector<YamlField> points = pts.items("link points");
    // Closed by its cord, a 2-point curve has no area: its virtual linking is always 0.
    if (points.size() < 3) pts.fail("a finger curve needs at least 3 points");
    for (const YamlField& p : points) c.points.push_back(read_link_point(b, p));
    b.m.curves.push_back(c);
  }
}

// The tool centre point, v_fwd, v_swd and the virtual-linking goal.
void read_hand_frame(ModelBuild& b, const YamlField& hand) {
  RobotModel& m = b.m;
  m.tcp = read_link_point(b, hand.required("tcp"));
  m.v_fwd = read_link_vector(b, hand.required("v_fwd"));
  m.v_swd = read_link_vector(b, hand.required("v_swd"));
  if (m.v_fwd.link == m.v_swd.link && std::abs(m.v_fwd.vector.dot(m.v_swd.vector)) > 1e-6)
    hand["v_swd"].fail("v_fwd and v_swd must be orthogonal");
  if (hand.has("vlink_goal")) {
    m.vlink_goal = hand["vlink_goal"].number();
    if (m.vlink_goal <= 0.0 || m.vlink_goal >= 1.0) hand["vlink_goal"].fail("must be in (0, 1)");
  }
}

// collision.mesh_hulls: every mesh shape replaced by its convex hull (a shared mesh once).
void use_mesh_hulls(RobotModel& m) {
  std::map<const TriangleMesh*, std::shared_ptr<const TriangleMesh>> hulls;
  for (CollisionShape& s : m.shapes) {
    if (s.type != CollisionShape::Type::kMesh) continue;
    auto& hull = hulls[s.mesh.get()];
    if (!hull) hull = std::make_shared<const TriangleMesh>(convex_hull(s.mesh->vertices, s.source));
    s.mesh = hull;
  }
}

// Allowed collision pairs, and mesh hulls.
void read_allowed_pairs(ModelBuild& b, const YamlField& root) {
  RobotModel& m = b.m;
  if (!root.has("collision")) return;
  const YamlField col = root["collision"];
  col.only({"allowed_pairs", "mesh_hulls"});
  if (col.has("mesh_hulls") && col["mesh_hulls"].boolean()) use_mesh_hulls(m);
  if (!col.has("allowed_pairs")) return;
  for (const YamlField& pair : col["allowed_pairs"].items("link pairs")) {
    if (!pair.is_list() || pair.node().size() != 2) pair.fail("expected a pair [link_a, link_b]");
    const std::vector<YamlField> links = pair.items();
    const int a = b.link_of(links[0]), c = b.link_of(links[1]);
    if (a == c) pair.fail("a link paired with itself");
    m.allowed_pairs.emplace_back(std::min(a, c), std::max(a, c));
  }
  std::sort(m.allowed_pairs.begin(), m.allowed_pairs.end());
  m.allowed_pairs.erase(std::unique(m.allowed_pairs.begin(), m.allowed_pairs.end()),
                        m.allowed_pairs.end());
}

// hand_urdf: the hand's own URDF (or, from `root` down, a whole robot's), mounted on an arm link
// at xyz / rpy (URDF conventions); the arm's own gripper, `replaces` (a link and its subtree), is
// left out of the arm's URDF.
void mount_hand(ModelBuild& b, const YamlField& n, const urdf::ModelInterface& hand,
                const std::string& hand_file) {
  const int parent = b.link_of(n.required("parent"));
  const Eigen::Vector3d xyz = n.has("xyz") ? n["xyz"].vector3() : Eigen::Vector3d::Zero();
  const Eigen::Vector3d rpy = n.has("rpy") ? n["rpy"].vector3() : Eigen::Vector3d::Zero();
  Eigen::Isometry3d origin = Eigen::Isometry3d::Identity();
  origin.translation() = xyz;
  origin.linear() = rpy_rotation(rpy);
  attach_urdf_tree(hand, hand_file, parent, origin, b.m, b.urdf,
                   n.has("root") ? n["root"].text() : std::string());
}

RobotModel build_model(const YamlField& root, const urdf::ModelInterface& urdf,
                       const std::string& urdf_file, const std::string& source,
                       const urdf::ModelInterface* hand_urdf, const std::string& hand_file) {
  ModelBuild b{urdf_file, source, {}, {}, {}, {}, {}, {}, {}};
  b.m.source = source;
  root.only({"name", "urdf", "hand_urdf", "arm", "hand", "collision"});
  b.m.name = root.required("name").text();
  std::vector<std::string> replaced;  // one link or a list
  if (hand_urdf && root["hand_urdf"].has("replaces")) {
    const YamlField r = root["hand_urdf"]["replaces"];
    if (r.node().IsSequence())
      for (const YamlField& link : r.items("replaces")) replaced.push_back(link.text());
    else
      replaced.push_back(r.text());
  }
  b.urdf = read_urdf_tree(urdf, urdf_file, b.m, replaced);
  if (hand_urdf) mount_hand(b, root["hand_urdf"], *hand_urdf, hand_file);

  const YamlField arm = root.required("arm");
  read_arm(b, arm);
  const YamlField hand = root.required("hand");
  read_hand_joints(b, hand);
  add_actuated_joints(b);
  read_home(b, arm);
  read_held(b, hand);
  resolve_joints(b);
  resolve_adaptive_joints(b);
  mark_support_and_hand(b);
  read_fingers(b, hand);
  read_curves(b, hand);
  read_hand_frame(b, hand);
  read_allowed_pairs(b, root);
  return b.m;
}

}  // namespace

RobotModel build_robot(const std::string& yaml_text, const std::string& yaml_file,
                       const UrdfReader& read_urdf, const std::string& source) {
  const YamlField root =
      YamlField::parse_map(yaml_text, yaml_file, "with keys name, urdf, arm, hand");
  try {
    const std::pair<std::string, std::string> urdf = read_urdf(root.required("urdf").text());
    const auto model = parse_urdf(urdf.second, urdf.first);
    urdf::ModelInterfaceSharedPtr hand;  // alive while the model is built: joints point into it
    std::string hand_file;
    if (root.has("hand_urdf")) {
      const YamlField n = root["hand_urdf"];
      n.only({"file", "root", "parent", "xyz", "rpy", "replaces"});
      const auto text = read_urdf(n.required("file").text());
      hand_file = text.first;
      hand = parse_urdf(text.second, text.first);
    }
    return build_model(root, *model, urdf.first, source, hand.get(), hand_file);
  } catch (const YAML::Exception& e) {
    fail(yaml_file, YamlField::line_of(e.mark) + one_line(e.msg));
  }
}

}  // namespace claspplan::robots::robot_model_detail
