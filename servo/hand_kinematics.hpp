// The hand at one configuration, in the world frame: what the task features read. Filled from the
// robot model (robots/) by servo/clasp_controller.cpp; kept as plain data so the features can be
// tested on their own.
#pragma once

#include <vector>

#include <Eigen/Core>

#include "servo/linking.hpp"

namespace claspplan::servo {

struct HandKinematics {
  /// The finger curves α (fingertip → finger joints → palm → thumb joints → thumb tip).
  std::vector<Points> curves;
  /// ∂(point)/∂q of every curve point, 3 × dof each, in the same layout as `curves`.
  std::vector<std::vector<Eigen::Matrix3Xd>> curve_jacobians;
  Eigen::Vector3d forward = Eigen::Vector3d::UnitZ();   ///< v_fwd
  Eigen::Vector3d sideways = Eigen::Vector3d::UnitY();  ///< v_swd
  /// ∂v_fwd/∂q and ∂v_swd/∂q (3 × dof each): −[v]× J_ω of the link that carries each vector.
  Eigen::Matrix3Xd forward_jacobian;
  Eigen::Matrix3Xd sideways_jacobian;

  int dof() const { return static_cast<int>(forward_jacobian.cols()); }
};

}  // namespace claspplan::servo
