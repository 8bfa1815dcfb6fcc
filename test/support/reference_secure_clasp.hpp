// The secure-clasp check as it was first written, kept as the reference the fast check
// (tsrrt::check_secure_clasp) is compared with: the whole object mesh, every sequence run to its
// end, one collision world per thread placing the robot at every step.
#pragma once

#include <algorithm>
#include <thread>
#include <vector>

#include "robots/collision_world.hpp"
#include "robots/kinematics.hpp"
#include "tsrrt/secure_clasp.hpp"
#include "tsrrt/secure_clasp_detail.hpp"

namespace claspplan::test {

inline tsrrt::SecureClaspReport reference_secure_clasp(
    const robots::RobotModel& model, const std::vector<Eigen::Vector3d>& object_vertices,
    const std::vector<Eigen::Vector3i>& object_triangles, const Eigen::VectorXd& q,
    const servo::Points& loop, const tsrrt::SecureClaspOptions& o) {
  tsrrt::SecureClaspReport report;
  const tsrrt::detail::ClaspCheckContext c =
      tsrrt::detail::clasp_check_context(model, q, loop, report);
  robots::RobotData data(model);
  robots::forward_kinematics(model, q, data);
  const int threads = std::max(1, std::min(o.threads > 0 ? o.threads : 2, o.sequences));
  std::vector<robots::CollisionWorld> worlds;
  for (int t = 0; t < threads; ++t) {
    worlds.emplace_back(model);
    worlds.back().set_self_collision(false);
    worlds.back().set_object(object_vertices, object_triangles);
  }
  if (worlds.front().in_collision(data)) {
    report.start_in_collision = true;
    return report;
  }
  report.sequences = o.sequences;
  std::vector<int> escape_at(o.sequences, -1);
  const auto work = [&](int t) {
    const auto collides = [&](const Eigen::Isometry3d& T) {
      worlds[t].set_object_pose(T);
      return worlds[t].in_collision(data);
    };
    for (int s = t; s < o.sequences; s += threads) {
      std::mt19937_64 rng(tsrrt::detail::sequence_seed(o.seed, s));
      Eigen::Isometry3d T = Eigen::Isometry3d::Identity();
      for (int m = 0; m < o.motions && escape_at[s] < 0; ++m)
        if (tsrrt::detail::random_motion(c, o, rng, T, collides)) escape_at[s] = m;
    }
  };
  std::vector<std::thread> pool;
  for (int t = 1; t < threads; ++t) pool.emplace_back(work, t);
  work(0);
  for (auto& th : pool) th.join();
  for (int s = 0; s < o.sequences; ++s) {
    if (escape_at[s] < 0) continue;
    ++report.escaped_sequences;
    if (report.escape_motion < 0) report.escape_motion = escape_at[s];
  }
  report.secure = report.escaped_sequences == 0;
  return report;
}

}  // namespace claspplan::test
