#include "robots/hand_size.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <vector>

#include <Eigen/Eigenvalues>

#include "core/polygon.hpp"
#include "robots/kinematics.hpp"

namespace claspplan::robots {
namespace {

double closed_length(const std::vector<Eigen::Vector3d>& c) {
  double l = 0.0;
  for (std::size_t i = 0; i < c.size(); ++i) l += (c[(i + 1) % c.size()] - c[i]).norm();
  return l;
}

// 1 - cord / closed length: the factor of paper eq. 2, what the curve's VLk is when it links.
double cord_ratio(const std::vector<Eigen::Vector3d>& c) {
  const double total = closed_length(c);
  return total > 0 ? 1.0 - (c.back() - c.front()).norm() / total : 0.0;
}

// The largest circle inside the closed curve, in its least-squares plane: its diameter and
// centre.
std::pair<double, Eigen::Vector3d> inscribed_circle(const std::vector<Eigen::Vector3d>& c) {
  Eigen::Vector3d mean = Eigen::Vector3d::Zero();
  for (const auto& p : c) mean += p;
  mean /= static_cast<double>(c.size());
  Eigen::Matrix3d cov = Eigen::Matrix3d::Zero();
  for (const auto& p : c) cov += (p - mean) * (p - mean).transpose();
  const Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> es(cov);
  const Eigen::Vector3d e1 = es.eigenvectors().col(2), e2 = es.eigenvectors().col(1);
  std::vector<Eigen::Vector2d> poly;
  Eigen::AlignedBox2d box;
  for (const auto& p : c) {
    poly.emplace_back((p - mean).dot(e1), (p - mean).dot(e2));
    box.extend(poly.back());
  }
  const double step = std::max(box.sizes().maxCoeff() / 100.0, 1e-5);
  double best = 0.0;
  Eigen::Vector2d centre = box.center();
  for (double x = box.min().x(); x <= box.max().x(); x += step) {
    for (double y = box.min().y(); y <= box.max().y(); y += step) {
      const Eigen::Vector2d q(x, y);
      if (!inside_polygon(poly, q)) continue;
      double d = std::numeric_limits<double>::infinity();
      for (std::size_t i = 0; i < poly.size(); ++i)
        d = std::min(d, segment_distance(q, poly[i], poly[(i + 1) % poly.size()]));
      if (d > best) {
        best = d;
        centre = q;
      }
    }
  }
  return {2.0 * best, mean + centre.x() * e1 + centre.y() * e2};
}

}  // namespace

double cross_section(const CollisionShape& s) {
  switch (s.type) {
    case CollisionShape::Type::kBox:
    case CollisionShape::Type::kMesh: {
      Eigen::Vector3d e = shape_bounds(s).sizes();
      std::sort(e.data(), e.data() + 3);
      return std::hypot(e[0], e[1]);
    }
    case CollisionShape::Type::kSphere:
    case CollisionShape::Type::kCylinder:
    case CollisionShape::Type::kCapsule:
      return 2.0 * s.radius;
  }
  return 0.0;
}

std::vector<HandSize> hand_sizes(const RobotModel& model, const std::vector<double>& goals) {
  if (!std::is_sorted(goals.begin(), goals.end()))
    throw std::invalid_argument("hand_sizes: the goals must be in ascending order");
  HandSize open;
  // The links the finger's own joints move (not a knuckle base that stays outside the hole).
  for (const Finger& f : model.fingers) {
    for (int link : f.links) {
      bool moved = false;
      for (int s : model.links[link].support)
        moved |=
            std::find(f.joints.begin(), f.joints.end(), model.links[s].q_index) != f.joints.end();
      if (!moved) continue;
      for (int s : model.links[link].shapes) {
        const double t = cross_section(model.shapes[s]);
        if (t > open.finger_thickness) {
          open.finger_thickness = t;
          open.thickest_link = link;
        }
      }
    }
  }
  std::vector<HandSize> sizes;
  // The hand at q, its curves and their mean cord ratio as the sweep saw them last.
  const auto closed = [&](const Eigen::VectorXd& q, const FingerCurvesData& curves, double ratio) {
    HandSize size = open;
    size.closed_q = q.tail(model.hand_dof);
    size.closed_ratio = ratio;
    double aperture = std::numeric_limits<double>::infinity();
    for (const auto& c : curves.points) {
      const auto [diameter, centre] = inscribed_circle(c);
      aperture = std::min(aperture, diameter);
      size.closed_centre += centre / static_cast<double>(curves.points.size());
    }
    size.closed_aperture =
        std::isfinite(aperture) ? std::max(0.0, aperture - size.finger_thickness) : 0.0;
    sizes.push_back(size);
  };

  // Close from the open pre-shape; each goal's hand is the first whose mean cord ratio reaches it
  // (eq. 4 averages), else the last one: the joints at their limits or 2000 steps done.
  constexpr double kStep = 0.005;  // rad per joint and step
  Eigen::VectorXd q = model.home;
  RobotData data(model);
  FingerCurvesData curves;
  const Eigen::VectorXd lower = model.lower(), upper = model.upper();
  double ratio = 0.0;
  for (int k = 0; k < 2000 && sizes.size() < goals.size(); ++k) {
    finger_curves(model, q, data, curves, false);
    double mean = 0.0;
    for (const auto& c : curves.points) mean += cord_ratio(c);
    ratio = curves.points.empty() ? 0.0 : mean / static_cast<double>(curves.points.size());
    if (curves.points.empty()) break;
    while (sizes.size() < goals.size() && ratio >= goals[sizes.size()]) closed(q, curves, ratio);
    if (sizes.size() == goals.size()) break;
    Eigen::VectorXd next = q;
    for (int j = model.arm_dof; j < model.dof(); ++j) next[j] += model.joints[j].closing * kStep;
    next = next.cwiseMax(lower).cwiseMin(upper);
    if (next == q) break;  // every closing joint at its limit
    q = next;
  }
  while (sizes.size() < goals.size()) closed(q, curves, ratio);
  return sizes;
}

HandSize hand_size(const RobotModel& model) {
  return hand_sizes(model, {model.vlink_goal}).front();
}

}  // namespace claspplan::robots
