#include "servo/task_features.hpp"

#include <array>
#include <iostream>
#include <limits>
#include <stdexcept>

#include <Eigen/Geometry>

namespace claspplan::servo {

JointSpaceFeature::JointSpaceFeature(unsigned int dimension) {
  dim_s = dimension;
  s.resize(dimension);
  // No per-parameter flags: features are recomputed as a whole by update().
  nbParameters = 0;
}

vpMatrix JointSpaceFeature::interaction(unsigned int select) {
  vpMatrix L(0, static_cast<unsigned int>(jacobian_.cols()));
  for (unsigned int i = 0; i < dim_s; ++i) {
    if (!(FEATURE_LINE[i] & select)) continue;
    vpMatrix row(1, static_cast<unsigned int>(jacobian_.cols()));
    for (Eigen::Index j = 0; j < jacobian_.cols(); ++j) row[0][j] = jacobian_(i, j);
    L.stack(row);
  }
  return L;
}

void JointSpaceFeature::print(unsigned int select) const {
  std::cout << "s =";
  for (unsigned int i = 0; i < dim_s; ++i)
    if (FEATURE_LINE[i] & select) std::cout << " " << s[i];
  std::cout << std::endl;
}

void JointSpaceFeature::init() {
  s = 0.0;
  jacobian_.resize(dim_s, 0);
}

FeatureGoal::FeatureGoal(const Eigen::VectorXd& value)
    : JointSpaceFeature(static_cast<unsigned int>(value.size())) {
  for (Eigen::Index i = 0; i < value.size(); ++i) set_value(static_cast<unsigned int>(i), value[i]);
}

PositionFeature::PositionFeature() : JointSpaceFeature(3) {}

void PositionFeature::update(const HandKinematics& hand) {
  const int dof = hand.dof();
  jacobian_.setZero(3, dof);
  // Per axis, the extreme points and the curve/point they belong to.
  Eigen::Vector3d lo = Eigen::Vector3d::Constant(std::numeric_limits<double>::infinity());
  Eigen::Vector3d hi = -lo;
  std::array<std::pair<int, int>, 3> lo_at{}, hi_at{};
  for (std::size_t c = 0; c < hand.curves.size(); ++c) {
    for (std::size_t k = 0; k < hand.curves[c].size(); ++k) {
      const Eigen::Vector3d& p = hand.curves[c][k];
      for (int a = 0; a < 3; ++a) {
        if (p[a] < lo[a]) lo[a] = p[a], lo_at[a] = {static_cast<int>(c), static_cast<int>(k)};
        if (p[a] > hi[a]) hi[a] = p[a], hi_at[a] = {static_cast<int>(c), static_cast<int>(k)};
      }
    }
  }
  for (int a = 0; a < 3; ++a) {
    set_value(a, 0.5 * (lo[a] + hi[a]));
    jacobian_.row(a) = 0.5 * (hand.curve_jacobians[lo_at[a].first][lo_at[a].second].row(a) +
                              hand.curve_jacobians[hi_at[a].first][hi_at[a].second].row(a));
  }
}

AlignmentFeature::AlignmentFeature(std::vector<ClaspTarget> targets, double hold_distance)
    : JointSpaceFeature(2), targets_(std::move(targets)), hold_distance_(hold_distance) {
  // update() aligns with the nearest target: there must be one.
  if (targets_.empty()) throw std::invalid_argument("the alignment feature needs clasp targets");
}

void AlignmentFeature::update(const HandKinematics& hand, const PositionFeature& position) {
  const Eigen::Vector3d centre = position.position();
  nearest_ = -1;
  double best = std::numeric_limits<double>::infinity();
  for (std::size_t i = 0; i < targets_.size(); ++i) {
    const double d = (targets_[i].point - centre).squaredNorm();
    if (d < best) best = d, nearest_ = static_cast<int>(i);
  }
  const ClaspTarget& target = targets_[nearest_];
  const Eigen::Vector3d& v_fwd = hand.forward;
  const Eigen::Vector3d& v_swd = hand.sideways;

  // s1 = |v_swd · p'|.
  const double along = v_swd.dot(target.tangent);
  const double sign = along < 0.0 ? -1.0 : 1.0;
  set_value(0, std::abs(along));
  jacobian_.resize(2, hand.dof());
  jacobian_.row(0) = sign * target.tangent.transpose() * hand.sideways_jacobian;

  // s2 = v_fwd · t with t = (p − c)/|p − c|; dt/dq = −(I − t tᵀ) J_pos / |p − c|.
  const Eigen::Vector3d to_target = target.point - centre;
  const double distance = to_target.norm();
  Eigen::Vector3d t;
  if (distance > hold_distance_) {
    t = to_target / distance;
    direction_ = t;
    has_direction_ = true;
    jacobian_.row(1) = t.transpose() * hand.forward_jacobian -
                       (v_fwd - t * t.dot(v_fwd)).transpose() * position.jacobian() / distance;
  } else {
    t = has_direction_ ? direction_ : v_fwd;
    jacobian_.row(1) = t.transpose() * hand.forward_jacobian;
  }
  set_value(1, v_fwd.dot(t));
}

VirtualLinkingFeature::VirtualLinkingFeature(Points loop)
    : JointSpaceFeature(1), loop_(std::move(loop)) {}

void VirtualLinkingFeature::update(const HandKinematics& hand) {
  const std::size_t fingers = hand.curves.size();
  jacobian_.setZero(1, hand.dof());
  finger_values_.assign(fingers, 0.0);
  double mean = 0.0;
  for (std::size_t c = 0; c < fingers; ++c) {
    const VirtualLinking v = virtual_linking(loop_, hand.curves[c]);
    finger_values_[c] = std::abs(v.value);
    mean += finger_values_[c];
    if (v.closed_linking == 0) continue;
    // d|VLk| = sign(Lk) dVLk, chained through each curve point's Jacobian.
    virtual_linking_gradient(v, hand.curves[c], gradient_);
    const double sign = v.closed_linking < 0 ? -1.0 : 1.0;
    for (std::size_t k = 0; k < gradient_.size(); ++k) {
      jacobian_.row(0) += sign * gradient_[k].transpose() * hand.curve_jacobians[c][k];
    }
  }
  if (fingers > 0) {
    set_value(0, mean / fingers);
    jacobian_ /= static_cast<double>(fingers);
  }
}

}  // namespace claspplan::servo
