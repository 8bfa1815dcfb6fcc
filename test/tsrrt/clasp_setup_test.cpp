// The pipeline as an API (tsrrt::plan_clasp): a request built in memory, from depth views of
// procedural objects, gives a verified clasp with all result fields; a cup without a handle is a
// valid problem without an answer; malformed requests throw.
#include "tsrrt/clasp_setup.hpp"

#include <gtest/gtest.h>

#include "core/stopped.hpp"
#include "examples/objects.hpp"
#include "perception/depth_render.hpp"
#include "test/support/purse_request.hpp"
#include "test/support/unseen_space.hpp"
#include "tsrrt/clasp_scene.hpp"

namespace claspplan::test {
namespace {

const std::shared_ptr<const robots::RobotModel>& sdh() {
  static const auto robot =
      std::make_shared<const robots::RobotModel>(robots::load_robot("kr5_sdh"));
  return robot;
}

tsrrt::ClaspRequest request_for(const TriangleMesh& object) {
  tsrrt::ClaspRequest r = floor_request(object);
  r.robot = sdh();
  return r;
}

class PurseFromDepth : public ::testing::Test {
 protected:
  static void SetUpTestSuite() {
    result_ = new tsrrt::ClaspResult(plan_clasp(request_for(purse())));
  }
  static void TearDownTestSuite() { delete result_; }
  static inline tsrrt::ClaspResult* result_ = nullptr;
};

TEST_F(PurseFromDepth, IsAVerifiedClaspFromTheStart) {
  const tsrrt::ClaspResult& r = *result_;
  ASSERT_EQ(r.status, tsrrt::ClaspStatus::kSuccess) << r.reason;
  EXPECT_TRUE(r.succeeded());
  EXPECT_TRUE(r.verified);
  EXPECT_TRUE(r.verification.secure);
  EXPECT_EQ(r.reason, "verified clasp");
  ASSERT_GE(r.motion.waypoints.size(), 2u);
  EXPECT_EQ(r.start.size(), sdh()->dof());
  EXPECT_EQ(r.motion.waypoints.front(), r.start);
  EXPECT_EQ(r.motion.final_q, r.motion.waypoints.back());
  EXPECT_EQ(r.start.head(6), request_for(purse()).start);
  // Every waypoint is free in the world the plan was checked in.
  robots::CollisionWorld world = tsrrt::make_collision_world(*sdh(), r);
  for (const auto& q : r.motion.waypoints) EXPECT_FALSE(world.in_collision(q));
}

TEST_F(PurseFromDepth, TargetsLieOnTheChosenLoop) {
  const tsrrt::ClaspResult& r = *result_;
  const perception::Loop* loop = r.chosen_loop();
  ASSERT_NE(loop, nullptr);
  EXPECT_TRUE(loop->claspable);
  EXPECT_EQ(r.targets.size(), 9u);
  ASSERT_GE(r.motion.target, 0);
  EXPECT_LT(r.motion.target, static_cast<int>(r.targets.size()));
  double longest = 0.0;
  for (std::size_t i = 0; i < loop->points.size(); ++i)
    longest =
        std::max(longest, (loop->points[(i + 1) % loop->points.size()] - loop->points[i]).norm());
  for (const auto& g : r.targets) {
    double nearest = 1e9;
    for (const auto& p : loop->points) nearest = std::min(nearest, (p - g.point).norm());
    EXPECT_LE(nearest, longest);
    EXPECT_NEAR(g.tangent.norm(), 1.0, 1e-9);
  }
  EXPECT_GT(r.hand.finger_thickness, 0.0);
  EXPECT_GT(r.hand.closed_aperture, 0.0);
  EXPECT_FALSE(r.collision_mesh.triangles.empty());
  EXPECT_EQ(r.environment.size(), 1u);
}

TEST_F(PurseFromDepth, StatisticsTimingsAndFinalState) {
  const tsrrt::ClaspResult& r = *result_;
  const tsrrt::ClaspStatistics& s = r.statistics;
  EXPECT_GE(s.cycles, 0);
  EXPECT_LE(s.cycles, 300);
  EXPECT_GT(s.nodes, 0);
  EXPECT_GT(s.control_steps, 0);
  EXPECT_GE(s.clasp_candidates, 1);
  EXPECT_EQ(s.connect_outcomes.attempts, s.connect_outcomes.endings());
  EXPECT_GE(s.connect_outcomes.accepted, 1);
  EXPECT_EQ(static_cast<int>(s.tree_points.size()), s.nodes);
  EXPECT_EQ(s.tree_parents.size(), s.tree_points.size());
  EXPECT_FALSE(s.solution_nodes.empty());
  EXPECT_GE(s.unpruned_waypoints, 2);
  EXPECT_GT(r.timings.perception, 0.0);
  EXPECT_GT(r.timings.search, 0.0);
  EXPECT_GT(r.timings.verification, 0.0);
  EXPECT_GE(r.timings.closing, 0.0);
  EXPECT_GE(r.timings.pruning, 0.0);
  EXPECT_GE(r.final_state.virtual_linking, sdh()->vlink_goal - 1e-9);
  EXPECT_FALSE(r.final_state.finger_virtual_linking.empty());
  EXPECT_EQ(r.final_state.finger_open_linking.size(), r.final_state.finger_virtual_linking.size());
}

TEST_F(PurseFromDepth, SameRequestSameResult) {
  const tsrrt::ClaspResult again = plan_clasp(request_for(purse()));
  ASSERT_EQ(again.motion.waypoints.size(), result_->motion.waypoints.size());
  for (std::size_t i = 0; i < again.motion.waypoints.size(); ++i)
    EXPECT_EQ(again.motion.waypoints[i], result_->motion.waypoints[i]) << "waypoint " << i;
  EXPECT_EQ(again.statistics.nodes, result_->statistics.nodes);
  EXPECT_EQ(again.final_state.virtual_linking, result_->final_state.virtual_linking);
}

// A caller's stop (a GUI's cancel, Ctrl-C in Python) ends the search where it is polled, with a
// reason that says so; a stop that never fires changes nothing.
TEST_F(PurseFromDepth, AStopEndsTheSearch) {
  tsrrt::ClaspRequest request = request_for(purse());
  int polls = 0;
  // Perception polls between its four steps; a stop there throws.
  request.stop = [&polls] { return ++polls == 2; };
  EXPECT_THROW(plan_clasp(request), Stopped);
  polls = 0;
  request.stop = [&polls] { return ++polls > 4; };  // once perception is done
  const tsrrt::ClaspResult stopped = plan_clasp(request);
  EXPECT_FALSE(stopped.succeeded());
  EXPECT_EQ(stopped.reason.rfind("search stopped by the caller", 0), 0u) << stopped.reason;
  EXPECT_EQ(polls, 5);
  request.stop = [] { return false; };
  const tsrrt::ClaspResult unstopped = plan_clasp(request);
  EXPECT_EQ(unstopped.motion.waypoints, result_->motion.waypoints);
}

// Issue 33: the planned path and the closed hand stay in space the cameras saw free (checked by
// points inside the robot's shapes against the sensed map, without the collision world).
TEST_F(PurseFromDepth, NoPartOfTheRobotEntersUnseenSpace) {
  const tsrrt::ClaspResult& r = *result_;
  ASSERT_TRUE(r.succeeded()) << r.reason;
  ASSERT_TRUE(r.object.sensed);
  const auto n = r.object.sensed->counts();
  EXPECT_GT(n[0], 0) << "the purse's inside and back are unknown";
  ASSERT_EQ(r.unseen.size(), 2u) << "the sensed map's voxels, and the finer ones near the loop";
  EXPECT_FALSE(r.unseen[0].centres.empty());
  EXPECT_FALSE(r.unseen[1].centres.empty());
  ASSERT_TRUE(r.sensed_near_loop);
  EXPECT_LT(r.unseen[1].edge, r.unseen[0].edge);
  const auto reached = first_in_unseen_space(*sdh(), r.motion.waypoints, *r.object.sensed,
                                             request_for(purse()).planning.collision_resolution,
                                             0.004, r.sensed_near_loop.get());
  EXPECT_FALSE(reached) << *reached;
}

// The check above can fail: a map without views is unknown everywhere, and the hand is in it.
TEST_F(PurseFromDepth, UnseenSpaceCheckFindsTheHandInAMapWithoutViews) {
  const tsrrt::ClaspResult& r = *result_;
  ASSERT_FALSE(r.motion.waypoints.empty());
  const perception::SensedSpace blind({}, r.object.sensed->region());
  EXPECT_TRUE(first_in_unseen_space(*sdh(), {r.motion.final_q}, blind, 0.02));
}

TEST(ClaspSetup, CupWithoutHandleIsNoAnswerWithAReason) {
  objects::Container cup;
  cup.handle_radius = 0.0;
  const tsrrt::ClaspResult r = plan_clasp(request_for(objects::container(cup)));
  EXPECT_EQ(r.status, tsrrt::ClaspStatus::kNoClaspableLoop);
  EXPECT_FALSE(r.succeeded());
  EXPECT_FALSE(r.reason.empty());
  EXPECT_EQ(r.chosen_loop(), nullptr);
  EXPECT_TRUE(r.motion.waypoints.empty());
  EXPECT_GT(r.timings.perception, 0.0);
}

// A small handle whose hole fills in at d' is not among the refused loops: the reason counts it.
TEST(ClaspSetup, NoLoopReasonCountsTheLoopsThatFilledIn) {
  perception::ObjectModel m;
  perception::Loop mouth;
  mouth.verdict = perception::LoopVerdict::kCavity;
  mouth.reason = "opening into a cavity: walls all around the passage";
  m.loops.push_back(mouth);
  m.unstable_loops = 2;
  m.persistence_d = 0.0192;
  const std::string why = tsrrt::no_loop_reason(m);
  EXPECT_EQ(why.rfind("no claspable loop: opening into a cavity", 0), 0u) << why;
  EXPECT_NE(why.find("2 more loops of K_d fill in by d' = 0.0192 m"), std::string::npos) << why;
  m.unstable_loops = 0;
  EXPECT_EQ(tsrrt::no_loop_reason(m).find("fill in"), std::string::npos);
}

// From a pose at the tree's closable tolerance, the controller goes on to the hand's linking goal
// by collision-free steps toward the same target (the third way close_and_check closes again).
TEST(ClaspSetup, DeepeningGoesOnToTheLinkingGoal) {
  tsrrt::ClaspRequest request = request_for(purse());
  int steps = -1;
  double closable = 0.0, deepened = 0.0;
  request.search = [&](const tsrrt::ClaspScene& scene, tsrrt::ClaspResult& r) {
    servo::ClaspController& c = scene.controller;
    Eigen::VectorXd q = r.start;
    servo::TaskState x = c.project(q);
    const Eigen::Vector3d target = c.targets()[x.nearest_target].point;
    for (int s = 0; s < 600 && x.linking < 0.65; ++s) {
      Eigen::VectorXd next = c.step(q, target, 1.0);
      if (!scene.world.motion_free(q, next, 0.02)) break;
      q = next;
      x = c.project(q);
    }
    closable = x.linking;
    const auto path = tsrrt::deepen_to_linking_goal(scene, q);
    steps = static_cast<int>(path.size());
    Eigen::VectorXd from = q;
    for (const auto& p : path) {
      EXPECT_TRUE(scene.world.motion_free(from, p, scene.planning.collision_resolution));
      from = p;
    }
    deepened = c.project(from).linking;
  };
  plan_clasp(request);
  ASSERT_GE(closable, 0.65) << "the controller alone did not reach the closable tolerance";
  ASSERT_LT(closable, sdh()->vlink_goal);
  EXPECT_GT(steps, 0);
  EXPECT_LE(steps, 30);
  EXPECT_GT(deepened, closable);
}

// A loop refused for the hand's room passed every other test: its reason comes first, and a
// reason shared by several loops is said once with their number.
TEST(ClaspSetup, NoLoopReasonPutsTheHandsRoomFirstAndCountsRepeats) {
  perception::ObjectModel m;
  perception::Loop wide, room;
  wide.verdict = perception::LoopVerdict::kTooNarrow;
  wide.reason = "too narrow for this hand";
  wide.hole_width = 0.08;
  room.verdict = perception::LoopVerdict::kNoRoom;
  room.reason = "no room for this hand";
  room.hole_width = 0.05;
  m.loops = {wide, room, room};
  EXPECT_EQ(tsrrt::no_loop_reason(m),
            "no claspable loop: no room for this hand (2 loops); too narrow for this hand");
}

// A closed hand is checked when its fingers keep the tree's tolerance: all of them on average,
// or all but one for a hand of three fingers or more.
TEST(ClaspSetup, ClosedHandLinksWhenAllButOneFingerDo) {
  EXPECT_TRUE(tsrrt::closed_hand_links({0.7, 0.66}, 0.65));
  EXPECT_FALSE(tsrrt::closed_hand_links({0.9, 0.0}, 0.65));  // two curves: none may miss
  EXPECT_TRUE(tsrrt::closed_hand_links({0.74, 0.79, 0.85, 0.0}, 0.65));  // one finger missed
  EXPECT_FALSE(tsrrt::closed_hand_links({0.74, 0.79, 0.85, 0.0}, 0.8));
  EXPECT_FALSE(tsrrt::closed_hand_links({0.9, 0.9, 0.0, 0.0}, 0.65));  // two missed
  EXPECT_FALSE(tsrrt::closed_hand_links({}, 0.65));

  tsrrt::ClaspPlanningOptions o;
  EXPECT_DOUBLE_EQ(tsrrt::closable_tolerance(o, 0.85), 0.65);
  EXPECT_DOUBLE_EQ(tsrrt::closable_tolerance(o, 0.6), 0.6);  // never above the goal
  o.closable_linking = 0.0;
  EXPECT_DOUBLE_EQ(tsrrt::closable_tolerance(o, 0.85), 0.85);
}

TEST(ClaspSetup, MalformedRequestsThrow) {
  tsrrt::ClaspRequest no_robot = request_for(purse());
  no_robot.robot = nullptr;
  EXPECT_THROW(plan_clasp(no_robot), std::invalid_argument);

  tsrrt::ClaspRequest too_long = request_for(purse());
  too_long.start = Eigen::VectorXd::Zero(sdh()->dof() + 1);
  EXPECT_THROW(plan_clasp(too_long), std::invalid_argument);

  // One goal for both modes, within (0, 1]: 0 no longer stands for the hand's default.
  for (const double goal : {0.0, -0.5, 1.5}) {
    tsrrt::ClaspRequest bad_goal = request_for(purse());
    bad_goal.goal_linking = goal;
    EXPECT_THROW(plan_clasp(bad_goal), InputError) << goal;
  }
  // The hand's sizes come from the robot: setting them too is a conflict, not an override.
  tsrrt::ClaspRequest sized = request_for(purse());
  sized.perception.finger_thickness = 0.02;
  EXPECT_THROW(plan_clasp(sized), InputError);

  // A box around the whole robot: the start configuration is in collision.
  tsrrt::ClaspRequest boxed = request_for(purse());
  boxed.name = "boxed";
  tsrrt::EnvironmentBox box;
  box.size = Eigen::Vector3d(3, 3, 3);
  boxed.environment.push_back(box);
  try {
    plan_clasp(boxed);
    ADD_FAILURE() << "no exception";
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("boxed: the start configuration is in collision"),
              std::string::npos)
        << e.what();
  }
}

}  // namespace
}  // namespace claspplan::test
