// The collision world: boxes, meshes, self-collision, per-link queries and interpolated motions.
#include <algorithm>
#include <cmath>
#include <random>
#include <string>

#include <gtest/gtest.h>

#include "robots/collision_world.hpp"
#include "test/robots/test_meshes.hpp"
#include "test/support/wire_sweep.hpp"

namespace claspplan::robots {
namespace {

constexpr double kDeg = M_PI / 180.0;

Eigen::Isometry3d at(double x, double y, double z) {
  Eigen::Isometry3d t = Eigen::Isometry3d::Identity();
  t.translation() = Eigen::Vector3d(x, y, z);
  return t;
}

// A bar (closed cylinder mesh) along world y, centred at (x, 0, z).
Eigen::Isometry3d bar_pose(double x, double z) {
  Eigen::Isometry3d t = at(x, 0, z);
  t.linear() = Eigen::AngleAxisd(M_PI / 2, Eigen::Vector3d::UnitX()).toRotationMatrix();
  return t;
}

TEST(Collision, NoSelfCollisionAtHomeWithTheHandOpen) {
  for (const std::string& name : builtin_robots()) {
    const RobotModel m = load_robot(name);
    CollisionWorld world(m);
    CollisionReport report;
    EXPECT_FALSE(world.in_collision(m.home, &report))
        << name << ": " << report.first << " / " << report.second;
    EXPECT_TRUE(report.first.empty());
    EXPECT_GT(world.self_collision_pairs().size(), 50u) << name;
  }
}

TEST(Collision, SelfCollisionPairsExcludeAdjacentRigidAndAllowedLinks) {
  const RobotModel m = load_robot("kr5_sdh");
  CollisionWorld world(m);
  const auto pairs = world.self_collision_pairs();
  auto has = [&](const std::string& a, const std::string& b) {
    int i = m.link_index(a), j = m.link_index(b);
    if (i > j) std::swap(i, j);
    return std::find(pairs.begin(), pairs.end(), std::make_pair(i, j)) != pairs.end();
  };
  EXPECT_FALSE(has("link_1", "link_2"));                // joined by joint_a2
  EXPECT_FALSE(has("link_6", "sdh_base"));              // through flange and tool0 (no geometry)
  EXPECT_FALSE(has("sdh_palm_link", "thumb_1_link"));   // never move relative to each other
  EXPECT_FALSE(has("finger_11_link", "thumb_1_link"));  // knuckle held: rigid too
  EXPECT_FALSE(has("link_4", "link_6"));                // collision.allowed_pairs
  EXPECT_FALSE(has("base_link", "link_2"));             // collision.allowed_pairs
  EXPECT_TRUE(has("base_link", "link_3"));
  EXPECT_TRUE(has("link_4", "sdh_base"));
  EXPECT_TRUE(has("finger_12_link", "thumb_1_link"));
  EXPECT_TRUE(has("finger_13_link", "thumb_3_link"));
  world.set_hand_self_collision(false);
  EXPECT_FALSE(world.self_collision_pairs().empty());
  for (const auto& [a, b] : world.self_collision_pairs())
    EXPECT_FALSE(m.links[a].hand && m.links[b].hand);
  world.set_self_collision(false);
  EXPECT_TRUE(world.self_collision_pairs().empty());
}

TEST(Collision, KnownSelfCollisions) {
  const RobotModel m = load_robot("kr5_sdh");
  CollisionWorld world(m);
  CollisionReport report;
  // Upper arm far back, forearm folded onto it.
  Eigen::VectorXd folded = m.home;
  folded.head(6) << 0, -150 * kDeg, 160 * kDeg, 0, 0, 0;
  EXPECT_TRUE(world.in_collision(folded, &report));
  EXPECT_EQ(report.first, "link_1");
  EXPECT_EQ(report.second, "link_3");
  // Finger 1's proximal link flexed onto the thumb's base.
  Eigen::VectorXd fist = m.home;
  fist[m.joint_index("finger_12_joint")] = 1.5;
  EXPECT_TRUE(world.in_collision(fist, &report));
  EXPECT_EQ(report.first, "finger_12_link");
  EXPECT_EQ(report.second, "thumb_1_link");
  EXPECT_GE(report.second_link, 0);
  world.set_hand_self_collision(false);
  EXPECT_FALSE(world.in_collision(fist));
  EXPECT_TRUE(world.in_collision(folded));
  world.set_self_collision(false);
  EXPECT_FALSE(world.in_collision(folded));
}

// Both at once (the arm folded and the finger flexed): self_contacts lists every pair, each once,
// where in_collision reports the first.
TEST(Collision, SelfContactsListsEveryPairAtOnce) {
  const RobotModel m = load_robot("kr5_sdh");
  CollisionWorld world(m);
  Eigen::VectorXd q = m.home;
  q.head(6) << 0, -150 * kDeg, 160 * kDeg, 0, 0, 0;
  q[m.joint_index("finger_12_joint")] = 1.5;
  RobotData data(m);
  forward_kinematics(m, q, data);
  const auto pairs = world.self_contacts(data);
  const auto has = [&](const std::string& a, const std::string& b) {
    return std::count(pairs.begin(), pairs.end(), std::make_pair(a, b)) == 1;
  };
  EXPECT_TRUE(has("link_1", "link_3"));
  EXPECT_TRUE(has("finger_12_link", "thumb_1_link"));
  forward_kinematics(m, m.home, data);
  EXPECT_TRUE(world.self_contacts(data).empty());
}

TEST(Collision, Boxes) {
  const RobotModel m = load_robot("kr5_sdh");
  CollisionWorld world(m);
  CollisionReport report;
  // At HOME the open SDH reaches from x 0.58 to 0.78 around z 0.79.
  world.add_box(at(1.2, 0, 0.79), {0.1, 0.1, 0.1});
  EXPECT_FALSE(world.in_collision(m.home, &report));
  world.add_box(at(0.80, 0.0, 0.70), {0.05, 0.2, 0.02});  // under finger tips 1 and 2
  EXPECT_TRUE(world.in_collision(m.home, &report));
  EXPECT_EQ(report.second, "box 1");
  EXPECT_TRUE(report.first == "finger_13_link" || report.first == "finger_23_link") << report.first;
  // Where they touch: on the box (FCL's contact, or the middle of the boxes' overlap).
  const Eigen::AlignedBox3d box_1(Eigen::Vector3d(0.775, -0.1, 0.69),
                                  Eigen::Vector3d(0.825, 0.1, 0.71));
  const Eigen::Vector3d on_box = world.contact_point(world.environment_hit());
  EXPECT_LE(box_1.exteriorDistance(on_box), 0.01) << on_box.transpose();
  // The same for space no sensor saw: 5 mm voxels of the box's top layer.
  world.clear_environment();
  std::vector<Eigen::Vector3d> voxels;
  for (double x = 0.7775; x < 0.825; x += 0.005)
    for (double y = -0.0975; y < 0.1; y += 0.005) voxels.emplace_back(x, y, 0.7075);
  world.add_voxels(voxels, 0.005);
  EXPECT_TRUE(world.in_collision(m.home, &report));
  EXPECT_EQ(report.second, "unseen space");
  const EnvironmentHit hit = world.environment_hit();
  // A kept hit gives its point after later queries have moved the shapes.
  Eigen::VectorXd turned = m.home;
  turned[0] += 0.5;  // the base turned: the hand 0.37 m to the side
  EXPECT_FALSE(world.in_collision(turned));
  EXPECT_LT(world.environment_hit().shape, 0) << "no hit: nothing touched";
  const Eigen::Vector3d on_voxels = world.contact_point(hit);
  EXPECT_LE(box_1.exteriorDistance(on_voxels), 0.01) << on_voxels.transpose();
  // The same voxels holding measured points the object's mesh leaves out are the object's
  // material, not unseen space; a shape through both met the material first.
  world.clear_environment();
  world.add_voxels(voxels, 0.005, CollisionWorld::VoxelKind::kMeasured);
  EXPECT_TRUE(world.in_collision(m.home, &report));
  EXPECT_EQ(report.second, "object");
  world.add_voxels(voxels, 0.005);
  EXPECT_TRUE(world.in_collision(m.home, &report));
  EXPECT_EQ(report.second, "object");
  world.clear_environment();
  EXPECT_FALSE(world.in_collision(m.home));
  // A table the base stands in: the base never moves, so it is not checked.
  world.add_box(at(0, 0, -0.02), {2.0, 2.0, 0.05});
  EXPECT_FALSE(world.in_collision(m.home));
  // ... but the arm reaching into it is.
  Eigen::VectorXd down = m.home;
  down.head(6) << 0, 20 * kDeg, 40 * kDeg, 0, 0, 0;
  EXPECT_TRUE(world.in_collision(down, &report)) << report.first;
  world.add_cylinder(at(0.7, 0, 0.79), 0.02, 0.3);
  EXPECT_TRUE(world.in_collision(m.home, &report));
  EXPECT_EQ(report.second, "cylinder 0");
  EXPECT_THROW(world.add_box(at(0, 0, 0), {0.1, -0.1, 0.1}), std::invalid_argument);
  EXPECT_THROW(world.add_cylinder(at(0, 0, 0), std::nan(""), 0.1), std::invalid_argument);
}

TEST(Collision, MeshObjectAndItsPose) {
  const RobotModel m = load_robot("kr5_sdh");
  CollisionWorld world(m);
  const test::TriMesh bar = test::bar_mesh(0.01, 0.3, 32);
  world.set_object(bar.vertices, bar.triangles);
  EXPECT_EQ(world.object_triangles(), 4 * 32);
  CollisionReport report;
  // Between the open fingers and the thumb: free.
  world.set_object_pose(bar_pose(0.70, 0.80));
  EXPECT_FALSE(world.in_collision(m.home, &report)) << report.first;
  // Through the palm.
  world.set_object_pose(bar_pose(0.62, 0.79));
  EXPECT_TRUE(world.in_collision(m.home, &report));
  EXPECT_EQ(report.second, "object");
  EXPECT_EQ(report.first, "sdh_palm_link");
  EXPECT_LT(world.environment_hit().shape, 0) << "a hit only for the environment";
  EXPECT_TRUE(world.contact_point(world.environment_hit()).hasNaN());
  // Far away.
  world.set_object_pose(bar_pose(1.5, 0.5));
  EXPECT_FALSE(world.in_collision(m.home));
  world.clear_object();
  EXPECT_FALSE(world.has_object());
  // A ring (torus mesh, axis along world x) around the thumb's distal link, which runs along world
  // x at z 0.901: free; shifted sideways by its radius, its tube cuts the thumb.
  const test::TriMesh ring = test::torus_mesh(0.05, 0.008, 48, 16);
  world.set_object(ring.vertices, ring.triangles);
  Eigen::Isometry3d ring_pose = at(0.75, 0.0, 0.901);
  ring_pose.linear() = Eigen::AngleAxisd(M_PI / 2, Eigen::Vector3d::UnitY()).toRotationMatrix();
  world.set_object_pose(ring_pose);
  EXPECT_FALSE(world.in_collision(m.home, &report)) << report.first;
  ring_pose.translation().y() = 0.05;
  world.set_object_pose(ring_pose);
  EXPECT_TRUE(world.in_collision(m.home, &report));
  EXPECT_EQ(report.first, "thumb_3_link");
}

// Unseen voxels fill a seen object's inside (no camera sees behind its surface): a shape through
// both met the object first, and says so, or a search's contacts with the object would read as
// space no sensor saw (and ask for a camera that cannot see inside the object).
TEST(Collision, AShapeThroughTheSeenSurfaceTouchesTheObjectNotTheUnseenSpaceBehindIt) {
  const RobotModel m = load_robot("kr5_sdh");
  CollisionWorld world(m);
  const test::TriMesh bar = test::bar_mesh(0.01, 0.3, 32);
  world.set_object(bar.vertices, bar.triangles);
  world.set_object_pose(bar_pose(0.62, 0.79));  // through the palm
  std::vector<Eigen::Vector3d> inside;          // 5 mm voxels within the bar's 1 cm radius
  for (double x = 0.6125; x < 0.63; x += 0.005)
    for (double y = -0.1475; y < 0.15; y += 0.005)
      for (double z = 0.7825; z < 0.80; z += 0.005)
        if (std::hypot(x - 0.62, z - 0.79) < 0.009) inside.emplace_back(x, y, z);
  world.add_voxels(inside, 0.005);
  CollisionReport report;
  EXPECT_TRUE(world.in_collision(m.home, &report));
  EXPECT_EQ(report.second, "object");
  EXPECT_EQ(report.first, "sdh_palm_link");
  EXPECT_LT(world.environment_hit().shape, 0) << "no hit of unseen space";
  RobotData data(m);
  forward_kinematics(m, m.home, data);
  EXPECT_TRUE(world.link_in_collision(data, m.link_index("sdh_palm_link"), &report));
  EXPECT_EQ(report.second, "object");
  // The same voxels without the seen surface in front of them: unseen space.
  world.clear_object();
  EXPECT_TRUE(world.in_collision(m.home, &report));
  EXPECT_EQ(report.second, "unseen space");
  EXPECT_EQ(report.first, "sdh_palm_link");
}

// The secure-clasp check's query: the object part of in_collision, at many object poses against a
// few configurations, asked in an order that makes it reuse and then replace its placed shapes.
TEST(Collision, ObjectQueryAgreesWithTheFullCheck) {
  const RobotModel m = load_robot("kr5_sdh");
  const test::TriMesh ring = test::torus_mesh(0.05, 0.008, 48, 16);
  CollisionWorld full(m), object_only(m);
  for (CollisionWorld* w : {&full, &object_only}) {
    w->set_self_collision(false);
    w->set_object(ring.vertices, ring.triangles);
  }
  std::mt19937_64 rng(3);
  std::uniform_real_distribution<double> shift(-0.04, 0.04), close(0.0, 0.8);
  int hits = 0, trials = 0;
  for (int c = 0; c < 4; ++c) {
    Eigen::VectorXd q = m.home;
    for (int i = m.arm_dof; i < m.dof(); ++i) q[i] += close(rng);
    RobotData data(m);
    forward_kinematics(m, m.clamp(q), data);
    for (int k = 0; k < 100; ++k, ++trials) {
      Eigen::Isometry3d pose = at(0.75 + shift(rng), shift(rng), 0.85 + shift(rng));
      pose.linear() = Eigen::AngleAxisd(M_PI / 2, Eigen::Vector3d::UnitY()).toRotationMatrix();
      full.set_object_pose(pose);
      object_only.set_object_pose(pose);
      const bool expected = full.in_collision(data);
      EXPECT_EQ(object_only.object_in_collision(data), expected) << c << " " << k;
      hits += expected;
      // A per-link query in between places some shapes anew: the next answer must not change.
      if (k % 10 == 0) object_only.link_in_collision(data, static_cast<int>(m.links.size()) - 1);
    }
  }
  EXPECT_GT(hits, trials / 10);
  EXPECT_LT(hits, trials * 9 / 10);
}

TEST(Collision, ClosingFingersUntilContact) {
  const RobotModel m = load_robot("kr5_sdh");
  CollisionWorld world(m);
  const test::TriMesh bar = test::bar_mesh(0.01, 0.3, 32);
  world.set_object(bar.vertices, bar.triangles);
  world.set_object_pose(bar_pose(0.70, 0.80));
  RobotData d(m);
  const int thumb = m.link_index("thumb_2_link");
  const int joint = m.joint_index("thumb_2_joint");
  Eigen::VectorXd q = m.home;
  forward_kinematics(m, q, d);
  double previous = world.link_object_distance(d, thumb, 0.2);
  EXPECT_GT(previous, 0.01);
  EXPECT_LT(previous, 0.03);
  EXPECT_DOUBLE_EQ(world.link_object_distance(d, thumb, 0.005), 0.005);  // capped
  EXPECT_TRUE(world.link_near_object(d, thumb, previous + 0.001));
  EXPECT_FALSE(world.link_near_object(d, thumb, previous - 0.001));
  EXPECT_FALSE(world.link_in_collision(d, thumb));
  const double start = previous;
  bool touched = false;
  for (int step = 0; step < 200 && !touched; ++step) {
    q[joint] += 0.01;
    forward_kinematics(m, q, d);
    touched = world.link_in_collision(d, thumb) || world.link_in_collision(d, thumb + 1);
    const double now = world.link_object_distance(d, thumb, 0.2);
    if (!touched) {
      EXPECT_LE(now, previous + 1e-4);  // GJK's tolerance: about constant while the joint's sphere
    }                                   // is nearest, then falling
    if (world.link_in_collision(d, thumb)) {
      EXPECT_EQ(now, 0.0);
    }
    previous = now;
  }
  EXPECT_TRUE(touched);
  EXPECT_LT(previous, start - 0.005);
  EXPECT_LT(q[joint], 1.0);
  // With include_self, a finger pressed onto the thumb's base counts too.
  Eigen::VectorXd fist = m.home;
  fist[m.joint_index("finger_12_joint")] = 1.5;
  forward_kinematics(m, fist, d);
  CollisionReport report;
  const int f12 = m.link_index("finger_12_link");
  world.clear_object();
  EXPECT_FALSE(world.link_in_collision(d, f12, &report));
  EXPECT_TRUE(world.link_in_collision(d, f12, &report, true));
  EXPECT_EQ(report.second, "thumb_1_link");
}

TEST(Collision, MotionThroughAnObstacleIsRefused) {
  const RobotModel m = load_robot("kr5_icub");
  CollisionWorld world(m);
  world.add_box(at(0.65, 0.0, 0.79), {0.04, 0.04, 0.3});  // a post among the fingers at HOME
  Eigen::VectorXd q0 = m.home, q1 = m.home;
  q0[0] = 40 * kDeg;
  q1[0] = -40 * kDeg;
  ASSERT_FALSE(world.in_collision(q0));
  ASSERT_FALSE(world.in_collision(q1));
  CollisionReport report;
  EXPECT_FALSE(world.motion_free(q0, q1, 0.01, &report));
  EXPECT_EQ(report.second, "box 0");
  EXPECT_FALSE(world.motion_free(q0, q1, 0.001));
  // Beside the post the same sweep of a shorter arc is free.
  q1[0] = 20 * kDeg;
  EXPECT_TRUE(world.motion_free(q0, q1, 0.01, &report));
  EXPECT_TRUE(report.first.empty());
  EXPECT_TRUE(world.motion_free(q0, q0, 0.01));
  EXPECT_THROW(world.motion_free(q0, q1, 0.0), std::invalid_argument);
  EXPECT_THROW(world.motion_free(q0, Eigen::VectorXd::Zero(3), 0.01), std::invalid_argument);
}

TEST(Collision, AWireBetweenTwoCheckedConfigurationsIsFoundByTheTravelBound) {
  const RobotModel m = load_robot("kr5_icub");
  CollisionWorld world(m);
  const auto [q0, q1] = claspplan::test::add_wire_across_sweep(world, m);
  ASSERT_TRUE(world.in_collision(m.home));
  ASSERT_FALSE(world.in_collision(q0));
  ASSERT_FALSE(world.in_collision(q1));
  EXPECT_TRUE(world.motion_free(q0, q1, 0.2));
  world.set_motion_travel(0.005);
  CollisionReport report;
  EXPECT_FALSE(world.motion_free(q0, q1, 0.2, &report));
  EXPECT_EQ(report.second, "box 0");
  world.set_motion_travel(0.0);
  EXPECT_TRUE(world.motion_free(q0, q1, 0.2));
  // A bound given to the one check, the world's left as it was.
  EXPECT_FALSE(world.motion_free(q0, q1, 0.2, 0.005));
  EXPECT_EQ(world.motion_travel(), 0.0);
  EXPECT_THROW(world.motion_free(q0, q1, 0.2, -0.001), std::invalid_argument);
  EXPECT_THROW(world.set_motion_travel(-0.001), std::invalid_argument);
  EXPECT_THROW(world.set_motion_travel(std::nan("")), std::invalid_argument);
}

TEST(Collision, BadInput) {
  const RobotModel m = load_robot("kr5_armar3");
  CollisionWorld world(m);
  EXPECT_THROW(world.set_object({}, {}), std::invalid_argument);
  EXPECT_THROW(world.set_object({{0, 0, 0}, {1, 0, 0}, {0, 1, 0}}, {{0, 1, 3}}),
               std::invalid_argument);
  EXPECT_THROW(world.set_object({{0, 0, 0}, {1, 0, std::nan("")}, {0, 1, 0}}, {{0, 1, 2}}),
               std::invalid_argument);
  EXPECT_THROW(world.set_object({{0, 0, 0}, {1, 0, 0}, {0, 1, 0}}, {{0, 1, 1}}),
               std::invalid_argument);
  Eigen::VectorXd q = m.home;
  q[3] = std::nan("");
  EXPECT_THROW(world.in_collision(q), std::invalid_argument);
  EXPECT_THROW(world.in_collision(Eigen::VectorXd::Zero(4)), std::invalid_argument);
  RobotData other(load_robot("kr5_sdh"));
  EXPECT_THROW(world.in_collision(other), std::invalid_argument);
}

}  // namespace
}  // namespace claspplan::robots
