// Internals of load_robot() (not installed): the steps that turn a hand description (YAML) and
// its URDF into a RobotModel. urdf_tree.cpp reads the URDF's links, joints and collision shapes;
// hand_description.cpp reads the YAML and checks it against the URDF; robot_model.cpp finds the
// files. Every problem is a one-line InputError naming the file.
#pragma once

#include <filesystem>
#include <functional>
#include <map>
#include <string>
#include <utility>
#include <vector>

#include <urdf_parser/urdf_parser.h>

#include "robots/robot_model.hpp"

namespace claspplan::robots::robot_model_detail {

/// Throws InputError "<file>: <what>".
[[noreturn]] void fail(const std::string& file, const std::string& what);

/// A text file's contents; InputError naming the file and `what` it should be when it is missing,
/// unreadable or over 64 MB.
std::string read_text_file(const std::filesystem::path& path, const std::string& what);

/// Parses a URDF; its errors (reported through console_bridge) become the exception's message.
urdf::ModelInterfaceSharedPtr parse_urdf(const std::string& text, const std::string& file);

/// The URDF's joints, for the checks of the hand description.
struct UrdfJoints {
  std::map<std::string, const urdf::Joint*> joint_of_link;  ///< by child link name
  std::map<std::string, int> link_by_joint;                 ///< link index by joint name
};

/// Fills model.links (parents first, depth-first) and model.shapes from the URDF tree, without
/// the links `left_out` and their subtrees.
UrdfJoints read_urdf_tree(const urdf::ModelInterface& urdf, const std::string& urdf_file,
                          RobotModel& model, const std::vector<std::string>& left_out = {});

/// The rotation of URDF roll, pitch, yaw (fixed axes X, then Y, then Z).
inline Eigen::Matrix3d rpy_rotation(const Eigen::Vector3d& rpy) {
  return (Eigen::AngleAxisd(rpy.z(), Eigen::Vector3d::UnitZ()) *
          Eigen::AngleAxisd(rpy.y(), Eigen::Vector3d::UnitY()) *
          Eigen::AngleAxisd(rpy.x(), Eigen::Vector3d::UnitX()))
      .toRotationMatrix();
}

/// Appends a second URDF's tree (a hand's) below link `parent`, its root at `origin` in the
/// parent's frame through a fixed joint "<parent>_to_<root>". `root` (default: the URDF's root)
/// takes only the subtree below that link: a hand cut from a whole robot's URDF (a humanoid's).
/// Link and joint names must be new.
void attach_urdf_tree(const urdf::ModelInterface& urdf, const std::string& urdf_file, int parent,
                      const Eigen::Isometry3d& origin, RobotModel& model, UrdfJoints& joints,
                      const std::string& root = "");

/// Reads a URDF: (its name for messages, its text), given the name the hand description uses.
using UrdfReader = std::function<std::pair<std::string, std::string>(const std::string&)>;

/// The model from a hand description's text and a way to read the URDF it names.
RobotModel build_robot(const std::string& yaml_text, const std::string& yaml_file,
                       const UrdfReader& read_urdf, const std::string& source);

}  // namespace claspplan::robots::robot_model_detail
