// The TS-RRT's view of a clasp (paper Sec. IV-D): the planning problem bound to the clasp
// controller and the collision world.
#pragma once

#include <functional>
#include <vector>

#include <Eigen/Core>

#include "robots/collision_world.hpp"
#include "servo/clasp_controller.hpp"
#include "tsrrt/problem.hpp"

namespace claspplan::tsrrt {

/// The TS-RRT's view of a clasp problem: TS-PROJECTION and TS-CONTROL from the clasp controller,
/// COLLISION-FREE from the collision world (interpolated at `resolution`; what a blocked motion
/// touches first tells the object, the environment and self-collision apart), TS-TOLERANCE on
/// virtual linking and, if `position_tolerance` > 0, also on the hand's distance to the goal.
/// The goals are the controller's clasp targets, in order (goal i is targets()[i]).
class ClaspProblem final : public PlanningProblem {
 public:
  /// `acceptance` (optional) decides on goal nodes, see PlanningProblem::accept().
  ClaspProblem(servo::ClaspController& controller, robots::CollisionWorld& world,
               double goal_linking, double position_tolerance, double resolution,
               std::function<bool(const Eigen::VectorXd&)> acceptance = {});
  TaskPoint project(const Eigen::VectorXd& q) override;
  Eigen::VectorXd control(const Eigen::VectorXd& q0, const TaskPoint& x0,
                          const TaskPoint& x1) override;
  /// The controller holds a joint that a step would push past its limit (it does not move in
  /// that step). An arm joint serves the arm tasks and the pose bias and so always moves unless
  /// held: the last step was limited when an arm joint within `kLimitMargin` of a limit did not
  /// move.
  bool control_limited() const override { return limited_; }
  MotionCheck check_motion(const Eigen::VectorXd& q0, const Eigen::VectorXd& q1) override;
  /// Also sampled so that no robot point travels more than kShortcutTravel between checks: at
  /// `resolution` alone a shortcut's fingertips, 1 m from the base, move 2 cm between checks
  /// across a shelf's edge.
  bool shortcut_free(const Eigen::VectorXd& q0, const Eigen::VectorXd& q1) override;
  bool reached(const TaskPoint& x, const TaskPoint& goal) const override;
  bool accept(const Eigen::VectorXd& q) override { return !acceptance_ || acceptance_(q); }
  /// Arm joints uniform within their limits, the hand open (its pre-shape), collision-free: up
  /// to 20 draws.
  bool sample_configuration(const std::function<std::uint64_t()>& bits,
                            Eigen::VectorXd& q) override;
  /// Detour points of clasp target p with unit tangent t (see clasp_approaches()), at
  /// approach_distance() from p.
  std::vector<TaskPoint> approaches(int goal) override;
  /// The detour points' distance from their target: the open hand's reach from its centre
  /// (half the diagonal of its finger curves' bounding box) plus 2 cm, within [0.08, 0.12] m.
  double approach_distance() const { return approach_distance_; }
  /// Where checked motions met space no sensor saw (world frame), the first kMaxContacts: what
  /// a next camera should see (next_view.hpp). Computed on request, from the hits kept.
  std::vector<Eigen::Vector3d> unseen_contacts() const;

  static constexpr std::size_t kMaxContacts = 20000;
  static constexpr double kLimitMargin = 0.05;      ///< rad (m): one controller step at most
  static constexpr double kShortcutTravel = 0.005;  ///< m

 private:
  servo::ClaspController& controller_;
  robots::CollisionWorld& world_;
  double goal_linking_, position_tolerance_, resolution_;
  std::function<bool(const Eigen::VectorXd&)> acceptance_;
  Eigen::VectorXd last_q_;  // the last control() result: continuing from it keeps the alignment
  bool limited_ = false;
  double approach_distance_ = 0.1;
  std::vector<robots::EnvironmentHit> unseen_hits_;
};

}  // namespace claspplan::tsrrt
