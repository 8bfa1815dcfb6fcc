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
/// shape's surface included); a mesh's vertices and triangle centres (its surface only).
inline std::vector<Eigen::Vector3d> shape_interior(const robots::CollisionShape& s, double step) {
  using Type = robots::CollisionShape::Type;
  if (s.type == Type::kMesh) {
    std::vector<Eigen::Vector3d> out = s.mesh->vertices;
    for (const auto& t : s.mesh->triangles)
      out.push_back((s.mesh->vertices[t[0]] + s.mesh->vertices[t[1]] + s.mesh->vertices[t[2]]) /
                    3.0);
    return out;
  }
  const Eigen::Vector3d half = robots::shape_bounds(s).max();
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
      case Type::kMesh:
        break;
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

/// The robot's moving shapes filled with points, checked against a sensed map: built once,
/// then any number of motions.
class UnseenSpaceProbe {
 public:
  UnseenSpaceProbe(const robots::RobotModel& model, const perception::SensedSpace& space,
                   double step = 0.004)
      : UnseenSpaceProbe(model, space, nullptr, step) {}
  /// With a finer map over part of the region (tsrrt::ClaspResult::sensed_near_loop), which
  /// stands for `space` where it has voxels; null: none.
  UnseenSpaceProbe(const robots::RobotModel& model, const perception::SensedSpace& space,
                   const perception::SensedSpace* finer, double step = 0.004)
      : model_(model),
        space_(space),
        finer_(finer && !finer->empty() ? finer : nullptr),
        data_(model),
        moves_(model.links.size(), false) {
    for (std::size_t l = 0; l < model.links.size(); ++l) {
      const robots::Link& link = model.links[l];
      moves_[l] = (link.parent >= 0 && moves_[link.parent]) ||
                  (link.type != robots::JointType::kFixed && link.q_index >= 0);
    }
    for (const auto& s : model.shapes) {
      interior_.push_back(shape_interior(s, step));
      double r = 0.0;
      for (const auto& p : interior_.back()) r = std::max(r, p.norm());
      reach_.push_back(r);
    }
  }

  /// The first point of a moving link's shape that lies in an unknown voxel, along the waypoints
  /// interpolated so that no joint moves more than `resolution` between samples; a line naming
  /// the link and the sample, or nothing. Links that no joint moves (the base) are skipped, and
  /// so are shapes wholly outside the map's region (unknown there is not near the object).
  std::optional<std::string> first_in(const std::vector<Eigen::VectorXd>& waypoints,
                                      double resolution) {
    for (std::size_t w = 0; w < waypoints.size(); ++w) {
      const Eigen::VectorXd& a = waypoints[w];
      const Eigen::VectorXd& b = w + 1 < waypoints.size() ? waypoints[w + 1] : a;
      const int samples =
          std::max(1, static_cast<int>(std::ceil((b - a).cwiseAbs().maxCoeff() / resolution)));
      for (int k = 0; k < samples; ++k) {
        const Eigen::VectorXd q = a + (b - a) * (static_cast<double>(k) / samples);
        if (auto hit = first_at(q))
          return *hit + " at waypoint " + std::to_string(w) + " (+" + std::to_string(k) + "/" +
                 std::to_string(samples) + ")";
      }
    }
    return std::nullopt;
  }

 private:
  std::optional<std::string> first_at(const Eigen::VectorXd& q) {
    robots::forward_kinematics(model_, q, data_);
    for (std::size_t s = 0; s < model_.shapes.size(); ++s) {
      const robots::CollisionShape& shape = model_.shapes[s];
      if (!moves_[shape.link]) continue;
      const Eigen::Isometry3d pose = data_.link_poses[shape.link] * shape.origin;
      if (space_.region().exteriorDistance(pose.translation()) > reach_[s]) continue;
      for (const auto& p : interior_[s]) {
        const Eigen::Vector3d x = pose * p;
        if (space_.region().contains(x) &&
            perception::sensed_at(space_, finer_, x) == perception::Sensed::kUnknown)
          return model_.links[shape.link].name + " reaches (" + std::to_string(x.x()) + ", " +
                 std::to_string(x.y()) + ", " + std::to_string(x.z()) + ")";
      }
    }
    return std::nullopt;
  }

  const robots::RobotModel& model_;
  const perception::SensedSpace& space_;
  const perception::SensedSpace* finer_;
  robots::RobotData data_;
  std::vector<bool> moves_;
  std::vector<std::vector<Eigen::Vector3d>> interior_;
  std::vector<double> reach_;  // the farthest interior point from the shape's origin
};

/// One motion through UnseenSpaceProbe::first_in.
inline std::optional<std::string> first_in_unseen_space(
    const robots::RobotModel& model, const std::vector<Eigen::VectorXd>& waypoints,
    const perception::SensedSpace& space, double resolution, double step = 0.004,
    const perception::SensedSpace* finer = nullptr) {
  return UnseenSpaceProbe(model, space, finer, step).first_in(waypoints, resolution);
}

}  // namespace claspplan::test
