#include "robots/motion_sampling.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <vector>

namespace claspplan::robots {
namespace {

// The farthest point of a link's shapes from the link's frame.
double shapes_radius(const RobotModel& model, const Link& link) {
  double r = 0.0;
  for (int s : link.shapes) {
    const CollisionShape& shape = model.shapes[s];
    const Eigen::AlignedBox3d box = shape_bounds(shape);
    for (int c = 0; c < 8; ++c) {
      const Eigen::Vector3d corner = box.corner(static_cast<Eigen::AlignedBox3d::CornerType>(c));
      r = std::max(r, (shape.origin * corner).norm());
    }
  }
  return r;
}

// How far a joint may slide the links below it from their place at value 0.
double prismatic_travel(const RobotModel& model, const Link& link) {
  if (link.type != JointType::kPrismatic) return 0.0;
  double extent = std::abs(link.offset);
  if (link.q_index >= 0) {
    const Joint& j = model.joints[link.q_index];
    extent += std::abs(link.multiplier) * std::max(std::abs(j.lower), std::abs(j.upper));
  }
  return extent;
}

}  // namespace

Eigen::VectorXd motion_reach(const RobotModel& model) {
  const int n = static_cast<int>(model.links.size());
  // radius[a]: the farthest shape point carried by link a's joint, from a's frame.
  std::vector<double> radius(n, 0.0);
  for (int d = 0; d < n; ++d) {
    double reach = shapes_radius(model, model.links[d]);
    for (int a = d; a >= 0; a = model.links[a].parent) {
      radius[a] = std::max(radius[a], reach);
      reach += model.links[a].origin.translation().norm() + prismatic_travel(model, model.links[a]);
    }
  }
  Eigen::VectorXd out = Eigen::VectorXd::Zero(model.dof());
  for (int a = 0; a < n; ++a) {
    const Link& l = model.links[a];
    if (l.column < 0 || l.type == JointType::kFixed) continue;
    const double lever = l.type == JointType::kRevolute ? radius[a] : 1.0;
    out[l.column] += std::abs(l.column_multiplier) * lever;
  }
  return out;
}

int motion_steps(const Eigen::VectorXd& reach, double travel, const Eigen::VectorXd& q0,
                 const Eigen::VectorXd& q1, double resolution) {
  if (!(resolution > 0) || !std::isfinite(resolution))
    throw std::invalid_argument("motion_free: resolution must be > 0");
  double samples = (q1 - q0).cwiseAbs().maxCoeff() / resolution;
  if (travel > 0) samples = std::max(samples, travel_bound(reach, q0, q1) / travel);
  if (samples > 1e6)
    throw std::invalid_argument(
        "motion_free: more than a million samples; use a coarser resolution");
  return std::max(1, static_cast<int>(std::ceil(samples)));
}

}  // namespace claspplan::robots
