#include "servo/controller_run.hpp"

namespace claspplan::servo {

ControllerRun run_controller(ClaspController& controller, robots::CollisionWorld& world,
                             const Eigen::VectorXd& q_start, double goal_linking,
                             const ControllerRunOptions& o) {
  ControllerRun run;
  Eigen::VectorXd q = q_start;
  run.waypoints.push_back(q);
  TaskState x = controller.project(q);
  run.target = x.nearest_target;
  const ClaspTarget& target = controller.targets()[run.target];
  run.linking_history.push_back(x.linking);
  if (world.in_collision(q, &run.collision)) {
    run.collided = true;
    run.reason = "the start configuration is in collision (" + run.collision.first + " with " +
                 run.collision.second + ")";
    run.final_state = x;
    return run;
  }

  double best_distance = (target.point - x.position).norm();
  double best_alignment = (Eigen::Vector2d::Ones() - x.alignment).norm();
  double best_linking = x.linking;
  int stalled = 0;
  for (int step = 0; step < o.max_steps; ++step) {
    if (x.linking >= goal_linking) {
      run.success = true;
      run.reason = "virtual-linking goal reached";
      break;
    }
    // x_goal = (p, 1.0), as TS-CONNECT-GOAL sets it (Alg. 1 line 9).
    const Eigen::VectorXd next = controller.step(q, target.point, 1.0);
    if (!world.motion_free(q, next, o.collision_resolution, &run.collision)) {
      run.collided = true;
      run.environment_hit = world.environment_hit();
      run.reason =
          "stopped by a collision (" + run.collision.first + " with " + run.collision.second + ")";
      break;
    }
    q = next;
    run.waypoints.push_back(q);
    x = controller.project(q);
    run.linking_history.push_back(x.linking);

    const double distance = (target.point - x.position).norm();
    const double alignment = (Eigen::Vector2d::Ones() - x.alignment).norm();
    const bool progress = distance < best_distance - o.stall_position ||
                          alignment < best_alignment - o.stall_alignment ||
                          x.linking > best_linking + o.stall_linking;
    best_distance = std::min(best_distance, distance);
    best_alignment = std::min(best_alignment, alignment);
    best_linking = std::max(best_linking, x.linking);
    stalled = progress ? 0 : stalled + 1;
    if (stalled >= o.stall_steps) {
      run.reason = "no progress for " + std::to_string(o.stall_steps) + " steps (" +
                   std::to_string(distance) + " m from the target, virtual linking " +
                   std::to_string(x.linking) + ")";
      break;
    }
  }
  if (!run.success && run.reason.empty()) {
    run.success = x.linking >= goal_linking;
    run.reason = run.success ? "virtual-linking goal reached"
                             : "step limit of " + std::to_string(o.max_steps) + " reached";
  }
  run.final_state = x;
  return run;
}

}  // namespace claspplan::servo
