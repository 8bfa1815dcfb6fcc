// What the Task-Space RRT needs of a clasp problem: the task-space projection, the local
// controller, collision checking of motions and the goal test (paper Sec. IV-D). The planner
// (tsrrt/planner.hpp) is written against this interface only; tsrrt/clasp_problem.hpp binds it to a
// robot, an object loop and the servo controller.
#pragma once

#include <Eigen/Core>

namespace claspplan::tsrrt {

/// A point of the task space X = X_pos × X_vlink searched by the tree: the hand's position
/// (Π_pos, metres) and the mean virtual linking (Π_vlink, eq. 4).
struct TaskPoint {
  Eigen::Vector3d position = Eigen::Vector3d::Zero();
  double linking = 0.0;
};

class PlanningProblem {
 public:
  virtual ~PlanningProblem() = default;

  /// TS-PROJECTION: q ↦ x.
  virtual TaskPoint project(const Eigen::VectorXd& q) = 0;

  /// TS-CONTROL (Alg. 4): one controller step from q0 (with x0 = project(q0)) toward x1.
  virtual Eigen::VectorXd control(const Eigen::VectorXd& q0, const TaskPoint& x0,
                                  const TaskPoint& x1) = 0;

  /// COLLISION-FREE: the straight joint-space motion q0 → q1 is free of collisions.
  virtual bool motion_free(const Eigen::VectorXd& q0, const Eigen::VectorXd& q1) = 0;

  /// TS-TOLERANCE: x satisfies the goal x_goal (virtual linking, optionally also position).
  virtual bool reached(const TaskPoint& x, const TaskPoint& goal) const = 0;

  /// Called when a node reaches the goal tolerance: whether the search may end with it. A clasp
  /// planner closes the fingers there and runs the secure-clasp check; a rejected node stays in
  /// the tree and the search goes on.
  virtual bool accept(const Eigen::VectorXd& q) {
    (void)q;
    return true;
  }
};

}  // namespace claspplan::tsrrt
