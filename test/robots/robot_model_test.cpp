// Loading the built-in robots and hand descriptions, and rejecting bad ones with a clear reason.
#include "robots/robot_model.hpp"

#include <filesystem>
#include <fstream>
#include <random>
#include <string>

#include <gtest/gtest.h>
#include <unistd.h>

#include "robots/embedded_models.hpp"

namespace claspplan::robots {
namespace {

std::string embedded(const std::string& name) {
  const char* text = embedded_model_file(name);
  EXPECT_NE(text, nullptr) << name;
  return text ? text : "";
}

// Replaces the first occurrence of `from` (which must exist) by `to`.
std::string replaced(std::string text, const std::string& from, const std::string& to) {
  const size_t at = text.find(from);
  EXPECT_NE(at, std::string::npos) << "test setup: '" << from << "' not found";
  if (at != std::string::npos) text.replace(at, from.size(), to);
  return text;
}

// Replaces the text from `from` up to (not including) `until` by `to`.
std::string cut(std::string text, const std::string& from, const std::string& until,
                const std::string& to) {
  const size_t a = text.find(from);
  const size_t b = text.find(until, a);
  EXPECT_TRUE(a != std::string::npos && b != std::string::npos) << "test setup: " << from;
  if (a != std::string::npos && b != std::string::npos) text.replace(a, b - a, to);
  return text;
}

// The reason load_robot_from_text() gives, or "" when it loads.
std::string load_error(const std::string& yaml, const std::string& urdf) {
  try {
    load_robot_from_text(yaml, urdf, "hand.yaml", "robot.urdf");
  } catch (const std::invalid_argument& e) {
    return e.what();
  }
  return "";
}

class TempDir {
 public:
  TempDir() {
    std::mt19937_64 rng(
        std::hash<std::string>()(::testing::UnitTest::GetInstance()->current_test_info()->name()));
    path_ = std::filesystem::temp_directory_path() /
            ("claspplan-robots-" + std::to_string(rng()) + std::to_string(::getpid()));
    std::filesystem::create_directories(path_);
  }
  ~TempDir() {
    std::error_code ec;
    std::filesystem::remove_all(path_, ec);
  }
  std::string write(const std::string& name, const std::string& text) const {
    const auto p = path_ / name;
    std::filesystem::create_directories(p.parent_path());
    std::ofstream(p, std::ios::binary) << text;
    return p.string();
  }
  const std::filesystem::path& path() const { return path_; }

