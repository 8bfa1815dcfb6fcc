// Drafting a hand description from a URDF (issue 35): each rule on a small synthetic robot, a
// three-joint arm with a palm and fingers of capsule-like cylinders, written per case.
#include "robots/description_draft.hpp"

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <string>

#include <gtest/gtest.h>
#include <unistd.h>

#include "core/input_error.hpp"
#include "robots/collision_world.hpp"
#include "robots/hand_size.hpp"
#include "robots/kinematics.hpp"

namespace claspplan::robots {
namespace {

namespace fs = std::filesystem;

struct Finger {
  std::string name;
  double x, y;         // base on the palm's top face (palm frame)
  int flex_sign = 1;   // +1: flexes toward +x
  bool mimic = false;  // the distal joint mimics the proximal one
  std::string parent = "palm";
};

std::string cylinder(const std::string& link, double length, double radius = 0.008) {
  return "<link name=\"" + link + "\"><collision><origin xyz=\"0 0 " + std::to_string(length / 2) +
         "\"/><geometry><cylinder radius=\"" + std::to_string(radius) + "\" length=\"" +
         std::to_string(length) + "\"/></geometry></collision></link>\n";
}

std::string joint(const std::string& name, const std::string& type, const std::string& parent,
                  const std::string& child, const std::string& xyz, const std::string& axis,
                  const std::string& extra = "", const std::string& rpy = "0 0 0") {
  return "<joint name=\"" + name + "\" type=\"" + type + "\"><parent link=\"" + parent +
         "\"/><child link=\"" + child + "\"/><origin xyz=\"" + xyz + "\" rpy=\"" + rpy +
         "\"/><axis xyz=\"" + axis + "\"/>" + extra + "</joint>\n";
}

const std::string kFlexLimits = "<limit lower=\"-0.2\" upper=\"1.6\" effort=\"1\" velocity=\"1\"/>";

// A finger of two flexing joints and a fixed tip link; the flexion turns it toward +x (or -x).
std::string finger(const Finger& f) {
  const std::string axis = f.flex_sign > 0 ? "0 1 0" : "0 -1 0";
  const std::string base = std::to_string(f.x) + " " + std::to_string(f.y) + " 0";
  std::string u = cylinder(f.name + "_proximal", 0.05) + cylinder(f.name + "_distal", 0.04) +
                  "<link name=\"" + f.name + "_tip\"/>\n";
  u += joint(f.name + "_1", "revolute", f.parent, f.name + "_proximal", base, axis, kFlexLimits);
  u += joint(f.name + "_2", "revolute", f.name + "_proximal", f.name + "_distal", "0 0 0.05", axis,
             kFlexLimits + (f.mimic ? "<mimic joint=\"" + f.name + "_1\"/>" : ""));
  u += joint(f.name + "_tip_joint", "fixed", f.name + "_distal", f.name + "_tip", "0 0 0.04",
             "0 0 1");
  return u;
}

// A finger of a one-motor hand closed at 0 (as Romeo's and NAO's are): each joint's origin turns
// it 0.3 rad toward the opposite finger, and the value 0.3, its upper limit, turns it straight.
// Every joint but `leader` mimics `leader`.
std::string coupled_finger(const Finger& f, const std::string& leader) {
  const std::string axis = f.flex_sign > 0 ? "0 -1 0" : "0 1 0";
  const std::string rpy = f.flex_sign > 0 ? "0 0.3 0" : "0 -0.3 0";
  const std::string base = std::to_string(f.x) + " " + std::to_string(f.y) + " 0";
  const auto limits = [&](const std::string& name) {
    return "<limit lower=\"0\" upper=\"0.3\" effort=\"1\" velocity=\"1\"/>" +
           (name == leader ? "" : "<mimic joint=\"" + leader + "\"/>");
  };
  std::string u = cylinder(f.name + "_proximal", 0.05) + cylinder(f.name + "_distal", 0.04) +
                  "<link name=\"" + f.name + "_tip\"/>\n";
  u += joint(f.name + "_1", "revolute", "palm", f.name + "_proximal", base, axis,
             limits(f.name + "_1"), rpy);
  u += joint(f.name + "_2", "revolute", f.name + "_proximal", f.name + "_distal", "0 0 0.05", axis,
             limits(f.name + "_2"), rpy);
  u += joint(f.name + "_tip_joint", "fixed", f.name + "_distal", f.name + "_tip", "0 0 0.04",
             "0 0 1");
  return u;
}

// The arm: base, three revolute joints, a palm (its top face at z = 0 of its frame, the fingers
// pointing along +z). `overlap`: the first two joints meet at one point, inside the base, so that
// the base and the lower arm (not adjacent: a small link lies between them) always touch.
std::string robot_urdf(const std::vector<Finger>& fingers, bool overlap = false) {
  const std::string limits = "<limit lower=\"-3\" upper=\"3\" effort=\"1\" velocity=\"1\"/>";
  std::string u = "<robot name=\"synthetic\">\n";
  u += "<link name=\"base\"><collision><origin xyz=\"0 0 0.05\"/><geometry><box size=\"0.1 0.1 "
       "0.1\"/></geometry></collision></link>\n";
  u += cylinder("upper", 0.01, 0.01) + cylinder("lower", 0.3, 0.03) + cylinder("wrist", 0.05, 0.03);
  u += "<link name=\"palm\"><collision><origin xyz=\"0.03 0 -0.03\"/><geometry><box size=\"0.1 "
       "0.08 0.06\"/></geometry></collision></link>\n";
  u += joint("j1", "revolute", "base", "upper", overlap ? "0 0 0.08" : "0 0 0.12", "0 0 1", limits);
  u += joint("j2", "revolute", "upper", "lower", overlap ? "0 0 0" : "0 0 0.05", "0 1 0", limits);
  u += joint("j3", "revolute", "lower", "wrist", "0 0 0.3", "0 1 0", limits);
  u += joint("palm_joint", "fixed", "wrist", "palm", "0 0 0.11", "0 0 1");
  for (const Finger& f : fingers) u += finger(f);
  return u + "</robot>\n";
}

// The arm and palm with three fingers that all follow a_1, closed at 0; the thumb c stands 12 cm
// across, so that the fist at 0 does not cross the fingers.
std::string one_motor_robot_urdf() {
  std::string urdf = robot_urdf({});
  std::string fingers;
  for (const Finger& f :
       {Finger{"a", 0.0, 0.02, 1}, Finger{"b", 0.0, -0.02, 1}, Finger{"c", 0.12, 0.0, -1}})
    fingers += coupled_finger(f, "a_1");
  return urdf.insert(urdf.rfind("</robot>"), fingers);
}

// Two fingers side by side and one facing them across the palm.
std::vector<Finger> three_fingers(bool mimic = false) {
  return {{"a", 0.0, 0.02, 1, false}, {"b", 0.0, -0.02, 1, mimic}, {"c", 0.06, 0.0, -1, false}};
}

class Folder {
 public:
  Folder() {
    char name[] = "/tmp/claspplan_draft_XXXXXX";
    path_ = mkdtemp(name);
  }
  ~Folder() { fs::remove_all(path_); }
  fs::path write(const std::string& name, const std::string& text) const {
    std::ofstream(path_ / name) << text;
    return path_ / name;
  }
  const fs::path& path() const { return path_; }

