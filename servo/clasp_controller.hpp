// TS-CONTROL (paper Alg. 4) for a robot: the position, alignment and virtual-linking features of
// the hand at q, composed by the prioritized hierarchy (servo/prioritized_control.hpp), with joint
// limits respected. TS-PROJECTION gives the task-space point (Π_pos, Π_vlink) the planner searches.
#pragma once

#include <vector>

#include <Eigen/Core>

#include "robots/kinematics.hpp"
#include "robots/robot_model.hpp"
#include "servo/prioritized_control.hpp"
#include "servo/task_features.hpp"

namespace claspplan::servo {

struct ControllerParameters {
  PriorityParameters priority;
  /// Alignment keeps its last direction to the target within this distance (m).
  double hold_distance = 0.01;
  /// The position error the arm servoes on per step is capped at this length (m), while the
  /// alignment is corrected in full: far from the target the hand first turns toward it and then
  /// approaches along its own pointing direction, instead of sweeping its fingers sideways into
  /// the object. GAIN(‖u_pos‖) still sees the true distance. 0 = no cap (Alg. 4 as written).
  double max_position_error = 0.02;
  /// Gain of the pose bias (paper Sec. III-C): each arm joint is pulled toward the middle of its
  /// range by gain·(mid − q)/(half range)², in the null space of the arm tasks. Keeps the wrist
  /// away from its limits, where the hand's palm meets the forearm. 0 = off.
  double pose_bias_gain = 0.05;
  /// M_arm weight of the hand joints and M_hand weight of the arm joints (0: the arm tasks use the
  /// arm only, the linking task the hand only).
  double hand_in_arm_tasks = 0.0;
  double arm_in_hand_task = 0.0;
};

/// The features' values at one configuration.
struct TaskState {
  Eigen::Vector3d position = Eigen::Vector3d::Zero();   ///< Π_pos
  Eigen::Vector2d alignment = Eigen::Vector2d::Zero();  ///< Π_align (eq. 3)
  double linking = 0.0;                                 ///< Π_vlink (eq. 4): mean |VLk|
  std::vector<double> finger_linking;                   ///< |VLk| per finger curve
  int nearest_target = -1;
};

class ClaspController {
 public:
  /// `loop`: the object loop γ to clasp; `targets`: its clasp targets G_γ (at least one).
  ClaspController(const robots::RobotModel& model, Points loop, std::vector<ClaspTarget> targets,
                  const ControllerParameters& parameters = {});

  /// TS-PROJECTION and the alignment, at q.
  TaskState project(const Eigen::VectorXd& q);

  /// TS-CONTROL: one step from q0 toward the task-space point (c_pos, c_vlink); c_align = (1, 1).
  /// Joints at a limit that the step would push further are held, and the step is solved again
  /// without them; the result is always within the limits.
  Eigen::VectorXd step(const Eigen::VectorXd& q0, const Eigen::Vector3d& c_pos, double c_vlink);

  /// Starts a new trajectory: the alignment task's kept direction is dropped (a tree search calls
  /// this when it continues from another node than the last step's result).
  void forget_direction() {
    alignment_.forget_direction();
    updated_ = false;  // the alignment at the same q may now differ
  }

  /// What the last step() decided.
  const PrioritizedStep& last_step() const { return last_; }
  const robots::RobotModel& model() const { return model_; }
  const std::vector<ClaspTarget>& targets() const { return alignment_.targets(); }
  const Points& loop() const { return linking_.loop(); }
  /// The features at the last project() or step() configuration (ViSP features).
  const PositionFeature& position_feature() const { return position_; }
  const AlignmentFeature& alignment_feature() const { return alignment_; }
  const VirtualLinkingFeature& linking_feature() const { return linking_; }
  /// The hand geometry at the last project() or step() configuration.
  const HandKinematics& hand() const { return hand_; }

 private:
  void update(const Eigen::VectorXd& q);

  const robots::RobotModel& model_;
  ControllerParameters p_;
  robots::RobotData data_;
  robots::FingerCurvesData curves_;
  HandKinematics hand_;
  PositionFeature position_;
  AlignmentFeature alignment_;
  VirtualLinkingFeature linking_;
  Eigen::VectorXd arm_mask_, hand_mask_;
  Eigen::VectorXd mid_, bias_weight_;  // pose bias: range middles and gain/(half range)²
  PrioritizedStep last_;
  // The configuration the features were last computed at: a search projects each new node and
  // then steps from it, so the second computation at the same q is skipped.
  Eigen::VectorXd updated_q_;
  bool updated_ = false;
};

}  // namespace claspplan::servo