 private:
  std::filesystem::path path_;
};

TEST(RobotModel, BuiltinJointCounts) {
  const std::vector<std::pair<std::string, int>> expected = {
      {"kr5_sdh", 6}, {"kr5_dlr", 12}, {"kr5_icub", 15}, {"kr5_armar3", 10}};
  ASSERT_EQ(builtin_robots().size(), expected.size());
  for (const auto& [name, hand] : expected) {
    const RobotModel m = load_robot(name);
    EXPECT_EQ(m.name, name);
    EXPECT_EQ(m.arm_dof, 6) << name;
    EXPECT_EQ(m.hand_dof, hand) << name;
    EXPECT_EQ(m.dof(), 6 + hand) << name;
    for (int i = 0; i < m.dof(); ++i) {
      EXPECT_EQ(m.joints[i].hand, i >= 6) << name << " " << m.joints[i].name;
      EXPECT_LE(m.joints[i].lower, m.joints[i].upper);
    }
    EXPECT_EQ(m.joints[0].name, "joint_a1");
    EXPECT_EQ(m.joints[5].name, "joint_a6");
    EXPECT_TRUE(m.within_limits(m.home)) << name;
    EXPECT_EQ(m.links[0].name, "base_link");
    EXPECT_EQ(m.links[m.tool_link].name, "tool0");
  }
}

TEST(RobotModel, CurveCountsAndFingers) {
  const std::vector<std::pair<std::string, int>> curves = {
      {"kr5_sdh", 2}, {"kr5_dlr", 3}, {"kr5_icub", 4}, {"kr5_armar3", 4}};
  for (const auto& [name, n] : curves) {
    const RobotModel m = load_robot(name);
    ASSERT_EQ(static_cast<int>(m.curves.size()), n) << name;
    int thumbs = 0;
    for (const Finger& f : m.fingers) {
      thumbs += f.thumb;
      EXPECT_FALSE(f.joints.empty());
      for (int j : f.joints) EXPECT_TRUE(m.joints[j].hand);
    }
    EXPECT_EQ(thumbs, 1) << name;
    // Every hand joint belongs to exactly one finger.
    std::vector<int> owner(m.dof(), 0);
    for (const Finger& f : m.fingers)
      for (int j : f.joints) ++owner[j];
    for (int j = m.arm_dof; j < m.dof(); ++j) EXPECT_EQ(owner[j], 1) << m.joints[j].name;
    EXPECT_NEAR(m.v_fwd.vector.dot(m.v_swd.vector), 0.0, 1e-12);
    EXPECT_GT(m.vlink_goal, 0.7);
  }
  EXPECT_DOUBLE_EQ(load_robot("kr5_sdh").vlink_goal, 0.85);
  EXPECT_DOUBLE_EQ(load_robot("kr5_dlr").vlink_goal, 0.85);
  EXPECT_DOUBLE_EQ(load_robot("kr5_armar3").vlink_goal, 0.8);
  EXPECT_DOUBLE_EQ(load_robot("kr5_icub").vlink_goal, 0.75);
}

TEST(RobotModel, HeldAndMimicJointsAreNotInQ) {
  const RobotModel sdh = load_robot("kr5_sdh");
  EXPECT_LT(sdh.find_joint("knuckle_joint"), 0);
  EXPECT_LT(sdh.find_joint("finger_21_joint"), 0);
  const Link& f21 = sdh.links[sdh.link_index("finger_21_link")];
  EXPECT_EQ(f21.q_index, -1);  // mimic of a held joint: constant
  EXPECT_DOUBLE_EQ(f21.offset, 0.0);

  const RobotModel dlr = load_robot("kr5_dlr");
  EXPECT_LT(dlr.find_joint("index_dip"), 0);
  const Link& dip = dlr.links[dlr.link_index("index_distal")];
  EXPECT_EQ(dip.q_index, dlr.joint_index("index_pip"));
  EXPECT_NEAR(dip.multiplier, 1.047619, 1e-12);

  const RobotModel icub = load_robot("kr5_icub");
  for (const char* held : {"thumb_opp", "index_abd", "middle_abd", "ring_abd", "pinky_abd"})
    EXPECT_LT(icub.find_joint(held), 0) << held;
  EXPECT_DOUBLE_EQ(icub.links[icub.link_index("thumb_opp_link")].offset, 1.3);

  const RobotModel armar = load_robot("kr5_armar3");
  EXPECT_LT(armar.find_joint("armar_palm2_joint"), 0);
}

TEST(RobotModel, OpenPreshapeAndClosingDirections) {
  const RobotModel sdh = load_robot("kr5_sdh");
  EXPECT_DOUBLE_EQ(sdh.home[sdh.joint_index("finger_12_joint")], -1.0);
  EXPECT_DOUBLE_EQ(sdh.home[sdh.joint_index("thumb_3_joint")], 1.0);
  EXPECT_NEAR(sdh.home[1], -M_PI / 2, 1e-12);
  EXPECT_NEAR(sdh.home[2], M_PI / 2, 1e-12);
  for (int j = sdh.arm_dof; j < sdh.dof(); ++j) EXPECT_EQ(sdh.joints[j].closing, 1);
  const RobotModel dlr = load_robot("kr5_dlr");
  EXPECT_EQ(dlr.joints[dlr.joint_index("index_abd")].closing, 0);
  Eigen::VectorXd q = Eigen::VectorXd::Constant(dlr.dof(), 0.3);
  EXPECT_EQ(dlr.open_hand(q).tail(dlr.hand_dof), dlr.home.tail(dlr.hand_dof));
}

TEST(RobotModel, CollisionShapesIncludeMergedCapsules) {
  const RobotModel icub = load_robot("kr5_icub");
  int capsules = 0, spheres = 0;
  for (const CollisionShape& s : icub.shapes) {
    capsules += s.type == CollisionShape::Type::kCapsule;
    spheres += s.type == CollisionShape::Type::kSphere;
    EXPECT_GE(s.link, 0);
  }
  EXPECT_EQ(spheres, 0);               // every cylinder + 2 end spheres became a capsule
  EXPECT_EQ(capsules, 1 + 4 * 4 + 4);  // link_4, 4 links per finger, thumb
  const CollisionShape& l4 = icub.shapes[icub.links[icub.link_index("link_4")].shapes.at(0)];
  EXPECT_EQ(l4.type, CollisionShape::Type::kCapsule);
  EXPECT_NEAR(l4.radius, 0.06, 1e-12);
  EXPECT_NEAR(l4.length, 0.13, 1e-12);
  EXPECT_NEAR(l4.origin.translation().x(), 0.325, 1e-12);
  EXPECT_STREQ(shape_type_name(l4.type), "capsule");
}

TEST(RobotModel, CompleteQAndClamp) {
  const RobotModel m = load_robot("kr5_sdh");
  const Eigen::VectorXd q = m.complete_q({0.1, -1.0});
  EXPECT_DOUBLE_EQ(q[0], 0.1);
  EXPECT_DOUBLE_EQ(q[1], -1.0);
  EXPECT_EQ(q.tail(m.dof() - 2), m.home.tail(m.dof() - 2));
  EXPECT_THROW(m.complete_q(std::vector<double>(13, 0.0)), std::invalid_argument);
  EXPECT_THROW(m.complete_q({std::nan("")}), std::invalid_argument);
  try {
    m.complete_q({0, 1.0});  // joint_a2 upper limit is 45°
    FAIL();
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("joint_a2"), std::string::npos) << e.what();
  }
  Eigen::VectorXd far = Eigen::VectorXd::Constant(m.dof(), 100.0);
  const Eigen::VectorXd c = m.clamp(far);
  EXPECT_TRUE(m.within_limits(c));
  EXPECT_DOUBLE_EQ(c[1], m.joints[1].upper);
  EXPECT_FALSE(m.within_limits(far));
}

TEST(RobotModel, LoadsFromAPathWithARelativeUrdf) {
  TempDir dir;
  dir.write("models/kr5_sdh.urdf", embedded("kr5_sdh.urdf"));
  const std::string yaml = dir.write(
      "desc/my_sdh.yaml",
      replaced(embedded("kr5_sdh.yaml"), "urdf: kr5_sdh.urdf", "urdf: ../models/kr5_sdh.urdf"));
  const RobotModel m = load_robot(yaml);
  EXPECT_EQ(m.dof(), 12);
  EXPECT_EQ(m.source, yaml);
  // Missing URDF file: the message names it.
  const std::string lonely = dir.write("lonely/r.yaml", embedded("kr5_sdh.yaml"));
  try {
    load_robot(lonely);
    FAIL();
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("kr5_sdh.urdf"), std::string::npos) << e.what();
  }
  EXPECT_THROW(load_robot((dir.path() / "nothing.yaml").string()), std::invalid_argument);
  EXPECT_THROW(load_robot("kr5_unknown"), std::invalid_argument);
}