 private:
  fs::path path_;
};

DescriptionDraft draft(const Folder& dir, const std::string& urdf, DraftOptions o = {}) {
  o.urdf = dir.write("robot.urdf", urdf);
  o.out = dir.path() / "robot.yaml";
  o.samples = 200;
  return draft_description(o);
}

TEST(DescriptionDraft, FindsTheArmTheFingersAndTheThumbAcrossFromThem) {
  Folder dir;
  const DescriptionDraft d = draft(dir, robot_urdf(three_fingers()));
  const RobotModel& m = d.model;
  EXPECT_EQ(m.arm_dof, 3);
  EXPECT_EQ(m.hand_dof, 6);
  EXPECT_EQ(m.links[m.hand_base_link].name, "palm");
  EXPECT_EQ(m.links[m.tool_link].name, "wrist");
  ASSERT_EQ(m.fingers.size(), 3u);
  int thumbs = 0;
  for (const auto& f : m.fingers) {
    thumbs += f.thumb;
    // The thumb is finger c, set across the palm from a and b.
    EXPECT_EQ(f.thumb, m.links[f.links.front()].name.rfind("c_", 0) == 0) << f.name;
  }
  EXPECT_EQ(thumbs, 1);
  EXPECT_EQ(m.curves.size(), 2u);  // a and b against the thumb
  // Every flexing joint closes its finger (toward the opposite one): +1 with these axes.
  for (int j = m.arm_dof; j < m.dof(); ++j) EXPECT_EQ(m.joints[j].closing, 1) << m.joints[j].name;
  // v_fwd along the fingers, v_swd normal to the plane they close in (x-z).
  EXPECT_NEAR(m.v_fwd.vector.z(), 1.0, 1e-9);
  EXPECT_NEAR(std::abs(m.v_swd.vector.y()), 1.0, 1e-9);
  // The closed hand reaches its goal and leaves room for a bar; the tcp lies inside it.
  const HandSize size = hand_size(m);
  EXPECT_GT(size.closed_aperture, 0.01);
  EXPECT_GE(m.vlink_goal, 0.5);
  EXPECT_LE(m.vlink_goal, 0.9);
  EXPECT_GT(m.tcp.point.z(), 0.0);
  EXPECT_LT(m.tcp.point.z(), 0.09);
  EXPECT_GT(m.tcp.point.x(), 0.0);
  EXPECT_LT(m.tcp.point.x(), 0.06);
  // Each guess is reported.
  std::string guesses;
  for (const auto& g : d.guesses) guesses += g + "\n";
  EXPECT_NE(guesses.find("hand root: palm"), std::string::npos) << guesses;
  EXPECT_NE(guesses.find("thumb: the finger of c_proximal"), std::string::npos) << guesses;
  EXPECT_NE(guesses.find("vlink_goal"), std::string::npos) << guesses;
  EXPECT_NE(d.yaml.find("# guessed"), std::string::npos);
}

TEST(DescriptionDraft, ClosingDirectionsFollowTheGeometryNotTheAxisSign) {
  // The thumb's axis is -y: it closes with + as well. Flip finger a's axis: it now closes with -.
  Folder dir;
  std::vector<Finger> fingers = three_fingers();
  fingers[0].flex_sign = -1;  // a's flexion (positive angles) now turns it away from the thumb
  const RobotModel m = draft(dir, robot_urdf(fingers)).model;
  for (int j = m.arm_dof; j < m.dof(); ++j) {
    const bool a = m.joints[j].name.rfind("a_", 0) == 0;
    EXPECT_EQ(m.joints[j].closing, a ? -1 : 1) << m.joints[j].name;
  }
  EXPECT_GT(hand_size(m).closed_aperture, 0.01);
}

TEST(DescriptionDraft, MimicJointsFollowTheirLeaderAndAreNotInQ) {
  Folder dir;
  const RobotModel m = draft(dir, robot_urdf(three_fingers(true))).model;
  EXPECT_EQ(m.hand_dof, 5);
  EXPECT_LT(m.find_joint("b_2"), 0);
  // b's distal link turns with b_1.
  const int b1 = m.joint_index("b_1");
  RobotData data(m);
  Eigen::VectorXd q = m.home;
  forward_kinematics(m, q, data);
  const Eigen::Vector3d before = data.link_poses[m.link_index("b_tip")].translation();
  q[b1] += 0.5;
  forward_kinematics(m, q, data);
  const Eigen::Vector3d after = data.link_poses[m.link_index("b_tip")].translation();
  EXPECT_GT((after - before).norm(), 0.03);
  for (const auto& f : m.fingers) {
    if (m.links[f.links.back()].name == "b_tip") {
      EXPECT_EQ(f.joints.size(), 1u);
    }
  }
}

// Two fingers on a plate that turns with the thumb (SVH's ring and little fingers): each is a
// finger of its own, and the plate, where their branches split, belongs to the palm.
TEST(DescriptionDraft, FingersOnAMovingPlateAreFingersOfTheirOwn) {
  Folder dir;
  std::vector<Finger> fingers = three_fingers();
  fingers[0].parent = fingers[1].parent = "plate";
  std::string urdf = robot_urdf(fingers);
  urdf.insert(urdf.rfind("</robot>"),
              cylinder("plate", 0.005, 0.03) +
                  joint("plate_joint", "revolute", "palm", "plate", "0 0 0", "1 0 0",
                        "<limit lower=\"0\" upper=\"0.1\" effort=\"1\" velocity=\"1\"/>"
                        "<mimic joint=\"c_1\" multiplier=\"0.05\"/>"));
  const RobotModel m = draft(dir, urdf).model;
  ASSERT_EQ(m.fingers.size(), 3u);
  for (const auto& f : m.fingers) {
    EXPECT_NE(m.links[f.links.front()].name, "plate") << f.name;
    EXPECT_EQ(f.thumb, m.links[f.links.front()].name.rfind("c_", 0) == 0) << f.name;
  }
  EXPECT_GT(hand_size(m).closed_aperture, 0.01);
}

TEST(DescriptionDraft, ANamedThumbAndTwoFingersThatFaceEachOther) {
  Folder dir;
  // Named: the thumb is the one called so, wherever it sits.
  std::vector<Finger> named = three_fingers();
  named[0].name = "thumb";
  named[0].flex_sign = -1;
  const RobotModel m = draft(dir, robot_urdf(named)).model;
  for (const auto& f : m.fingers)
    EXPECT_EQ(f.thumb, m.links[f.links.front()].name.rfind("thumb_", 0) == 0);
  // Two fingers: the second is the thumb.
  const std::vector<Finger> two = {{"a", 0.0, 0.0, 1, false}, {"c", 0.06, 0.0, -1, false}};
  const RobotModel g = draft(dir, robot_urdf(two)).model;
  ASSERT_EQ(g.fingers.size(), 2u);
  EXPECT_FALSE(g.fingers[0].thumb);
  EXPECT_TRUE(g.fingers[1].thumb);
  EXPECT_GT(hand_size(g).closed_aperture, 0.01);
}

TEST(DescriptionDraft, AllowsPairsThatAlwaysTouchAndThoseAtAGivenHome) {
  Folder dir;
  // The base and the lower arm meet at the first joints' common point in every configuration.
  const DescriptionDraft d = draft(dir, robot_urdf(three_fingers(), true));
  ASSERT_EQ(d.model.allowed_pairs.size(), 1u) << d.yaml;
  const auto [a, b] = d.model.allowed_pairs[0];
  EXPECT_EQ(d.model.links[a].name, "base");
  EXPECT_EQ(d.model.links[b].name, "lower");
  EXPECT_GT(d.never_colliding_pairs, 0);
  // Folded onto itself at the guessed home, the arm's contacts there are reported, not allowed;
  // at a home the user gives, they are allowed (MoveIt's "default" pairs).
  DraftOptions folded;
  folded.home = {0.0, 2.9, 2.9};
  const DescriptionDraft given = draft(dir, robot_urdf(three_fingers()), folded);
  EXPECT_FALSE(given.model.allowed_pairs.empty());
  CollisionWorld world(given.model);
  RobotData data(given.model);
  forward_kinematics(given.model, given.model.home, data);
  EXPECT_FALSE(world.in_collision(data));
}

TEST(DescriptionDraft, RefusesWhatItCannotDraft) {
  Folder dir;
  // No hand: an arm whose only branch has no fingers.
  EXPECT_THROW(draft(dir, robot_urdf({{"a", 0.0, 0.0, 1, false}})), InputError);
  try {
    draft(dir, robot_urdf({{"a", 0.0, 0.0, 1, false}}));
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("--hand-root"), std::string::npos) << e.what();
  }
  DraftOptions o;
  o.home = {0.0};
  EXPECT_THROW(draft(dir, robot_urdf(three_fingers()), o), InputError);  // 1 value for 3 joints
  o = {};
  o.replaces = {"c_proximal"};
  EXPECT_THROW(draft(dir, robot_urdf(three_fingers()), o), InputError);  // no --hand-urdf
  o = {};
  o.hand_root = "nowhere";
  EXPECT_THROW(draft(dir, robot_urdf(three_fingers()), o), InputError);
  o = {};
  o.urdf = dir.path() / "missing.urdf";
  o.out = dir.path() / "robot.yaml";
  EXPECT_THROW(draft_description(o), InputError);
}

TEST(DescriptionDraft, AHandFromItsOwnUrdfIsMountedAndTheArmsGripperLeftOut) {
  Folder dir;
  // The arm carries a two-finger gripper of its own; the hand's URDF is the three-finger hand.
  const std::string hand = robot_urdf(three_fingers());
  const std::string arm = robot_urdf({{"g", 0.0, 0.0, 1, false}, {"h", 0.06, 0.0, -1, false}});
  // The hand's URDF: the palm and its fingers only.
  const size_t palm = hand.find("<link name=\"palm\">");
  std::string hand_urdf =
      "<robot name=\"hand\">\n" + hand.substr(palm, hand.find("</link>", palm) + 8 - palm);
  for (const Finger& f : three_fingers()) hand_urdf += finger(f);
  hand_urdf += "</robot>\n";
  DraftOptions o;
  o.hand_urdf = dir.write("hand.urdf", hand_urdf);
  o.mount = "wrist";
  o.mount_xyz = {0, 0, 0.2};
  o.replaces = {"palm"};
  const DescriptionDraft d = draft(dir, arm, o);
  EXPECT_EQ(d.model.hand_dof, 6);
  EXPECT_EQ(d.model.fingers.size(), 3u);
  EXPECT_LT(d.model.find_link("g_tip"), 0);
  EXPECT_NE(d.yaml.find("replaces: [palm]"), std::string::npos) << d.yaml;
}

// A one-motor hand closed at 0, cut from a whole robot's URDF (hand_urdf root), mounted turned:
// its fingers are found through their mimic joints, the motor opens at its upper limit, and the
// tips and v_fwd are read at the open hand, not at the fist the joints' zero makes.
TEST(DescriptionDraft, AOneMotorHandClosedAtZeroIsCutFromAWholeRobot) {
  Folder dir;
  DraftOptions o;
  o.hand_urdf = dir.write("whole.urdf", one_motor_robot_urdf());
  o.hand_urdf_root = "palm";
  o.mount = "wrist";
  o.mount_xyz = {0, 0, 0.11};
  o.mount_rpy = {0, 0, M_PI / 2};
  o.replaces = {"palm"};
  const DescriptionDraft d = draft(dir, robot_urdf({{"g", 0.0, 0.0, 1}, {"h", 0.06, 0.0, -1}}), o);
  const RobotModel& m = d.model;
  EXPECT_EQ(m.arm_dof, 3);
  ASSERT_EQ(m.hand_dof, 1);
  const Joint& motor = m.joints[m.arm_dof];
  EXPECT_EQ(motor.name, "a_1");
  EXPECT_EQ(motor.open, 0.3);
  EXPECT_EQ(motor.closing, -1);
  ASSERT_EQ(m.fingers.size(), 3u);
  for (const auto& f : m.fingers) EXPECT_EQ(f.joints, std::vector<int>{m.arm_dof}) << f.name;
  // One motor for every finger: the draft names --adaptive for an underactuated hand.
  EXPECT_TRUE(std::any_of(d.guesses.begin(), d.guesses.end(), [](const std::string& g) {
    return g.find("'a_1' closes several fingers") != std::string::npos &&
           g.find("--adaptive") != std::string::npos;
  }));
  // Along the straight fingers (the palm's z), not tilted toward the fist.
  EXPECT_NEAR(m.v_fwd.vector.z(), 1.0, 1e-9);
  EXPECT_GT(hand_size(m).closed_aperture, 0.01);
  // The palm hangs off the arm's wrist, turned a quarter turn about z.
  const int palm = m.link_index("palm");
  EXPECT_EQ(m.links[m.links[palm].parent].name, "wrist");
  RobotData data(m);
  forward_kinematics(m, m.home, data);
  const Eigen::Matrix3d turn =
      data.link_poses[m.link_index("wrist")].linear().transpose() * data.link_poses[palm].linear();
  EXPECT_NEAR(turn(1, 0), 1.0, 1e-9);
  EXPECT_NE(d.yaml.find("root: palm"), std::string::npos) << d.yaml;
  // A root that is not in the URDF is refused.
  o.hand_urdf_root = "no_such_link";
  EXPECT_THROW(draft(dir, robot_urdf({}), o), InputError);
}

// --adaptive: the same kind of hand, its fingers' mimic joints as joints of their own that follow
// the motor and close the way it closes them.
TEST(DescriptionDraft, AnAdaptiveHandsMimicJointsAreJointsOfTheirOwn) {
  Folder dir;
  DraftOptions o;
  o.hand_root = "palm";
  o.adaptive = true;
  const DescriptionDraft d = draft(dir, one_motor_robot_urdf(), o);
  const RobotModel& m = d.model;
  ASSERT_EQ(m.hand_dof, 6);  // a_1 and the five joints that mimic it
  const int motor = m.joint_index("a_1");
  for (int j = m.arm_dof; j < m.dof(); ++j) {
    if (j == motor) continue;
    EXPECT_EQ(m.joints[j].follows, motor) << m.joints[j].name;
    EXPECT_EQ(m.joints[j].closing, m.joints[motor].closing) << m.joints[j].name;
    EXPECT_EQ(m.home[j], m.home[motor]) << m.joints[j].name;
  }
  for (const auto& f : m.fingers) {  // each finger closes on its own joints
    ASSERT_EQ(f.joints.size(), 2u) << f.name;
    EXPECT_EQ(m.joints[f.joints[0]].link, m.link_index(m.links[f.links[0]].name)) << f.name;
  }
  EXPECT_NE(d.yaml.find("# adaptive: follows a_1"), std::string::npos) << d.yaml;
  for (const std::string& g : d.guesses)
    EXPECT_EQ(g.find("closes several fingers"), std::string::npos);
}

}  // namespace
}  // namespace claspplan::robots
