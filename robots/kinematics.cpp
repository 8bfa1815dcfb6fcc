#include "robots/kinematics.hpp"

#include <stdexcept>
#include <string>

namespace claspplan::robots {

RobotData::RobotData(const RobotModel& model)
    : q(Eigen::VectorXd::Zero(model.dof())),
      link_poses(model.links.size(), Eigen::Isometry3d::Identity()),
      joint_axes(model.links.size(), Eigen::Vector3d::Zero()) {}

void forward_kinematics(const RobotModel& model, const Eigen::VectorXd& q, RobotData& data) {
  if (q.size() != model.dof()) {
    throw std::invalid_argument(model.name + ": q has " + std::to_string(q.size()) +
                                " values, the robot has " + std::to_string(model.dof()) +
                                " actuated joints");
  }
  const size_t n = model.links.size();
  if (data.link_poses.size() != n) {
    data.link_poses.assign(n, Eigen::Isometry3d::Identity());
    data.joint_axes.assign(n, Eigen::Vector3d::Zero());
  }
  data.q = q;
  data.link_poses[0].setIdentity();
  for (size_t i = 1; i < n; ++i) {
    const Link& l = model.links[i];
    const Eigen::Isometry3d& parent = data.link_poses[l.parent];
    Eigen::Isometry3d& pose = data.link_poses[i];
    if (l.type == JointType::kFixed) {
      pose = parent * l.origin;
      continue;
    }
    const double value = l.q_index >= 0 ? l.multiplier * q[l.q_index] + l.offset : l.offset;
    pose = parent * l.origin;
    if (l.type == JointType::kRevolute) {
      pose.linear() = pose.linear() * Eigen::AngleAxisd(value, l.axis).toRotationMatrix();
    } else {
      pose.translation() += pose.linear() * (value * l.axis);
    }
    data.joint_axes[i] = pose.linear() * l.axis;
  }
}

Eigen::Vector3d point_position(const RobotData& data, const LinkPoint& p) {
  return data.link_poses[p.link] * p.point;
}

Eigen::Isometry3d shape_pose(const RobotData& data, const CollisionShape& shape) {
  return data.link_poses[shape.link] * shape.origin;
}

namespace {

// Adds the columns of a world point p on `link` to J (3 × dof, zeroed by the caller).
template <typename Block>
void add_point_columns(const RobotModel& model, const RobotData& data, int link,
                       const Eigen::Vector3d& p, Block&& J) {
  for (int a : model.links[link].support) {
    const Link& l = model.links[a];
    const Eigen::Vector3d& axis = data.joint_axes[a];
    if (l.type == JointType::kRevolute) {
      J.col(l.column) += l.column_multiplier * axis.cross(p - data.link_poses[a].translation());
    } else {
      J.col(l.column) += l.column_multiplier * axis;
    }
  }
}

}  // namespace

Eigen::Matrix<double, 3, Eigen::Dynamic> point_jacobian(const RobotModel& model,
                                                        const RobotData& data, int link,
                                                        const Eigen::Vector3d& local_point) {
  Eigen::Matrix<double, 3, Eigen::Dynamic> J = Eigen::MatrixXd::Zero(3, model.dof());
  add_point_columns(model, data, link, data.link_poses[link] * local_point, J);
  return J;
}

Eigen::Matrix<double, 3, Eigen::Dynamic> angular_jacobian(const RobotModel& model,
                                                          const RobotData& data, int link) {
  Eigen::Matrix<double, 3, Eigen::Dynamic> J = Eigen::MatrixXd::Zero(3, model.dof());
  for (int a : model.links[link].support) {
    const Link& l = model.links[a];
    if (l.type == JointType::kRevolute) J.col(l.column) += l.column_multiplier * data.joint_axes[a];
  }
  return J;
}

Eigen::Vector3d vector_direction(const RobotData& data, const LinkVector& v) {
  return data.link_poses[v.link].linear() * v.vector;
}

Eigen::Matrix<double, 3, Eigen::Dynamic> vector_jacobian(const RobotModel& model,
                                                         const RobotData& data,
                                                         const LinkVector& v) {
  // dv/dt = ω × v = −v × ω.
  const Eigen::Vector3d w = vector_direction(data, v);
  Eigen::Matrix3d skew;
  skew << 0, -w.z(), w.y(), w.z(), 0, -w.x(), -w.y(), w.x(), 0;
  return -skew * angular_jacobian(model, data, v.link);
}

void finger_curves(const RobotModel& model, const RobotData& data, FingerCurvesData& out,
                   bool with_jacobians) {
  const size_t nc = model.curves.size();
  out.points.resize(nc);
  if (with_jacobians) out.jacobians.resize(nc);
  for (size_t c = 0; c < nc; ++c) {
    const auto& pts = model.curves[c].points;
    auto& world = out.points[c];
    world.resize(pts.size());
    for (size_t i = 0; i < pts.size(); ++i) world[i] = data.link_poses[pts[i].link] * pts[i].point;
    if (!with_jacobians) continue;
    auto& J = out.jacobians[c];
    J.resize(pts.size());
    for (size_t i = 0; i < pts.size(); ++i) {
      J[i].setZero(3, model.dof());  // no allocation once sized
      add_point_columns(model, data, pts[i].link, world[i], J[i]);
    }
  }
}

void finger_curves(const RobotModel& model, const Eigen::VectorXd& q, RobotData& data,
                   FingerCurvesData& out, bool with_jacobians) {
  forward_kinematics(model, q, data);
  finger_curves(model, data, out, with_jacobians);
}

}  // namespace claspplan::robots
