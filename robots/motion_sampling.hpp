// Where a straight joint-space motion is checked for collisions. How far any point of the robot
// can travel along it: for each entry of q, the farthest its joint(s) can swing a point of the
// links they carry. The bound Σ_j |Δq_j| · reach_j (the arc length a revolute joint gives a point
// at distance reach_j, or the prismatic joint's own travel) holds whatever the configuration, so
// that sampling a motion every d of it leaves no point of the robot more than d between two
// checked configurations.
#pragma once

#include <utility>
#include <vector>

#include <Eigen/Core>

#include "robots/robot_model.hpp"

namespace claspplan::robots {

/// reach[j] (m per unit of q[j]): Σ over the joints credited to q[j] (Link::column) of
/// |column_multiplier| times the distance from the joint's frame to the farthest corner of any
/// collision shape it carries (revolute; link offsets summed along the chain, prismatic travel
/// included), or |column_multiplier| (prismatic).
Eigen::VectorXd motion_reach(const RobotModel& model);

/// The longest path any robot point takes from q0 to q1 (linear in q): Σ_j |q1_j − q0_j| reach_j.
inline double travel_bound(const Eigen::VectorXd& reach, const Eigen::VectorXd& q0,
                           const Eigen::VectorXd& q1) {
  return (q1 - q0).cwiseAbs().dot(reach);
}

/// How many equal steps the motion q0 -> q1 is checked in: no joint moves more than `resolution`
/// per step and, when travel > 0, no robot point farther than `travel` (by travel_bound()). At
/// least 1. Throws std::invalid_argument for resolution <= 0 and above a million steps.
int motion_steps(const Eigen::VectorXd& reach, double travel, const Eigen::VectorXd& q0,
                 const Eigen::VectorXd& q1, double resolution);

/// Whether free(k) holds for every sample k = 0..steps, visited coarse to fine (both ends, then
/// each interval's midpoint breadth-first), so that a collision shows early; each sample once.
template <class Free>
bool all_samples_free(int steps, Free&& free) {
  if (!free(steps) || !free(0)) return false;
  std::vector<std::pair<int, int>> queue{{0, steps}};
  for (std::size_t head = 0; head < queue.size(); ++head) {
    const auto [lo, hi] = queue[head];
    if (hi - lo < 2) continue;
    const int mid = lo + (hi - lo) / 2;
    if (!free(mid)) return false;
    queue.emplace_back(lo, mid);
    queue.emplace_back(mid, hi);
  }
  return true;
}

}  // namespace claspplan::robots
