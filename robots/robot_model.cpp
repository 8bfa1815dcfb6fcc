// RobotModel's members and load_robot(): finding the hand description and its URDF (built in or
// on disk). Reading them: urdf_tree.cpp and hand_description.cpp.
#include "robots/robot_model.hpp"

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <stdexcept>

#include "core/input_error.hpp"
#include "robots/embedded_models.hpp"
#include "robots/robot_model_detail.hpp"

namespace claspplan::robots {

const char* shape_type_name(CollisionShape::Type type) {
  switch (type) {
    case CollisionShape::Type::kBox:
      return "box";
    case CollisionShape::Type::kSphere:
      return "sphere";
    case CollisionShape::Type::kCylinder:
      return "cylinder";
    case CollisionShape::Type::kCapsule:
      return "capsule";
    case CollisionShape::Type::kMesh:
      return "mesh";
  }
  return "unknown";
}

Eigen::AlignedBox3d shape_bounds(const CollisionShape& s) {
  using Type = CollisionShape::Type;
  Eigen::Vector3d half = Eigen::Vector3d::Zero();
  switch (s.type) {
    case Type::kBox:
      half = 0.5 * s.size;
      break;
    case Type::kSphere:
      half.setConstant(s.radius);
      break;
    case Type::kCylinder:
    case Type::kCapsule:
      half = Eigen::Vector3d(s.radius, s.radius,
                             0.5 * s.length + (s.type == Type::kCapsule ? s.radius : 0.0));
      break;
    case Type::kMesh:
      return bounds(*s.mesh);
  }
  return {-half, half};
}

double shape_reach(const CollisionShape& s) {
  using Type = CollisionShape::Type;
  switch (s.type) {
    case Type::kBox:
      return 0.5 * s.size.norm();
    case Type::kSphere:
      return s.radius;
    case Type::kCylinder:
      return std::hypot(s.radius, 0.5 * s.length);
    case Type::kCapsule:
      return s.radius + 0.5 * s.length;
    case Type::kMesh: {
      double r = 0.0;
      for (const auto& v : s.mesh->vertices) r = std::max(r, v.norm());
      return r;
    }
  }
  return 0.0;
}

// ---------------------------------------------------------------------------------------------
// RobotModel members

int RobotModel::find_link(const std::string& link_name) const {
  for (size_t i = 0; i < links.size(); ++i)
    if (links[i].name == link_name) return static_cast<int>(i);
  return -1;
}

int RobotModel::find_joint(const std::string& joint_name) const {
  for (size_t i = 0; i < joints.size(); ++i)
    if (joints[i].name == joint_name) return static_cast<int>(i);
  return -1;
}

int RobotModel::link_index(const std::string& link_name) const {
  const int i = find_link(link_name);
  if (i < 0) throw InputError(name + ": no link named '" + link_name + "'");
  return i;
}

int RobotModel::joint_index(const std::string& joint_name) const {
  const int i = find_joint(joint_name);
  if (i < 0) throw InputError(name + ": no actuated joint named '" + joint_name + "'");
  return i;
}

Eigen::VectorXd RobotModel::lower() const {
  Eigen::VectorXd v(dof());
  for (int i = 0; i < dof(); ++i) v[i] = joints[i].lower;
  return v;
}

Eigen::VectorXd RobotModel::upper() const {
  Eigen::VectorXd v(dof());
  for (int i = 0; i < dof(); ++i) v[i] = joints[i].upper;
  return v;
}

Eigen::VectorXd RobotModel::clamp(const Eigen::VectorXd& q) const {
  Eigen::VectorXd c = q;
  for (int i = 0; i < dof() && i < q.size(); ++i)
    c[i] = std::min(std::max(q[i], joints[i].lower), joints[i].upper);
  return c;
}

bool RobotModel::within_limits(const Eigen::VectorXd& q, double tolerance) const {
  if (q.size() != dof()) return false;
  for (int i = 0; i < dof(); ++i) {
    if (!std::isfinite(q[i])) return false;
    if (q[i] < joints[i].lower - tolerance || q[i] > joints[i].upper + tolerance) return false;
  }
  return true;
}

Eigen::VectorXd RobotModel::couple(const Eigen::VectorXd& q) const {
  Eigen::VectorXd c = q;
  for (int i = arm_dof; i < dof() && i < q.size(); ++i) {
    const Joint& j = joints[i];
    if (j.follows < 0) continue;
    const double v = j.follow_multiplier * q[j.follows] + j.follow_offset;
    c[i] = std::min(std::max(v, j.lower), j.upper);
  }
  return c;
}

Eigen::VectorXd RobotModel::open_hand(const Eigen::VectorXd& q) const {
  Eigen::VectorXd r = q;
  for (int i = arm_dof; i < dof(); ++i) r[i] = joints[i].open;
  return r;
}

Eigen::VectorXd RobotModel::complete_q(const std::vector<double>& prefix) const {
  if (static_cast<int>(prefix.size()) > dof()) {
    throw InputError(name + " has " + std::to_string(dof()) + " actuated joints, got " +
                     std::to_string(prefix.size()) + " values");
  }
  Eigen::VectorXd q = home;
  for (size_t i = 0; i < prefix.size(); ++i) {
    const Joint& j = joints[i];
    const double v = prefix[i];
    if (!std::isfinite(v)) {
      throw InputError("value " + std::to_string(i + 1) + " (" + j.name +
                       ") is not a finite number");
    }
    if (v < j.lower - 1e-9 || v > j.upper + 1e-9) {
      std::ostringstream s;
      s << j.name << " = " << v << " is outside its limits [" << j.lower << ", " << j.upper << "]";
      throw InputError(s.str());
    }
    q[i] = std::min(std::max(v, j.lower), j.upper);
  }
  return q;
}

namespace robot_model_detail {

[[noreturn]] void fail(const std::string& file, const std::string& what) {
  throw InputError(file + ": " + what);
}

std::string read_text_file(const std::filesystem::path& path, const std::string& what) {
  std::error_code ec;
  if (!std::filesystem::is_regular_file(path, ec))
    throw InputError(path.string() + ": " + what + " not found or not a regular file");
  const auto size = std::filesystem::file_size(path, ec);
  if (ec) throw InputError(path.string() + ": cannot read the " + what);
  if (size > 64u * 1024u * 1024u)
    throw InputError(path.string() + ": the " + what + " is larger than 64 MB");
  std::ifstream in(path, std::ios::binary);
  if (!in) throw InputError(path.string() + ": cannot open the " + what);
  std::stringstream ss;
  ss << in.rdbuf();
  return ss.str();
}

}  // namespace robot_model_detail

namespace {

using robot_model_detail::build_robot;
using robot_model_detail::read_text_file;

RobotModel load_robot_unchecked(const std::string& name_or_path) {
  const auto names = builtin_robots();
  if (std::find(names.begin(), names.end(), name_or_path) != names.end()) {
    const std::string yaml_name = name_or_path + ".yaml";
    const char* yaml = embedded_model_file(yaml_name);
    if (!yaml) throw std::logic_error("built-in robot file " + yaml_name + " is not embedded");
    return build_robot(
        yaml, yaml_name,
        [](const std::string& urdf_name) {
          const char* text = embedded_model_file(urdf_name);
          if (!text) throw InputError(urdf_name + ": not one of the built-in model files");
          return std::make_pair(urdf_name, std::string(text));
        },
        name_or_path);
  }
  const std::filesystem::path path(name_or_path);
  std::error_code ec;
  if (!std::filesystem::exists(path, ec)) {
    std::string list;
    for (const auto& n : names) list += (list.empty() ? "" : ", ") + n;
    throw InputError("robot '" + name_or_path + "' is neither a built-in robot (" + list +
                     ") nor an existing hand-description file");
  }
  const std::string yaml = read_text_file(path, "hand description");
  return build_robot(
      yaml, path.string(),
      [&](const std::string& urdf_name) {
        const std::filesystem::path urdf_path = path.parent_path() / urdf_name;
        return std::make_pair(urdf_path.string(), read_text_file(urdf_path, "URDF file"));
      },
      path.string());
}

}  // namespace

std::vector<std::string> builtin_robots() {
  return {"kr5_sdh", "kr5_dlr", "kr5_icub", "kr5_armar3"};
}

RobotModel load_robot(const std::string& name_or_path) {
  // Whatever check a description fails, deep in the model's construction too, is about the file.
  return as_input_error([&] { return load_robot_unchecked(name_or_path); });
}

RobotModel load_robot_from_text(const std::string& yaml_text, const std::string& urdf_text,
                                const std::string& yaml_name, const std::string& urdf_name) {
  return as_input_error([&] {
    return build_robot(
        yaml_text, yaml_name,
        [&](const std::string&) { return std::make_pair(urdf_name, urdf_text); }, yaml_name);
  });
}

}  // namespace claspplan::robots