struct BadCase {
  std::string label;
  std::string yaml, urdf;
  std::string expected;  // a piece of the reason
};

TEST(RobotModel, BadFilesGiveOneLineReasons) {
  const std::string yaml = embedded("kr5_sdh.yaml");
  const std::string urdf = embedded("kr5_sdh.urdf");
  ASSERT_EQ(load_error(yaml, urdf), "");
  const std::string dlr_yaml = embedded("kr5_dlr.yaml"), dlr_urdf = embedded("kr5_dlr.urdf");
  const std::vector<BadCase> cases = {
      {"truncated XML", yaml, urdf.substr(0, urdf.size() / 2), "robot.urdf: not a valid URDF"},
      {"not XML", yaml, "this is not xml", "robot.urdf"},
      {"empty URDF", yaml, "", "robot.urdf: the URDF is empty"},
      {"URDF link missing", yaml, replaced(urdf, "<link name=\"finger_13_tip\"/>", ""),
       "robot.urdf: not a valid URDF"},
      {"mesh file missing", yaml,
       replaced(urdf, "<box size=\"0.274 0.216 0.211\"/>", "<mesh filename=\"base.stl\"/>"),
       "link 'base_link': mesh 'base.stl' not found"},
      {"unknown link in a curve", replaced(yaml, "{link: finger_13_tip}", "{link: finger_99_tip}"),
       urdf, "unknown link 'finger_99_tip'"},
      {"unknown hand joint", replaced(yaml, "name: finger_12_joint", "name: finger_19_joint"), urdf,
       "unknown joint 'finger_19_joint'"},
      {"unknown arm joint", replaced(yaml, "joint_a6]", "joint_a7]"), urdf,
       "unknown joint 'joint_a7'"},
      {"unknown finger joint", replaced(yaml, "joints: [thumb_2_joint,", "joints: [knuckle,"), urdf,
       "'knuckle' is not a hand joint"},
      {"empty curve",
       cut(yaml, "      points:\n", "    - name: finger_2-thumb", "      points: []\n"), urdf,
       "hand.curves[0].points: a finger curve needs at least 3 points"},
      {"one-point curve",
       cut(yaml, "      points:\n", "    - name: finger_2-thumb",
           "      points:\n        - {link: finger_13_tip}\n"),
       urdf, "at least 3 points"},
      {"malformed YAML", "name: [unclosed\nurdf: x", urdf, "hand.yaml: malformed YAML: line"},
      {"YAML not a mapping", "- just\n- a list\n", urdf, "hand.yaml: expected a YAML mapping"},
      {"binary YAML", std::string("\x89PNG\r\n\x1a\n\0\0", 10), urdf, "hand.yaml"},
      {"joint left out", replaced(yaml, "    - {name: thumb_3_joint, open: 1.0, closing: 1}\n", ""),
       urdf, "joint 'thumb_3_joint' moves but is not listed"},
      {"NaN value", replaced(yaml, "open: -1.0", "open: .nan"), urdf, "must be finite"},
      {"open outside limits", replaced(yaml, "open: -1.0", "open: -2.0"), urdf,
       "outside its limits ["},
      {"home outside limits",
       replaced(yaml, "home: [0, -1.5707963267948966", "home: [3.5, -1.5707963267948966"), urdf,
       "value 3.5 for 'joint_a1' is outside its limits [-2.96706, 2.96706]"},
      {"word for a number", replaced(yaml, "vlink_goal: 0.85", "vlink_goal: high"), urdf,
       "expected a number, got 'high'"},
      {"goal out of range", replaced(yaml, "vlink_goal: 0.85", "vlink_goal: 1.5"), urdf,
       "must be in (0, 1)"},
      {"missing key", replaced(yaml, "  tcp: {link: sdh_palm_link, xyz: [0, 0, 0.19]}", ""), urdf,
       "missing key 'tcp'"},
      {"typo key", replaced(yaml, "  v_fwd:", "  v_fwdd:"), urdf, "unknown key 'v_fwdd'"},
      {"zero vector", replaced(yaml, "vector: [0, 0, 1]", "vector: [0, 0, 0]"), urdf,
       "must not be zero"},
      {"not orthogonal", replaced(yaml, "vector: [0, 1, 0]", "vector: [0, 1, 1]"), urdf,
       "orthogonal"},
      {"adaptive joint with an open value",
       replaced(dlr_yaml, "    - {name: ring_pip, open: 0, closing: 1}\n",
                "    - {name: ring_pip, open: 0, closing: 1}\n    - {name: ring_dip, open: 0}\n"),
       dlr_urdf, "opens with its leader"},
      {"joint twice", replaced(yaml, "name: finger_13_joint", "name: finger_12_joint"), urdf,
       "listed twice"},
      {"bad allowed pair", replaced(yaml, "- [link_4, link_6]", "- [link_4, nope]"), urdf,
       "unknown link 'nope'"},
  };
  for (const BadCase& c : cases) {
    const std::string reason = load_error(c.yaml, c.urdf);
    EXPECT_FALSE(reason.empty()) << c.label << ": loaded";
    EXPECT_EQ(reason.find('\n'), std::string::npos) << c.label << ": " << reason;
    if (!c.expected.empty()) {
      EXPECT_NE(reason.find(c.expected), std::string::npos) << c.label << ": " << reason;
    }
  }
}

