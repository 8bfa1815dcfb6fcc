// The three task features of the clasp controller (paper Sec. IV-E) as ViSP features: each holds
// its value s and its Jacobian ∂s/∂q, which ViSP calls the interaction matrix; here it maps joint
// velocities rather than a camera twist, which is why they derive from vpBasicFeature directly
// (vpGenericFeature keeps only 6 columns).
#pragma once

#include <vector>

#include <Eigen/Core>
#include <visp3/visual_features/vpBasicFeature.h>

#include "core/clasp_target.hpp"
#include "servo/hand_kinematics.hpp"

namespace claspplan::servo {

/// A feature in joint space: s (dim entries) and ∂s/∂q (dim × dof).
class JointSpaceFeature : public vpBasicFeature {
 public:
  explicit JointSpaceFeature(unsigned int dimension);

  /// ∂s/∂q for the selected rows.
  vpMatrix interaction(unsigned int select = FEATURE_ALL) override;
  void print(unsigned int select = FEATURE_ALL) const override;
  void init() override;
  /// Joint-space features have no image-plane representation to draw.
  void display(const vpCameraParameters&, const vpImage<unsigned char>&, const vpColor&,
               unsigned int) const override {}
  void display(const vpCameraParameters&, const vpImage<vpRGBa>&, const vpColor&,
               unsigned int) const override {}

  double value(unsigned int i) const { return s[i]; }
  const Eigen::MatrixXd& jacobian() const { return jacobian_; }

 protected:
  void set_value(unsigned int i, double v) { s[i] = v; }
  Eigen::MatrixXd jacobian_;
};

/// A desired value s* for a feature of the same dimension (no Jacobian).
class FeatureGoal final : public JointSpaceFeature {
 public:
  explicit FeatureGoal(const Eigen::VectorXd& value);
  vpBasicFeature* duplicate() const override { return new FeatureGoal(*this); }
};

/// Π_pos: the centre of the axis-aligned bounding box of all finger-curve points. It follows the
/// hand's shape as the fingers close, so the hand keeps the loop centred while it closes.
class PositionFeature final : public JointSpaceFeature {
 public:
  PositionFeature();
  void update(const HandKinematics& hand);
  Eigen::Vector3d position() const { return {s[0], s[1], s[2]}; }
  vpBasicFeature* duplicate() const override { return new PositionFeature(*this); }
};

/// Π_align (eq. 3): (|v_swd · p'_near|, v_fwd · t_near) for the clasp target nearest to the hand
/// centre, with t_near the unit direction from the hand centre to it. (1, 1) exactly when the hand
/// points at the target and its sideways axis lies along the loop's tangent.
class AlignmentFeature final : public JointSpaceFeature {
 public:
  /// Within `hold_distance` of the target t_near is ill-defined; the last direction is kept
  /// (or v_fwd itself, making the pointing term 1, when there is none).
  AlignmentFeature(std::vector<ClaspTarget> targets, double hold_distance);
  void update(const HandKinematics& hand, const PositionFeature& position);
  /// Starts a new trajectory: the kept direction is dropped.
  void forget_direction() { has_direction_ = false; }
  int nearest_target() const { return nearest_; }
  const std::vector<ClaspTarget>& targets() const { return targets_; }
  vpBasicFeature* duplicate() const override { return new AlignmentFeature(*this); }

 private:
  std::vector<ClaspTarget> targets_;
  double hold_distance_;
  bool has_direction_ = false;
  Eigen::Vector3d direction_ = Eigen::Vector3d::Zero();
  int nearest_ = -1;
};

/// Π_vlink (eq. 4): the mean over finger curves of |VLk(γ, α)|. A loop found over Z2 has no
/// orientation, so the sign of Lk(γ, α̂) is arbitrary; taking |VLk| = |Lk|·(1 − δ/|α̂|) per curve
/// makes the task independent of it (as the paper's Fig. 6 does with |Lk|).
class VirtualLinkingFeature final : public JointSpaceFeature {
 public:
  explicit VirtualLinkingFeature(Points loop);
  void update(const HandKinematics& hand);
  /// |VLk| of each finger curve at the last update.
  const std::vector<double>& finger_values() const { return finger_values_; }
  const Points& loop() const { return loop_; }
  vpBasicFeature* duplicate() const override { return new VirtualLinkingFeature(*this); }

 private:
  Points loop_;
  std::vector<double> finger_values_;
  Points gradient_;  // workspace
};

}  // namespace claspplan::servo
