// Room for the hand at a clasp target: the hand alone, closed to its virtual-linking goal and
// placed as the controller leaves it (the position feature's centre on the target, v_swd along
// the loop's tangent, v_fwd along an approach), tested against the static environment. Next to the
// floor or a wall a long-fingered hand may find no approach at which its closed fingers fit
// around the bar: the clasp itself is impossible there, whatever the search does.
#pragma once

#include <vector>

#include <Eigen/Core>
#include <Eigen/Geometry>

#include "robots/collision_world.hpp"
#include "robots/robot_model.hpp"
#include "servo/task_features.hpp"

namespace claspplan::tsrrt {

/// The hand alone at one shape, placed by the frame the controller aligns (origin: the finger
/// curves' bounding-box centre; axes v_fwd, v_swd, v_fwd × v_swd). The link poses in that frame
/// are computed once; a placement is then one product per link.
class FloatingHand {
 public:
  /// `hand_q`: the hand joints (model.hand_dof values).
  FloatingHand(const robots::RobotModel& model, const Eigen::VectorXd& hand_q);

  /// Does the hand, centred at `centre` with v_fwd along `forward` and v_swd along ± `tangent`,
  /// touch what `world` holds, at both signs? (The alignment feature takes either.)
  bool blocked(robots::CollisionWorld& world, const Eigen::Vector3d& centre,
               const Eigen::Vector3d& forward, const Eigen::Vector3d& tangent);

 private:
  robots::RobotData data_;
  std::vector<int> links_;                        // hand links with collision shapes
  std::vector<Eigen::Isometry3d> in_hand_frame_;  // their poses in the hand frame
};

/// The approach angles the room is tested at, each as (cos θ, sin θ): clasp_approaches()' five
/// (approach_angles()) and ±22.5°, ±67.5° between them.
std::vector<Eigen::Vector2d> room_approach_angles();

/// For each target: does the hand closed to its linking goal (`closed_hand_q`,
/// robots::HandSize::closed_q) fit beside `environment` at some of the room_approach_angles()
/// approach directions, centred on the target or up to 4 cm back along the approach (where verified
/// clasps leave it: 2-4 cm short)? `environment` should hold no object: at the target the hand
/// is around the object's bar by design.
std::vector<bool> clasp_room(const robots::RobotModel& model, const Eigen::VectorXd& closed_hand_q,
                             robots::CollisionWorld& environment, const servo::Points& loop,
                             const std::vector<ClaspTarget>& targets);

}  // namespace claspplan::tsrrt
