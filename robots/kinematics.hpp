// Forward kinematics and Jacobians on a RobotModel. RobotData holds one configuration's results
// (Pinocchio style): call forward_kinematics() once per q, then any number of Jacobian queries.
//
// Jacobians are with respect to q (dof() columns, arm joints then hand joints). Mimic joints add
// multiplier × their motion to the leader's column (chain rule), and so do adaptive joints, which
// planned motions move with their leader (RobotModel::couple); held joints add nothing.
#pragma once

#include <vector>

#include <Eigen/Core>
#include <Eigen/Geometry>

#include "robots/robot_model.hpp"

namespace claspplan::robots {

/// Per-configuration results. Build once per model, reuse for every query (no allocation after
/// the first call of each function).
struct RobotData {
  RobotData() = default;
  explicit RobotData(const RobotModel& model);

  Eigen::VectorXd q;                          ///< the configuration of the last FK
  std::vector<Eigen::Isometry3d> link_poses;  ///< world pose of every link frame
  std::vector<Eigen::Vector3d> joint_axes;    ///< world axis of each link's parent joint
};

/// All link poses at q (q.size() must be model.dof(); values are used as given, see
/// RobotModel::clamp()). The world frame is the root link.
void forward_kinematics(const RobotModel& model, const Eigen::VectorXd& q, RobotData& data);

/// World position of a link-fixed point (after forward_kinematics).
Eigen::Vector3d point_position(const RobotData& data, const LinkPoint& p);

/// World pose of a collision shape (for drawing the robot; cylinder and capsule axes are z).
Eigen::Isometry3d shape_pose(const RobotData& data, const CollisionShape& shape);

/// ∂p/∂q of the link-fixed point `local_point` (in `link`'s frame): 3 × dof.
Eigen::Matrix<double, 3, Eigen::Dynamic> point_jacobian(const RobotModel& model,
                                                        const RobotData& data, int link,
                                                        const Eigen::Vector3d& local_point);

/// Angular velocity Jacobian of `link`: ω = J q̇, 3 × dof.
Eigen::Matrix<double, 3, Eigen::Dynamic> angular_jacobian(const RobotModel& model,
                                                          const RobotData& data, int link);

/// World direction of a link-fixed unit vector and its Jacobian ∂v/∂q = −[v]× J_ω (3 × dof).
Eigen::Vector3d vector_direction(const RobotData& data, const LinkVector& v);
Eigen::Matrix<double, 3, Eigen::Dynamic> vector_jacobian(const RobotModel& model,
                                                         const RobotData& data,
                                                         const LinkVector& v);

/// All finger curves α ∈ C in the world with their point Jacobians (the controller's hot path).
struct FingerCurvesData {
  /// points[c][i]: point i of curve c (model.curves[c].points order).
  std::vector<std::vector<Eigen::Vector3d>> points;
  /// jacobians[c][i] = ∂points[c][i]/∂q, 3 × dof (the layout of servo::HandKinematics).
  std::vector<std::vector<Eigen::Matrix3Xd>> jacobians;
};

/// Fills `out` from data (after forward_kinematics). Without Jacobians only the points are set.
void finger_curves(const RobotModel& model, const RobotData& data, FingerCurvesData& out,
                   bool with_jacobians = true);

/// Convenience: FK at q, then finger_curves().
void finger_curves(const RobotModel& model, const Eigen::VectorXd& q, RobotData& data,
                   FingerCurvesData& out, bool with_jacobians = true);

}  // namespace claspplan::robots
