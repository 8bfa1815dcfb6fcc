#include "tsrrt/hand_room.hpp"

#include <cmath>
#include <stdexcept>
#include <string>

#include "robots/kinematics.hpp"
#include "tsrrt/approach.hpp"

namespace claspplan::tsrrt {

namespace {

// A right-handed frame with x along `forward` and y along `sideways` made orthogonal to it.
Eigen::Matrix3d hand_frame(const Eigen::Vector3d& forward, const Eigen::Vector3d& sideways) {
  Eigen::Matrix3d r;
  r.col(0) = forward.normalized();
  r.col(1) = (sideways - r.col(0) * r.col(0).dot(sideways)).normalized();
  r.col(2) = r.col(0).cross(r.col(1));
  return r;
}

}  // namespace

FloatingHand::FloatingHand(const robots::RobotModel& model, const Eigen::VectorXd& hand_q)
    : data_(model) {
  if (hand_q.size() != model.hand_dof)
    throw std::invalid_argument("FloatingHand: the hand needs " + std::to_string(model.hand_dof) +
                                " joint values");
  Eigen::VectorXd q = model.home;
  q.tail(model.hand_dof) = hand_q;
  robots::FingerCurvesData curves;
  robots::finger_curves(model, q, data_, curves, false);
  Eigen::AlignedBox3d box;
  for (const auto& curve : curves.points)
    for (const auto& point : curve) box.extend(point);
  Eigen::Isometry3d hand = Eigen::Isometry3d::Identity();
  hand.linear() = hand_frame(robots::vector_direction(data_, model.v_fwd),
                             robots::vector_direction(data_, model.v_swd));
  hand.translation() = box.isEmpty() ? data_.link_poses[model.tool_link].translation()
                                     : Eigen::Vector3d(box.center());
  const Eigen::Isometry3d to_hand = hand.inverse();
  for (int l = 0; l < static_cast<int>(model.links.size()); ++l) {
    if (!model.links[l].hand || model.links[l].shapes.empty()) continue;
    links_.push_back(l);
    in_hand_frame_.push_back(to_hand * data_.link_poses[l]);
  }
}

bool FloatingHand::blocked(robots::CollisionWorld& world, const Eigen::Vector3d& centre,
                           const Eigen::Vector3d& forward, const Eigen::Vector3d& tangent) {
  for (double sign : {1.0, -1.0}) {
    Eigen::Isometry3d hand = Eigen::Isometry3d::Identity();
    hand.linear() = hand_frame(forward, sign * tangent);
    hand.translation() = centre;
    for (std::size_t i = 0; i < links_.size(); ++i)
      data_.link_poses[links_[i]] = hand * in_hand_frame_[i];
    bool touches = false;
    for (std::size_t i = 0; i < links_.size() && !touches; ++i)
      touches = world.link_in_collision(data_, links_[i]);
    if (!touches) return false;
  }
  return true;
}

std::vector<Eigen::Vector2d> room_approach_angles() {
  std::vector<Eigen::Vector2d> angles = approach_angles();
  const double c = std::cos(M_PI / 8), s = std::sin(M_PI / 8);
  angles.insert(angles.end(), {{c, s}, {c, -s}, {s, c}, {s, -c}});
  return angles;
}

std::vector<bool> clasp_room(const robots::RobotModel& model, const Eigen::VectorXd& closed_hand_q,
                             robots::CollisionWorld& environment, const servo::Points& loop,
                             const std::vector<ClaspTarget>& targets) {
  const std::vector<Eigen::Vector2d> angles = room_approach_angles();
  FloatingHand closed(model, closed_hand_q);
  std::vector<bool> out;
  for (const auto& target : targets) {
    const ApproachFrame frame = approach_frame(loop, target);
    bool fits = false;
    for (std::size_t i = 0; i < angles.size() && !fits; ++i) {
      const Eigen::Vector3d away = frame.direction(angles[i]);  // v_fwd is -away
      for (double back : {0.0, 0.02, 0.04}) {
        fits = fits || !closed.blocked(environment, target.point + back * away, -away, frame.t);
      }
    }
    out.push_back(fits);
  }
  return out;
}

}  // namespace claspplan::tsrrt
