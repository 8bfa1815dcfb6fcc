// A two-finger hand of capsules in the x-z plane of tool0 (a prismatic lift along z, the fingers
// pointing up, v_fwd = +z) and a ring (a torus) to put around, at or beside it: geometry built by
// hand for the secure-clasp check's tests.
#pragma once

#include <cmath>
#include <string>

#include <Eigen/Geometry>

#include "robots/robot_model.hpp"
#include "servo/linking.hpp"
#include "test/robots/test_meshes.hpp"

namespace claspplan::test {

inline constexpr double kFingerRadius = 0.007;
inline constexpr double kProximal = 0.04, kDistal = 0.018;  // capsule lengths (m)

// A capsule of the URDF convention: a cylinder along z from 0 to `length` with a sphere at each
// end.
inline std::string capsule(double length) {
  const std::string r = std::to_string(kFingerRadius), l = std::to_string(length);
  return "<collision><origin xyz=\"0 0 " + std::to_string(0.5 * length) +
         "\"/><geometry><cylinder radius=\"" + r + "\" length=\"" + l +
         "\"/></geometry></collision>"
         "<collision><geometry><sphere radius=\"" +
         r + "\"/></geometry></collision><collision><origin xyz=\"0 0 " + l +
         "\"/><geometry><sphere radius=\"" + r + "\"/></geometry></collision>";
}

// A finger (side +1 at +x, the thumb -1 at -x): two revolute joints about y, closing toward the
// other side; fully closed (at the limits) the tips stop 4 mm apart above the palm.
inline std::string finger(const std::string& name, int side) {
  const std::string s = side > 0 ? "" : "-";
  const std::string base = name + "_base", distal = name + "_distal";
  const auto limits = [&](double closed, double open) {
    const double lo = side > 0 ? closed : -open, hi = side > 0 ? open : -closed;
    return "<limit lower=\"" + std::to_string(lo) + "\" upper=\"" + std::to_string(hi) +
           "\" effort=\"1\" velocity=\"1\"/>";
  };
  return "<link name=\"" + base + "\">" + capsule(kProximal) + "</link><link name=\"" + distal +
         "\">" + capsule(kDistal) + "</link><link name=\"" + name + "_tip\"/>" + "<joint name=\"" +
         name + "_1\" type=\"revolute\"><parent link=\"palm\"/><child link=\"" + base +
         "\"/><origin xyz=\"" + s + "0.035 0 0.01\"/><axis xyz=\"0 1 0\"/>" + limits(-0.2, 0.4) +
         "</joint><joint name=\"" + name + "_2\" type=\"revolute\"><parent link=\"" + base +
         "\"/><child link=\"" + distal + "\"/><origin xyz=\"0 0 " + std::to_string(kProximal) +
         "\"/><axis xyz=\"0 1 0\"/>" + limits(-1.4, 0.0) + "</joint><joint name=\"" + name +
         "_tip_joint\" type=\"fixed\"><parent link=\"" + distal + "\"/><child link=\"" + name +
         "_tip\"/><origin xyz=\"0 0 " + std::to_string(kDistal) + "\"/></joint>";
}

// The hand's URDF: the lift, the palm, finger("finger", 1) and the thumb given (its URDF text).
// With `pointing_down`, base_link is turned half a turn about x: the fingers and v_fwd point to
// world -z (as a hand reaching into a container from above), x stays x.
inline std::string capsule_hand_urdf(const std::string& thumb, bool pointing_down = false) {
  return "<robot name=\"capsule_hand\"><link name=\"base_link\"/><link name=\"tool0\"/>"
         "<joint name=\"lift\" type=\"prismatic\"><parent link=\"base_link\"/><child "
         "link=\"tool0\"/>" +
         std::string(pointing_down ? "<origin rpy=\"3.141592653589793 0 0\"/>" : "") +
         "<axis xyz=\"0 0 1\"/><limit lower=\"-0.5\" upper=\"0.5\" effort=\"1\" "
         "velocity=\"1\"/></joint><link name=\"palm\"><collision><geometry><box size=\"0.08 "
         "0.03 0.02\"/></geometry></collision></link><joint name=\"palm_joint\" "
         "type=\"fixed\"><parent link=\"tool0\"/><child link=\"palm\"/></joint>" +
         finger("finger", 1) + thumb + "</robot>";
}

// The hand's URDF with one motor pair: thumb_1 and thumb_2 mimic finger_1 and finger_2 (× −1), as
// Romeo's fingers all follow LHand.
inline std::string one_motor_hand_urdf() {
  std::string thumb = finger("thumb", -1);
  for (const char* j : {"thumb_1", "thumb_2"}) {
    const std::size_t at = thumb.find("</joint>", thumb.find("name=\"" + std::string(j) + "\""));
    thumb.insert(at,
                 "<mimic joint=\"finger_" + std::string(j).substr(6) + "\" multiplier=\"-1\"/>");
  }
  return capsule_hand_urdf(thumb);
}

// The hand's description: `joints` its hand joints' entries (YAML flow maps, one per line), the
// thumb moved by `thumb_joints` ("[thumb_1, thumb_2]").
inline std::string capsule_hand_yaml(const std::string& name, const std::string& joints,
                                     const std::string& thumb_joints) {
  return "name: " + name + "\nurdf: " + name +
         ".urdf\narm: {joints: [lift], home: [0], tool_link: tool0}\nhand:\n  base_link: palm\n"
         "  joints:\n" +
         joints +
         "  fingers:\n"
         "    - {name: finger, joints: [finger_1, finger_2], links: [finger_base, finger_distal]}\n"
         "    - {name: thumb, thumb: true, joints: " +
         thumb_joints + R"(, links: [thumb_base, thumb_distal]}
  curves:
    - name: finger-thumb
      points: [{link: finger_tip}, {link: finger_distal}, {link: finger_base}, {link: palm},
               {link: thumb_base}, {link: thumb_distal}, {link: thumb_tip}]
  tcp: {link: palm, xyz: [0, 0, 0.03]}
  v_fwd: {link: tool0, vector: [0, 0, 1]}
  v_swd: {link: tool0, vector: [0, 1, 0]}
  vlink_goal: 0.8
)";
}

