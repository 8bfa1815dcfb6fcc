#include "tsrrt/finger_closing.hpp"

#include <algorithm>
#include <cmath>

#include "robots/kinematics.hpp"

namespace claspplan::tsrrt {

Eigen::VectorXd close_fingers(const robots::RobotModel& model, robots::CollisionWorld& world,
                              const Eigen::VectorXd& q_start, const FingerClosingOptions& o,
                              std::vector<robots::EnvironmentHit>* unseen_stops) {
  Eigen::VectorXd q = q_start;
  robots::RobotData data(model);
  const Eigen::VectorXd lower = model.lower(), upper = model.upper();
  // The links a finger's closing checks: its own, and any other that its closing joints move
  // through mimic joints (a one-motor hand's other fingers, a plate the thumb turns).
  std::vector<std::vector<int>> moved;
  for (const robots::Finger& finger : model.fingers) {
    std::vector<int> closing;
    for (int j : finger.joints)
      if (model.joints[j].closing != 0.0) closing.push_back(j);
    std::vector<int>& links = moved.emplace_back(finger.links);
    for (int link = 0; link < static_cast<int>(model.links.size()); ++link) {
      if (model.links[link].shapes.empty() ||
          std::find(links.begin(), links.end(), link) != links.end())
        continue;
      for (int s : model.links[link].support) {
        if (std::find(closing.begin(), closing.end(), model.links[s].q_index) != closing.end()) {
          links.push_back(link);
          break;
        }
      }
    }
  }
  const auto blocked_link = [&](std::size_t finger) {
    robots::CollisionReport report;
    for (int link : moved[finger]) {
      if (world.link_near_object(data, link, o.clearance)) return link;
      if (world.link_in_collision(data, link, &report, /*include_self=*/true)) {
        if (unseen_stops && report.second == "unseen space")
          unseen_stops->push_back(world.environment_hit());
        return link;
      }
    }
    return -1;
  };
  // All fingers close together, one step each per round, so that opposing fingers meet halfway.
  // A blocked link freezes the joints that move it while the joints beyond it keep closing, so
  // that a finger stopped at its base by a narrow hole still curls its tip around the bar.
  std::vector<std::vector<bool>> active;
  for (const auto& finger : model.fingers) active.emplace_back(finger.joints.size(), true);
  for (int round = 0; round < o.max_steps; ++round) {
    bool any = false;
    for (std::size_t f = 0; f < model.fingers.size(); ++f) {
      const robots::Finger& finger = model.fingers[f];
      for (;;) {
        Eigen::VectorXd trial = q;
        for (std::size_t k = 0; k < finger.joints.size(); ++k) {
          const int j = finger.joints[k];
          if (active[f][k]) trial[j] += model.joints[j].closing * o.step;
        }
        trial = trial.cwiseMax(lower).cwiseMin(upper);
        if (trial == q) break;  // no active joint, or all at their limits
        robots::forward_kinematics(model, trial, data);
        const int link = blocked_link(f);
        if (link < 0) {
          q = trial;
          any = true;
          break;
        }
        // Freeze the joints that move the blocked link; when none is active the finger is done.
        bool froze = false;
        for (std::size_t k = 0; k < finger.joints.size(); ++k) {
          if (!active[f][k]) continue;
          for (int s : model.links[link].support) {
            if (model.links[s].q_index == finger.joints[k]) {
              active[f][k] = false;
              froze = true;
            }
          }
        }
        if (!froze) std::fill(active[f].begin(), active[f].end(), false);
      }
    }
    if (!any) break;
  }
  return q;
}

}  // namespace claspplan::tsrrt
