// The secure-clasp check and finger closing on geometry built here, not on the planner's output:
// a two-finger hand of capsules in the x-z plane of tool0 and a ring (a torus) put around, at or
// beside it by hand.
#include <gtest/gtest.h>

#include "robots/kinematics.hpp"
#include "robots/robot_model.hpp"
#include "test/robots/test_meshes.hpp"
#include "test/support/capsule_hand.hpp"
#include "tsrrt/finger_closing.hpp"
#include "tsrrt/secure_clasp.hpp"

namespace claspplan::tsrrt {
namespace {

using test::capsule_hand;
using test::closed_hand;
using test::kDistal;
using test::kFingerRadius;
using test::Ring;
using test::ring_with_bottom_at;

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
