// What the Task-Space RRT needs of a clasp problem: the task-space projection, the local
// controller, collision checking of motions and the goal test (paper Sec. IV-D). The planner
// (tsrrt/planner.hpp) is written against this interface only; tsrrt/clasp_problem.hpp binds it to
// a robot, an object loop and the servo controller.
#pragma once

#include <cstdint>
#include <functional>
#include <vector>

#include <Eigen/Core>

namespace claspplan::tsrrt {

/// A point of the task space X = X_pos × X_vlink searched by the tree: the hand's position
/// (Π_pos, metres) and the mean virtual linking (Π_vlink, eq. 4).
struct TaskPoint {
  Eigen::Vector3d position = Eigen::Vector3d::Zero();
  double linking = 0.0;
};

/// What a checked motion ran into, if anything.
enum class MotionCheck {
  kFree,         ///< collision-free
  kObject,       ///< the robot touches the object (to be clasped)
  kEnvironment,  ///< the robot touches the static environment (table, walls, obstacles)
  kUnseen,       ///< the robot enters space near the object that no sensor saw
  kSelf,         ///< the robot touches itself
};

class PlanningProblem {
 public:
  virtual ~PlanningProblem() = default;

  /// TS-PROJECTION: q ↦ x.
  virtual TaskPoint project(const Eigen::VectorXd& q) = 0;

  /// TS-CONTROL (Alg. 4): one controller step from q0 (with x0 = project(q0)) toward x1.
  virtual Eigen::VectorXd control(const Eigen::VectorXd& q0, const TaskPoint& x0,
                                  const TaskPoint& x1) = 0;

  /// Whether the last control() step held a joint at its limit that the controller wanted to
  /// move further: a connect attempt that stops making progress while this is so ends at the
  /// joint limits rather than in a plain stall.
  virtual bool control_limited() const { return false; }

  /// COLLISION-FREE with the reason: the straight joint-space motion q0 → q1 is free
  /// (MotionCheck::kFree), or what it runs into first.
  virtual MotionCheck check_motion(const Eigen::VectorXd& q0, const Eigen::VectorXd& q1) = 0;

  /// COLLISION-FREE: the straight joint-space motion q0 → q1 is free of collisions.
  bool motion_free(const Eigen::VectorXd& q0, const Eigen::VectorXd& q1) {
    return check_motion(q0, q1) == MotionCheck::kFree;
  }

  /// Whether path pruning may join q0 and q1 directly: by default motion_free(). A shortcut
  /// replaces many short steps by one long motion, which a problem may check more finely.
  virtual bool shortcut_free(const Eigen::VectorXd& q0, const Eigen::VectorXd& q1) {
    return motion_free(q0, q1);
  }

  /// TS-TOLERANCE: x satisfies the goal x_goal (virtual linking, optionally also position).
  virtual bool reached(const TaskPoint& x, const TaskPoint& goal) const = 0;

  /// Called when a node reaches the goal tolerance: whether the search may end with it. A clasp
  /// planner closes the fingers there and runs the secure-clasp check; a rejected node stays in
  /// the tree and the search goes on.
  virtual bool accept(const Eigen::VectorXd& q) {
    (void)q;
    return true;
  }

  /// A random collision-free configuration for goal sampling (planner.hpp, sample_probability),
  /// drawn with `bits` (a source of uniform 64-bit words); false when the problem offers none
  /// (the default: the planner then never starts an approach away from its tree).
  virtual bool sample_configuration(const std::function<std::uint64_t()>& bits,
                                    Eigen::VectorXd& q) {
    (void)bits;
    (void)q;
    return false;
  }

  /// Detour points for goal `goal` (an index into the planner's goals): places from which the
  /// goal may be approached from other directions. When a connect attempt toward the goal ends
  /// against the object (contact, a stall or the joint limits), the planner backs off along the
  /// attempt, extends toward the next of these (cycling through them per goal) and connects to
  /// the goal again from there. None by default: failed attempts are then simply retried from
  /// other nodes.
  virtual std::vector<TaskPoint> approaches(int goal) {
    (void)goal;
    return {};
  }
};

}  // namespace claspplan::tsrrt