// A continuous joint gets two turns either way: a vendor's home at 4.8 rad loads, 7 rad does not,
// and the message gives the range.
TEST(RobotModel, ContinuousJointsSpanTwoTurnsEitherWay) {
  const std::string urdf =
      replaced(embedded("kr5_sdh.urdf"), "<joint name=\"joint_a1\" type=\"revolute\">",
               "<joint name=\"joint_a1\" type=\"continuous\">");
  const std::string yaml = embedded("kr5_sdh.yaml");
  const std::string home = "home: [0, -1.5707963267948966";
  const RobotModel m = load_robot_from_text(replaced(yaml, home, "home: [4.8, -1.5707963267948966"),
                                            urdf, "hand.yaml", "robot.urdf");
  EXPECT_DOUBLE_EQ(m.joints[0].upper, 0.5 * kContinuousRange);
  EXPECT_DOUBLE_EQ(m.joints[0].lower, -0.5 * kContinuousRange);
  EXPECT_DOUBLE_EQ(m.home[0], 4.8);
  const std::string reason =
      load_error(replaced(yaml, home, "home: [7, -1.5707963267948966"), urdf);
  EXPECT_NE(reason.find("outside its limits [-6.28319, 6.28319]"), std::string::npos) << reason;
}

// Fingers that hang directly off the arm's last link: that link is the hand's base, and the joint
// into it stays an arm joint (issue 35: a Kinova j2s7s300's fingers on j2s7s300_link_7).
TEST(RobotModel, FingersMayHangOffTheArmsLastLink) {
  const std::string urdf = embedded("kr5_sdh.urdf");
  const std::string yaml = embedded("kr5_sdh.yaml");
  const RobotModel m =
      load_robot_from_text(replaced(replaced(yaml, "base_link: sdh_base", "base_link: link_6"),
                                    "tool_link: tool0", "tool_link: link_6"),
                           urdf, "hand.yaml", "robot.urdf");
  EXPECT_EQ(m.hand_base_link, m.link_index("link_6"));
  EXPECT_EQ(m.arm_dof, 6);
  EXPECT_FALSE(m.joints[m.joint_index("joint_a6")].hand);
  EXPECT_TRUE(m.links[m.link_index("link_6")].hand);
  EXPECT_FALSE(m.links[m.link_index("link_5")].hand);
  // A hand joint above the hand's base is still refused, naming its link.
  const std::string above =
      load_error(replaced(yaml, "base_link: sdh_base", "base_link: finger_11_link"), urdf);
  EXPECT_NE(above.find("a hand joint but not below hand.base_link"), std::string::npos) << above;
}

