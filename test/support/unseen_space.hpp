// An independent check that a robot motion stays out of the space no sensor saw: points sampled
// inside every collision shape of the moving links, along the motion, against the sensed map
// (perception/sensed_space.hpp), without the planner's collision world or FCL.
#pragma once

#include <algorithm>
#include <cmath>
#include <optional>
#include <string>
#include <vector>

#include <Eigen/Geometry>

#include "perception/sensed_space.hpp"
#include "robots/kinematics.hpp"
#include "robots/robot_model.hpp"

namespace claspplan::test {

/// Points on a grid of spacing `step` inside one collision shape, in the shape's frame (the
/// shape's surface included).
inline std::vector<Eigen::Vector3d> shape_interior(const robots::CollisionShape& s, double step) {
  using Type = robots::CollisionShape::Type;
  Eigen::Vector3d half;
  if (s.type == Type::kBox) {
    half = 0.5 * s.size;
  } else if (s.type == Type::kSphere) {
    half = Eigen::Vector3d::Constant(s.radius);
  } else {
    const double axis = 0.5 * s.length + (s.type == Type::kCapsule ? s.radius : 0.0);
    half = Eigen::Vector3d(s.radius, s.radius, axis);
  }
  const auto inside = [&](const Eigen::Vector3d& p) {
    switch (s.type) {
      case Type::kBox:
        return true;
      case Type::kSphere:
        return p.norm() <= s.radius;
      case Type::kCylinder:
        return p.head<2>().norm() <= s.radius;
      case Type::kCapsule: {
        const double z = std::clamp(p.z(), -0.5 * s.length, 0.5 * s.length);
        return (p - Eigen::Vector3d(0, 0, z)).norm() <= s.radius;
      }
    }
    return false;
  };
  std::vector<Eigen::Vector3d> out;
  const Eigen::Vector3i n = (2.0 * half / step).array().ceil().cast<int>().max(1);
  for (int i = 0; i <= n.x(); ++i)
    for (int j = 0; j <= n.y(); ++j)
      for (int k = 0; k <= n.z(); ++k) {
        const Eigen::Vector3d p =
            -half + Eigen::Vector3d(2.0 * half.x() * i / n.x(), 2.0 * half.y() * j / n.y(),
                                    2.0 * half.z() * k / n.z());
        if (inside(p)) out.push_back(p);
      }
  return out;
}

/// The first point of a moving link's shape that lies in an unknown voxel of `space`, along the
/// waypoints interpolated so that no joint moves more than `resolution` between samples; a line
/// naming the link and the sample, or nothing. Links that no joint moves (the base) are skipped.
inline std::optional<std::string> first_in_unseen_space(
    const robots::RobotModel& model, const std::vector<Eigen::VectorXd>& waypoints,
    const perception::SensedSpace& space, double resolution, double step = 0.004) {
  std::vector<bool> moves(model.links.size(), false);
  for (std::size_t l = 0; l < model.links.size(); ++l) {
    const robots::Link& link = model.links[l];
    moves[l] = (link.parent >= 0 && moves[link.parent]) ||
               (link.type != robots::JointType::kFixed && link.q_index >= 0);
  }
  std::vector<std::vector<Eigen::Vector3d>> interior;
  for (const auto& s : model.shapes) interior.push_back(shape_interior(s, step));
  robots::RobotData data(model);
  for (std::size_t w = 0; w < waypoints.size(); ++w) {
    const Eigen::VectorXd& a = waypoints[w];
    const Eigen::VectorXd& b = w + 1 < waypoints.size() ? waypoints[w + 1] : a;
    const int samples =
        std::max(1, static_cast<int>(std::ceil((b - a).cwiseAbs().maxCoeff() / resolution)));
    for (int k = 0; k < samples; ++k) {
      const Eigen::VectorXd q = a + (b - a) * (static_cast<double>(k) / samples);
      robots::forward_kinematics(model, q, data);
      for (std::size_t s = 0; s < model.shapes.size(); ++s) {
        const robots::CollisionShape& shape = model.shapes[s];
        if (!moves[shape.link]) continue;
        const Eigen::Isometry3d pose = data.link_poses[shape.link] * shape.origin;
        for (const auto& p : interior[s]) {
          const Eigen::Vector3d x = pose * p;
          if (space.region().contains(x) && space.at(x) == perception::Sensed::kUnknown)
            return model.links[shape.link].name + " at waypoint " + std::to_string(w) + " (+" +
                   std::to_string(k) + "/" + std::to_string(samples) + ") reaches (" +
                   std::to_string(x.x()) + ", " + std::to_string(x.y()) + ", " +
                   std::to_string(x.z()) + ")";
        }
      }
    }
  }
  return std::nullopt;
}

}  // namespace claspplan::test
