#include "robots/description_draft.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <map>
#include <random>

#include <Eigen/Geometry>

#include "core/input_error.hpp"
#include "core/random_draws.hpp"
#include "robots/collision_world.hpp"
#include "robots/description_draft_detail.hpp"
#include "robots/hand_size.hpp"
#include "robots/kinematics.hpp"
#include "robots/robot_model_detail.hpp"

namespace claspplan::robots {
namespace {

namespace fs = std::filesystem;
using namespace robot_model_detail;
using namespace draft_detail;

// The URDF tree before any description: links, shapes and the joints' URDF records.
struct Tree {
  urdf::ModelInterfaceSharedPtr arm, hand;  // alive: `joints` points into them
  RobotModel m;                             // links and shapes only
  UrdfJoints joints;
  std::vector<std::vector<int>> children;
  std::vector<int> below;  // per link: moving joints in its subtree, its own included

  const urdf::Joint* joint(int link) const {
    const auto it = joints.joint_of_link.find(m.links[link].name);
    return it == joints.joint_of_link.end() ? nullptr : it->second;
  }
  // A joint that moves: revolute, continuous or prismatic (a mimic of another too).
  bool moves(int link) const {
    const urdf::Joint* j = joint(link);
    return j && (j->type == urdf::Joint::REVOLUTE || j->type == urdf::Joint::CONTINUOUS ||
                 j->type == urdf::Joint::PRISMATIC);
  }
  // A joint the user drives: one that moves and is not a mimic of another.
  bool actuated(int link) const { return moves(link) && !joint(link)->mimic; }
  // The joint the user drives to move `link`: its own, or the leader its mimic chain ends at
  // ("" for a fixed joint; a chain that does not end in a driven joint is the loader's error).
  std::string driver(int link) const {
    const urdf::Joint* j = moves(link) ? joint(link) : nullptr;
    for (std::size_t hops = 0; j && j->mimic && hops <= m.links.size(); ++hops) {
      const auto it = joints.link_by_joint.find(j->mimic->joint_name);
      j = it == joints.link_by_joint.end() ? nullptr : joint(it->second);
    }
    return j && !j->mimic ? j->name : std::string();
  }
  int link(const std::string& name, const std::string& flag) const {
    const int i = m.find_link(name);
    if (i < 0) throw InputError(flag + ": no link '" + name + "' in the URDF");
    return i;
  }
};

Tree read_tree(const DraftOptions& o) {
  Tree t;
  t.arm = parse_urdf(read_text_file(o.urdf, "URDF file"), o.urdf.string());
  if (!o.replaces.empty() && o.hand_urdf.empty())
    throw InputError("--replaces leaves the arm's gripper out for --hand-urdf's hand: give both");
  if (!o.hand_urdf_root.empty() && o.hand_urdf.empty())
    throw InputError("--hand-urdf-root takes the hand from --hand-urdf's URDF: give both");
  t.joints = read_urdf_tree(*t.arm, o.urdf.string(), t.m, o.replaces);
  if (!o.hand_urdf.empty()) {
    if (o.mount.empty()) throw InputError("--hand-urdf needs --mount LINK (the arm link it is on)");
    t.hand = parse_urdf(read_text_file(o.hand_urdf, "hand URDF file"), o.hand_urdf.string());
    Eigen::Isometry3d origin = Eigen::Isometry3d::Identity();
    origin.translation() = o.mount_xyz;
    origin.linear() = rpy_rotation(o.mount_rpy);
    attach_urdf_tree(*t.hand, o.hand_urdf.string(), t.link(o.mount, "--mount"), origin, t.m,
                     t.joints, o.hand_urdf_root);
  }
  const int n = static_cast<int>(t.m.links.size());
  t.children.assign(n, {});
  t.below.assign(n, 0);
  for (int i = n - 1; i >= 0; --i) {  // parents come first: children are done before them
    t.below[i] += t.moves(i) ? 1 : 0;
    if (t.m.links[i].parent >= 0) {
      t.children[t.m.links[i].parent].insert(t.children[t.m.links[i].parent].begin(), i);
      t.below[t.m.links[i].parent] += t.below[i];
    }
  }
  return t;
}

// The children of `link` whose subtrees hold moving joints.
std::vector<int> moving_branches(const Tree& t, int link) {
  std::vector<int> out;
  for (int c : t.children[link])
    if (t.below[c] > 0) out.push_back(c);
  return out;
}

// Down from `link` along single moving branches: the first link with none or several.
int first_split(const Tree& t, int link) {
  for (std::vector<int> below = moving_branches(t, link); below.size() == 1;
       below = moving_branches(t, link))
    link = below[0];
  return link;
}

int find_hand_root(const Tree& t, const DraftOptions& o) {
  if (!o.hand_root.empty()) return t.link(o.hand_root, "--hand-root");
  // A mounted hand's fingers are below its own root, whatever else the arm carries.
  const std::string mounted =
      o.hand_urdf_root.empty() && t.hand ? t.hand->getRoot()->name : o.hand_urdf_root;
  const int root = first_split(t, t.hand ? t.m.link_index(mounted) : 0);
  if (moving_branches(t, root).empty())
    throw InputError(
        "no hand found: no link has two or more branches with moving joints (a hand's "
        "fingers); name the hand's root link with --hand-root");
  return root;
}

// The first links of the fingers below `link`, one per moving branch. A branch that splits again
// into moving branches (SVH's ring and little fingers on a plate that turns with the thumb) gives
// one finger per branch below the split; the links before it are part of the palm.
void finger_starts(const Tree& t, int link, std::vector<int>& out) {
  for (int branch : moving_branches(t, link)) {
    const int split = first_split(t, branch);
    if (moving_branches(t, split).empty())
      out.push_back(branch);
    else
      finger_starts(t, split, out);
  }
}

// A finger: from a branch of the hand's root down to a leaf, following the branch with the most
// moving joints (then the first), so that a fixed fingertip link ends it.
std::vector<int> finger_chain(const Tree& t, int first) {
  std::vector<int> chain{first};
  while (!t.children[chain.back()].empty()) {
    const auto& c = t.children[chain.back()];
    chain.push_back(*std::max_element(c.begin(), c.end(),
                                      [&](int a, int b) { return t.below[a] < t.below[b]; }));
  }
  return chain;
}

JointDraft joint_draft(const Tree& t, int link) {
  const urdf::Joint* j = t.joint(link);
  JointDraft d;
  d.name = j->name;
  if (j->type == urdf::Joint::CONTINUOUS || !j->limits) {
    d.lower = -0.5 * kContinuousRange;
    d.upper = 0.5 * kContinuousRange;
  } else {
    d.lower = j->limits->lower;
    d.upper = j->limits->upper;
  }
  d.open = std::clamp(0.0, d.lower, d.upper);
  return d;
}

RobotModel load_draft(const Draft& d, const DraftOptions& o) {
  const fs::path dir = fs::absolute(o.out).parent_path();
  return build_robot(
      to_yaml(d), o.out.string(),
      [&](const std::string& file) {
        const fs::path p = dir / file;
        return std::make_pair(p.string(), read_text_file(p, "URDF file"));
      },
      o.out.string());
}

std::string relative_to_out(const fs::path& file, const DraftOptions& o) {
  return fs::absolute(file)
      .lexically_normal()
      .lexically_relative(fs::absolute(o.out).parent_path().lexically_normal())
      .generic_string();
}

// The part of the draft the URDF's tree decides: arm chain, hand joints, fingers.
Draft topology(const Tree& t, const DraftOptions& o, int root) {
  Draft d;
  d.name = !o.name.empty() ? o.name : t.arm->getName() + (t.hand ? "_" + t.hand->getName() : "");
  d.urdf = relative_to_out(o.urdf, o);
  if (t.hand) {
    d.hand_urdf = relative_to_out(o.hand_urdf, o);
    d.mount = o.mount;
    d.mount_xyz = o.mount_xyz;
    d.mount_rpy = o.mount_rpy;
    d.hand_urdf_root = o.hand_urdf_root;
    d.replaces = o.replaces;
  }
  d.mesh_hulls = o.mesh_hulls;
  std::vector<int> path;
  for (int l = root; l >= 0; l = t.m.links[l].parent) path.insert(path.begin(), l);
  for (int l : path)
    if (t.actuated(l)) d.arm.push_back(joint_draft(t, l));
  d.base_link = t.m.links[root].name;
  d.tcp = {d.base_link};
  if (d.arm.empty()) throw InputError("no arm joints above the hand's root '" + d.base_link + "'");
  if (!o.home.empty() && o.home.size() != d.arm.size())
    throw InputError("--home: " + std::to_string(o.home.size()) + " values for the arm's " +
                     std::to_string(d.arm.size()) + " joints");
  for (std::size_t i = 0; i < o.home.size(); ++i) d.arm[i].open = o.home[i];
  d.home_given = !o.home.empty();
  const int parent = t.m.links[root].parent;
  d.tool_link = t.hand                           ? o.mount
                : t.actuated(root) || parent < 0 ? d.base_link
                                                 : t.m.links[parent].name;
  // Every actuated joint below the root is a hand joint, in the tree's order.
  std::vector<int> stack(t.children[root].rbegin(), t.children[root].rend());
  while (!stack.empty()) {
    const int l = stack.back();
    stack.pop_back();
    if (t.actuated(l)) d.hand.push_back(joint_draft(t, l));
    stack.insert(stack.end(), t.children[l].rbegin(), t.children[l].rend());
  }
  std::vector<int> starts;
  finger_starts(t, root, starts);
  for (int branch : starts) {
    FingerDraft f;
    f.chain = finger_chain(t, branch);
    for (int l : f.chain) {  // a coupled finger's joints are the ones its mimics follow
      f.links.push_back(t.m.links[l].name);
      const std::string j = t.driver(l);
      if (!j.empty() && std::find(f.joints.begin(), f.joints.end(), j) == f.joints.end())
        f.joints.push_back(j);
    }
    f.name = "finger_" + std::to_string(d.fingers.size() + 1);
    d.fingers.push_back(f);
  }
  return d;
}

// --adaptive: each mimic joint of a finger becomes a hand joint of its own (an adaptive joint)
// that closes as its driver closes it, and a finger's joints are then its own joints.
void make_adaptive(Draft& d, const Tree& t, const RobotModel& m,
                   std::vector<std::string>& guesses) {
  int added = 0;
  for (FingerDraft& f : d.fingers) {
    f.joints.clear();
    for (int l : f.chain) {
      if (!t.moves(l)) continue;
      const urdf::Joint* j = t.joint(l);
      const std::string driver = t.driver(l);
      if (driver.empty()) continue;
      if (j->mimic) {
        const auto lead = std::find_if(d.hand.begin(), d.hand.end(),
                                       [&](const JointDraft& h) { return h.name == driver; });
        if (lead == d.hand.end()) continue;  // a mimic of an arm joint stays one
        JointDraft a = joint_draft(t, l);
        // Its value is multiplier × the driver's (the loaded model's chain product).
        const double rate = m.links[m.link_index(t.m.links[l].name)].multiplier;
        a.closing = rate > 0 ? lead->closing : -lead->closing;
        a.follows = driver;
        d.hand.push_back(a);
        ++added;
      }
      f.joints.push_back(j->name);
    }
  }
  guesses.push_back("adaptive: " + std::to_string(added) +
                    " mimic joints of the fingers in q, each closing until its own finger stops "
                    "(--adaptive)");
}

// A hand joint that closes two or more fingers (through their mimic joints), or "".
std::string shared_motor(const Draft& d) {
  std::map<std::string, int> fingers;
  for (const FingerDraft& f : d.fingers) {
    for (const std::string& j : f.joints) {
      const auto closes = [&](const JointDraft& h) { return h.name == j && h.closing != 0; };
      if (std::any_of(d.hand.begin(), d.hand.end(), closes) && ++fingers[j] == 2) return j;
    }
  }
  return "";
}

// A closed hand should enclose a 3 cm bar (a typical handle) with 1 cm to spare.
constexpr double kWantedAperture = 0.04;

// The highest goal the closing hand reaches with kWantedAperture left inside it (else the one
// that leaves the most), and the tcp in the middle of the hand closed to it.
void choose_goal(Draft& d, const DraftOptions& o, std::vector<std::string>& guesses) {
  const RobotModel m = load_draft(d, o);
  const std::vector<double> goals = {0.5, 0.55, 0.6, 0.65, 0.7, 0.75, 0.8, 0.85, 0.9};
  const std::vector<HandSize> sizes = hand_sizes(m, goals);  // one closing sweep
  double best = -1.0, best_goal = 0.0;
  Eigen::Vector3d centre = Eigen::Vector3d::Zero();  // of the hand closed to the goal chosen
  for (std::size_t i = goals.size(); i-- > 0;) {     // the highest first
    const double goal = goals[i];
    const HandSize& size = sizes[i];
    if (size.closed_ratio < goal - 1e-3) continue;  // the fingers' limits stop short of it
    if (size.closed_aperture > best + 1e-9) {
      best = size.closed_aperture;
      best_goal = goal;
      centre = size.closed_centre;
    }
    if (size.closed_aperture >= kWantedAperture) break;
  }
  if (best < 0) {
    d.vlink_goal = 0.5;
    d.vlink_note = "guessed: the closing fingers never reach 0.5: check the closing directions";
    guesses.push_back("vlink_goal: no goal from 0.9 down to 0.5 is reached when the fingers close");
  } else {
    d.vlink_goal = best_goal;
    char what[160];
    std::snprintf(what, sizeof what,
                  "the highest goal that leaves the closed hand %.1f cm inside (%s 4 cm)",
                  100.0 * best, best >= kWantedAperture ? ">=" : "the most, short of");
    d.vlink_note = std::string("guessed: ") + what;
    guesses.push_back("vlink_goal " + draft_number(best_goal) + ": " + what);
  }
  RobotData data(m);
  forward_kinematics(m, m.home, data);
  const Eigen::Isometry3d& root = data.link_poses[m.link_index(d.base_link)];
  d.tcp = {d.base_link, root.inverse() * centre, true};
}

// MoveIt's rule: pairs in contact at the (given) home pose or in nearly every random
// configuration are allowed; those never in contact are counted (FCL checks them quickly anyway).
void allow_pairs(Draft& d, const DraftOptions& o, DescriptionDraft& out) {
  const RobotModel m = load_draft(d, o);
  CollisionWorld world(m);
  RobotData data(m);
  forward_kinematics(m, m.home, data);
  const auto at_home = world.self_contacts(data);
  std::map<std::pair<std::string, std::string>, int> seen;  // samples in contact, per pair
  for (const auto& pair : at_home) seen[pair] = 0;
  std::mt19937_64 rng(o.seed);
  Eigen::VectorXd q = m.home;
  for (int k = 0; k < o.samples; ++k) {
    for (int j = 0; j < m.dof(); ++j) {
      const double lo = std::max(m.joints[j].lower, -M_PI), hi = std::min(m.joints[j].upper, M_PI);
      q[j] = lo + uniform01(rng()) * (hi - lo);
    }
    forward_kinematics(m, q, data);
    for (const auto& pair : world.self_contacts(data)) ++seen[pair];
  }
  int touched = 0;
  std::string at_guessed_home;
  for (const auto& [pair, count] : seen) {
    ++touched;
    const bool home = std::find(at_home.begin(), at_home.end(), pair) != at_home.end();
    const bool always = o.samples > 0 && count >= 0.95 * o.samples;
    // Contacts at a guessed home are a pose to change, not pairs to allow.
    if (home && o.home.empty() && !always) {
      at_guessed_home += (at_guessed_home.empty() ? "" : ", ") + pair.first + " / " + pair.second;
      continue;
    }
    if (!home && !always) continue;
    d.allowed.push_back(pair);
    out.allowed.push_back(pair.first + " / " + pair.second +
                          (always ? " (in contact in " + std::to_string(count) + " of " +
                                        std::to_string(o.samples) + " random configurations)"
                                  : " (in contact at the home pose)"));
  }
  if (!at_guessed_home.empty())
    out.guesses.push_back("home: links in contact at the guessed home (" + at_guessed_home +
                          "): give the vendor's home with --home, or write a free one");
  out.never_colliding_pairs =
      std::max(0, static_cast<int>(world.self_collision_pairs().size()) - touched);
}

}  // namespace

DescriptionDraft draft_description(const DraftOptions& o) {
  if (o.samples < 0) throw InputError("--samples must be >= 0");
  DescriptionDraft out;
  const Tree t = read_tree(o);
  const int root = find_hand_root(t, o);
  Draft d = topology(t, o, root);
  if (d.fingers.size() < 2)
    throw InputError("the hand's root '" + d.base_link +
                     "' has fewer than two fingers (branches with moving joints)");
  if (o.hand_root.empty())
    out.guesses.push_back("hand root: " + d.base_link +
                          ", the first link with two or more moving branches (--hand-root)");
  for (FingerDraft& f : d.fingers) f.tip = {f.links.back()};  // shape_hand finds the tips
  // A first model, to see the hand: every finger against the next through the palm (the last
  // one a thumb for now).
  d.fingers.back().thumb = true;
  for (std::size_t f = 0; f + 1 < d.fingers.size(); ++f)
    d.curves.push_back({"draft_" + std::to_string(f + 1),
                        {d.fingers[f].tip, {d.base_link}, d.fingers[f + 1].tip}});
  shape_hand(d, load_draft(d, o), out.guesses);
  if (o.adaptive) {
    make_adaptive(d, t, load_draft(d, o), out.guesses);
  } else if (const std::string motor = shared_motor(d); !motor.empty()) {
    out.guesses.push_back("coupling: '" + motor +
                          "' closes several fingers through mimic joints, so they stop together at "
                          "the first contact; if the hand is underactuated (tendons, springs), "
                          "draft it with --adaptive");
  }
  choose_goal(d, o, out.guesses);
  allow_pairs(d, o, out);
  out.yaml = to_yaml(d);
  out.model = load_draft(d, o);
  return out;
}

}  // namespace claspplan::robots
