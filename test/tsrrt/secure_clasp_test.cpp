// tsrrt::check_secure_clasp (exact round shapes, rounds with an early stop, all cores) gives the
// reference check's verdict (test/support/reference_secure_clasp.hpp: the check as first
// written) on final poses of planned purse clasps, as planned and perturbed: fingers opened,
// the object shifted. Both verdicts occur among them.
#include <gtest/gtest.h>

#include "test/support/purse_request.hpp"
#include "test/support/reference_secure_clasp.hpp"
#include "tsrrt/secure_clasp_detail.hpp"

namespace claspplan::test {
namespace {

struct Pose {
  std::string name;
  std::shared_ptr<const robots::RobotModel> robot;
  Eigen::VectorXd q;
  std::vector<Eigen::Vector3d> vertices;
  std::vector<Eigen::Vector3i> triangles;
  servo::Points loop;
};

// The planned clasp, its fingers opened by `open` rad, its object shifted by `shift`.
Pose perturbed(const tsrrt::ClaspRequest& request, const tsrrt::ClaspResult& r, double open,
               const Eigen::Vector3d& shift) {
  Pose p{request.robot->name,        request.robot,
         r.motion.final_q,           r.collision_mesh.vertices,
         r.collision_mesh.triangles, r.chosen_loop()->points};
  for (const robots::Finger& f : p.robot->fingers)
    for (int j : f.joints) p.q[j] -= p.robot->joints[j].closing * open;
  p.q = p.robot->clamp(p.q);
  for (auto& v : p.vertices) v += shift;
  for (auto& v : p.loop) v += shift;
  return p;
}

std::vector<Pose> plan_poses() {
  std::vector<Pose> poses;
  for (const char* robot : {"kr5_sdh", "kr5_icub", "kr5_armar3"}) {
    const tsrrt::ClaspRequest request = floor_request(purse(), robot, 1);
    const tsrrt::ClaspResult r = tsrrt::plan_clasp(request);
    EXPECT_TRUE(r.verified) << robot << ": " << r.reason;
    if (!r.verified) continue;
    for (double open : {0.0, 0.025, 0.05, 0.075, 0.1, 0.15, 0.2, 0.25, 0.3, 0.4, 0.5, 0.6, 0.7, 0.8,
                        0.9, 1.0, 1.2})
      poses.push_back(perturbed(request, r, open, Eigen::Vector3d::Zero()));
    for (double d : {0.005, 0.01, 0.02})
      for (const Eigen::Vector3d& axis : {Eigen::Vector3d(1, 0, 0), Eigen::Vector3d(0, 1, 0),
                                          Eigen::Vector3d(0, 0, 1), Eigen::Vector3d(0, 0, -1)})
        poses.push_back(perturbed(request, r, 0.0, d * axis));
  }
  return poses;
}

const std::vector<Pose>& saved_poses() {
  static const std::vector<Pose> poses = plan_poses();
  return poses;
}

TEST(SecureClasp, SameVerdictsAsTheReferenceOnSavedPoses) {
  tsrrt::SecureClaspOptions o;
  o.sequences = 4;
  o.motions = 100;
  o.escape_stages = false;  // the reference is the random motions alone
  int secure = 0, insecure = 0, touching = 0;
  for (const Pose& p : saved_poses()) {
    const auto expected = reference_secure_clasp(*p.robot, p.vertices, p.triangles, p.q, p.loop, o);
    const auto got = tsrrt::check_secure_clasp(*p.robot, p.vertices, p.triangles, p.q, p.loop, o);
    EXPECT_EQ(got.start_in_collision, expected.start_in_collision) << p.name;
    EXPECT_EQ(got.secure, expected.secure) << p.name;
    EXPECT_EQ(got.escaped_sequences > 0, expected.escaped_sequences > 0) << p.name;
    // Where the object got free is kept for escape.png: the motion of an escaping sequence.
    EXPECT_EQ(got.escape.has_value(), got.escaped_sequences > 0) << p.name;
    if (got.escape) {
      tsrrt::SecureClaspReport scratch;
      const auto c = tsrrt::detail::clasp_check_context(*p.robot, p.q, p.loop, scratch);
      EXPECT_TRUE(tsrrt::detail::object_free(c, *got.escape, o.free_distance)) << p.name;
    }
    if (expected.start_in_collision) {
      ++touching;
    } else {
      (expected.secure ? secure : insecure)++;
    }
  }
  EXPECT_GE(secure + insecure, 50) << touching << " poses touched the object";
  EXPECT_GE(secure, 10);
  EXPECT_GE(insecure, 10);
}

// Each sequence has its own random stream and the rounds end together: one thread or three give
// the same report, escapes included.
TEST(SecureClasp, SameReportForAnyNumberOfThreads) {
  tsrrt::SecureClaspOptions o;
  o.sequences = 5;
  o.motions = 60;
  int escapes = 0;
  const auto& poses = saved_poses();
  for (std::size_t i = 0; i < poses.size(); i += 3) {
    const Pose& p = poses[i];
    o.threads = 1;
    const auto one = tsrrt::check_secure_clasp(*p.robot, p.vertices, p.triangles, p.q, p.loop, o);
    o.threads = 3;
    const auto three = tsrrt::check_secure_clasp(*p.robot, p.vertices, p.triangles, p.q, p.loop, o);
    EXPECT_EQ(one.secure, three.secure) << i;
    EXPECT_EQ(one.escaped_sequences, three.escaped_sequences) << i;
    EXPECT_EQ(one.escape_motion, three.escape_motion) << i;
    escapes += one.escaped_sequences > 0;
  }
  EXPECT_GT(escapes, 0);
}

// A caller's stop (Ctrl-C in Python) ends a check as its deadline does: not passed, timed out.
TEST(SecureClasp, AStopEndsTheCheckUnpassed) {
  const Pose& p = saved_poses().front();  // a planned clasp, as planned
  tsrrt::SecureClaspOptions o;
  o.sequences = 5;
  o.motions = 60;
  int polls = 0;
  o.stop = [&] { return ++polls < 0; };
  const auto asked = tsrrt::check_secure_clasp(*p.robot, p.vertices, p.triangles, p.q, p.loop, o);
  EXPECT_TRUE(asked.secure);
  EXPECT_GT(polls, 1);  // between the rounds and the stages
  o.stop = [] { return true; };
  const auto stopped = tsrrt::check_secure_clasp(*p.robot, p.vertices, p.triangles, p.q, p.loop, o);
  EXPECT_FALSE(stopped.secure);
  EXPECT_TRUE(stopped.timed_out);
}

// A checker keeps the object's geometry between hands: reused over the poses of one object (the
// fingers opened step by step), it reports what a fresh check of each pose reports.
TEST(SecureClasp, ACheckerReusedOverHandsReportsAsFreshChecks) {
  tsrrt::SecureClaspOptions o;
  o.sequences = 4;
  o.motions = 60;
  std::unique_ptr<tsrrt::SecureClaspChecker> checker;
  const Pose* owner = nullptr;
  int reused = 0, escapes = 0;
  for (const Pose& p : saved_poses()) {
    const bool same_object = owner && owner->robot == p.robot && owner->vertices == p.vertices;
    if (!same_object) {
      checker = std::make_unique<tsrrt::SecureClaspChecker>(*p.robot, p.vertices, p.triangles, o);
      owner = &p;
    }
    reused += same_object;
    bool screened_out = false;
    const auto got = checker->check(p.q, p.loop, &screened_out);
    const auto fresh = tsrrt::check_secure_clasp(*p.robot, p.vertices, p.triangles, p.q, p.loop, o);
    EXPECT_EQ(got.start_in_collision, fresh.start_in_collision) << p.name;
    EXPECT_EQ(got.secure, fresh.secure) << p.name;
    EXPECT_EQ(got.escaped_sequences, fresh.escaped_sequences) << p.name;
    EXPECT_EQ(got.escape_motion, fresh.escape_motion) << p.name;
    // 60 motions are within the screening's two rounds (25, then 100): every failure of the
    // random motions shows there; the escape stages come after the screening.
    EXPECT_EQ(screened_out, got.escaped_sequences > 0 || got.start_in_collision) << p.name;
    EXPECT_EQ(got.escape_stage, fresh.escape_stage) << p.name;
    escapes += fresh.escaped_sequences > 0;
  }
  EXPECT_GE(reused, 30);
  EXPECT_GT(escapes, 0);
}

}  // namespace
}  // namespace claspplan::test