TEST(RobotModel, EmptyCurveListIsRejected) {
  const std::string yaml = cut(embedded("kr5_sdh.yaml"), "  curves:\n", "  tcp:", "  curves: []\n");
  const std::string reason = load_error(yaml, embedded("kr5_sdh.urdf"));
  EXPECT_NE(reason.find("hand.curves: the list is empty"), std::string::npos) << reason;
}

TEST(RobotModel, FingersWithoutGeometryOrJointsAndTwoPointCurvesAreRejected) {
  const std::string urdf = embedded("kr5_sdh.urdf");
  const std::string yaml = embedded("kr5_sdh.yaml");
  const std::string finger = "links: [finger_11_link, finger_12_link, finger_13_link]";
  EXPECT_NE(load_error(replaced(yaml, finger, "links: []"), urdf)
                .find("hand.fingers[0].links: no link of the finger has collision geometry"),
            std::string::npos);
  // sdh_base carries no collision geometry of its own.
  EXPECT_NE(load_error(replaced(yaml, finger, "links: [tool0]"), urdf).find("collision geometry"),
            std::string::npos);
  EXPECT_NE(
      load_error(replaced(yaml, "joints: [finger_12_joint, finger_13_joint]", "joints: []"), urdf)
          .find("a finger needs at least one joint"),
      std::string::npos);
  // finger_1-thumb from its tip straight to the thumb's tip.
  const std::string two_points =
      cut(yaml, "        - {link: finger_13_link}", "        - {link: thumb_3_tip}", "");
  EXPECT_NE(load_error(two_points, urdf).find("a finger curve needs at least 3 points"),
            std::string::npos);
}

TEST(RobotModel, EmbeddedFilesAreListed) {
  const auto names = embedded_model_names();
  EXPECT_EQ(names.size(), 8u);
  EXPECT_EQ(embedded_model_file("nope.yaml"), nullptr);
}

}  // namespace
}  // namespace claspplan::robots
