// The secure-clasp check and finger closing on geometry built here, not on the planner's output:
// a two-finger hand of capsules in the x-z plane of tool0 and a ring (a torus) put around, at or
// beside it by hand.
#include <gtest/gtest.h>

#include "robots/kinematics.hpp"
#include "robots/robot_model.hpp"
#include "test/robots/test_meshes.hpp"
#include "tsrrt/clasp_planning.hpp"

namespace claspplan::tsrrt {
namespace {

constexpr double kFingerRadius = 0.007;
constexpr double kProximal = 0.04, kDistal = 0.018;  // capsule lengths (m)

// A capsule of the URDF convention: a cylinder along z from 0 to `length` with a sphere at each
// end.
std::string capsule(double length) {
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
std::string finger(const std::string& name, int side) {
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

robots::RobotModel capsule_hand() {
  const std::string urdf =
      "<robot name=\"capsule_hand\"><link name=\"base_link\"/><link name=\"tool0\"/>"
      "<joint name=\"lift\" type=\"prismatic\"><parent link=\"base_link\"/><child "
      "link=\"tool0\"/><axis xyz=\"0 0 1\"/><limit lower=\"-0.5\" upper=\"0.5\" effort=\"1\" "
      "velocity=\"1\"/></joint><link name=\"palm\"><collision><geometry><box size=\"0.08 0.03 "
      "0.02\"/></geometry></collision></link><joint name=\"palm_joint\" type=\"fixed\"><parent "
      "link=\"tool0\"/><child link=\"palm\"/></joint>" +
      finger("finger", 1) + finger("thumb", -1) + "</robot>";
  const std::string yaml = R"(name: capsule_hand
urdf: capsule_hand.urdf
arm: {joints: [lift], home: [0], tool_link: tool0}
hand:
  base_link: palm
  joints:
    - {name: finger_1, open: 0.4, closing: -1}
    - {name: finger_2, open: 0.0, closing: -1}
    - {name: thumb_1, open: -0.4, closing: 1}
    - {name: thumb_2, open: 0.0, closing: 1}
  fingers:
    - {name: finger, joints: [finger_1, finger_2], links: [finger_base, finger_distal]}
    - {name: thumb, thumb: true, joints: [thumb_1, thumb_2], links: [thumb_base, thumb_distal]}
  curves:
    - name: finger-thumb
      points:
        - {link: finger_tip}
        - {link: finger_distal}
        - {link: finger_base}
        - {link: palm}
        - {link: thumb_base}
        - {link: thumb_distal}
        - {link: thumb_tip}
  tcp: {link: palm, xyz: [0, 0, 0.03]}
  v_fwd: {link: tool0, vector: [0, 0, 1]}
  v_swd: {link: tool0, vector: [0, 1, 0]}
  vlink_goal: 0.8
)";
  return robots::load_robot_from_text(yaml, urdf, "capsule_hand.yaml", "capsule_hand.urdf");
}

Eigen::VectorXd closed_hand(const robots::RobotModel& m) {
  Eigen::VectorXd q = m.home;
  for (int j = m.arm_dof; j < m.dof(); ++j)
    q[j] = m.joints[j].closing > 0 ? m.joints[j].upper : m.joints[j].lower;
  return q;
}

// A ring in the y-z plane (the closing plane's normal is y): its lowest point at `bottom`, where
// its tangent is y. Major radius 5 cm, tube radius 6 mm; `loop` is its centre line.
struct Ring {
  test::TriMesh mesh;
  servo::Points loop;
};

Ring ring_with_bottom_at(const Eigen::Vector3d& bottom) {
  constexpr double R = 0.05, r = 0.006;
  Eigen::Isometry3d pose = Eigen::Isometry3d::Identity();
  pose.translate(bottom + Eigen::Vector3d(0, 0, R));
  pose.rotate(Eigen::AngleAxisd(M_PI / 2, Eigen::Vector3d::UnitY()));  // its axis along x
  Ring ring;
  ring.mesh = test::torus_mesh(R, r, 64, 12);
  for (auto& v : ring.mesh.vertices) v = pose * v;
  for (int i = 0; i < 48; ++i) {
    const double u = 2.0 * M_PI * i / 48;
    ring.loop.push_back(pose * Eigen::Vector3d(R * std::cos(u), R * std::sin(u), 0));
  }
  return ring;
}

SecureClaspReport check(const robots::RobotModel& m, const Ring& ring, const Eigen::VectorXd& q) {
  SecureClaspOptions o;
  o.sequences = 6;
  o.motions = 300;
  o.threads = 1;
  return check_secure_clasp(m, ring.mesh.vertices, ring.mesh.triangles, q, ring.loop, o);
}

TEST(SecureClaspCheck, RingInsideTheClosedHandIsSecure) {
  const robots::RobotModel m = capsule_hand();
  // The ring's tube passes between the palm (top z = 0.01) and the closed fingers (distal links
  // from z = 0.041 up): 1 cm of room either way; the fingertips' gap (4 mm) is narrower than it.
  const SecureClaspReport r = check(m, ring_with_bottom_at({0, 0, 0.026}), closed_hand(m));
  EXPECT_FALSE(r.start_in_collision);
  EXPECT_TRUE(r.secure);
  EXPECT_EQ(r.escaped_sequences, 0);
  EXPECT_EQ(r.sequences, 6);
  ASSERT_EQ(r.virtual_linking.size(), 1u);
  EXPECT_GT(r.virtual_linking[0], 0.5);  // the finger curve closed by its short cord links it
}

TEST(SecureClaspCheck, RingNotEnclosedIsNotSecure) {
  const robots::RobotModel m = capsule_hand();
  const struct {
    const char* what;
    Eigen::Vector3d ring_bottom;
    Eigen::VectorXd q;
  } cases[] = {
      // The same closed hand; the ring's tube (6 mm) rests 2 mm above the fingertips (7 mm
      // capsules whose axes end at z = 0.0487), outside the fist.
      {"at the fingertips", {0, 0, 0.0487 + 0.007 + 0.006 + 0.002}, closed_hand(m)},
      {"beside the open hand", {0.12, 0, 0.02}, m.home},
      // Where the closed hand holds it, but the fingers are open: nothing keeps it.
      {"through the open hand", {0, 0, 0.026}, m.home},
  };
  for (const auto& c : cases) {
    const SecureClaspReport r = check(m, ring_with_bottom_at(c.ring_bottom), c.q);
    EXPECT_FALSE(r.start_in_collision) << c.what;
    EXPECT_FALSE(r.secure) << c.what;
    EXPECT_EQ(r.escaped_sequences, r.sequences) << c.what;
  }
}

// Distance from a finger link's capsule to an axis-aligned box (sampled along the capsule's axis,
// 0.1 mm apart), computed here without FCL.
double capsule_box_distance(const robots::RobotData& data, int link, double length,
                            const Eigen::AlignedBox3d& box) {
  double best = std::numeric_limits<double>::infinity();
  for (int k = 0; k <= 400; ++k) {
    const Eigen::Vector3d p = data.link_poses[link] * Eigen::Vector3d(0, 0, length * k / 400.0);
    best = std::min(best, box.exteriorDistance(p));
  }
  return best - kFingerRadius;
}

TEST(FingerClosing, StopsAtTheClearanceAgainstAPlate) {
  const robots::RobotModel m = capsule_hand();
  // A 12 mm plate standing between finger and thumb: fully closed, both tips would be inside it.
  const Eigen::AlignedBox3d plate(Eigen::Vector3d(-0.006, -0.04, 0.03),
                                  Eigen::Vector3d(0.006, 0.04, 0.12));
  test::TriMesh box;
  for (int c = 0; c < 8; ++c)
    box.vertices.push_back(plate.corner(Eigen::AlignedBox3d::CornerType(c)));
  // Corner c has bit 0 for x, bit 1 for y, bit 2 for z; two triangles per face.
  const int faces[6][4] = {{0, 2, 6, 4}, {1, 5, 7, 3}, {0, 4, 5, 1},
                           {2, 3, 7, 6}, {0, 1, 3, 2}, {4, 6, 7, 5}};
  for (const auto& f : faces) {
    box.triangles.emplace_back(f[0], f[1], f[2]);
    box.triangles.emplace_back(f[0], f[2], f[3]);
  }
  robots::CollisionWorld world(m);
  world.set_object(box.vertices, box.triangles);
  robots::RobotData data(m);
  const Eigen::VectorXd closed = closed_hand(m);
  for (const double clearance : {0.002, 0.008}) {
    FingerClosingOptions o;
    o.clearance = clearance;
    const Eigen::VectorXd q = close_fingers(m, world, m.home, o);
    robots::forward_kinematics(m, q, data);
    for (const std::string name : {"finger", "thumb"}) {
      const int distal = m.link_index(name + "_distal");
      const double gap = capsule_box_distance(data, distal, kDistal, plate);
      // Never nearer than the clearance; at most one closing step (0.01 rad on each joint moves
      // the tip by < 1 mm) farther.
      EXPECT_GE(gap, clearance - 2e-4) << name << " at clearance " << clearance;
      EXPECT_LE(gap, clearance + 1e-3) << name << " at clearance " << clearance;
      // Stopped by the plate, not by its joint limits.
      const int j = m.joint_index(name + "_2");
      EXPECT_GT(std::abs(q[j] - closed[j]), 0.05) << name;
      EXPECT_GT(std::abs(q[j] - m.home[j]), 0.05) << name;
    }
  }
}

}  // namespace
}  // namespace claspplan::tsrrt