inline robots::RobotModel capsule_hand(bool pointing_down = false) {
  const std::string urdf = capsule_hand_urdf(finger("thumb", -1), pointing_down);
  const std::string yaml = capsule_hand_yaml("capsule_hand",
                                             "    - {name: finger_1, open: 0.4, closing: -1}\n"
                                             "    - {name: finger_2, open: 0.0, closing: -1}\n"
                                             "    - {name: thumb_1, open: -0.4, closing: 1}\n"
                                             "    - {name: thumb_2, open: 0.0, closing: 1}\n",
                                             "[thumb_1, thumb_2]");
  return robots::load_robot_from_text(yaml, urdf, "capsule_hand.yaml", "capsule_hand.urdf");
}

inline Eigen::VectorXd closed_hand(const robots::RobotModel& m) {
  Eigen::VectorXd q = m.home;
  for (int j = m.arm_dof; j < m.dof(); ++j)
    q[j] = m.joints[j].closing > 0 ? m.joints[j].upper : m.joints[j].lower;
  return q;
}

// A ring in the y-z plane (the closing plane's normal is y): its lowest point at `bottom`, where
// its tangent is y. Major radius 5 cm, tube radius 6 mm; `loop` is its centre line.
struct Ring {
  TriMesh mesh;
  servo::Points loop;
};

inline Ring ring_with_bottom_at(const Eigen::Vector3d& bottom) {
  constexpr double R = 0.05, r = 0.006;
  Eigen::Isometry3d pose = Eigen::Isometry3d::Identity();
  pose.translate(bottom + Eigen::Vector3d(0, 0, R));
  pose.rotate(Eigen::AngleAxisd(M_PI / 2, Eigen::Vector3d::UnitY()));  // its axis along x
  Ring ring;
  ring.mesh = torus_mesh(R, r, 64, 12);
  for (auto& v : ring.mesh.vertices) v = pose * v;
  for (int i = 0; i < 48; ++i) {
    const double u = 2.0 * M_PI * i / 48;
    ring.loop.push_back(pose * Eigen::Vector3d(R * std::cos(u), R * std::sin(u), 0));
  }
  return ring;
}

}  // namespace claspplan::test
