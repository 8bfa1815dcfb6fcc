// A first hand description for a robot nobody has described yet, drafted from its URDF(s): the
// arm chain, the fingers below the hand's root, finger curves, tcp, v_fwd and v_swd, the open
// pre-shape and closing directions, a vlink_goal from the closed aperture, and the link pairs to
// allow in self-collision checks, found by sampling configurations. Every guess is reported, so
// the user knows which lines to check (`claspplan describe`).
#pragma once

#include <cstdint>
#include <filesystem>
#include <string>
#include <vector>

#include <Eigen/Core>

#include "robots/robot_model.hpp"

namespace claspplan::robots {

struct DraftOptions {
  std::filesystem::path urdf;       ///< the arm's URDF (or the whole robot's)
  std::filesystem::path hand_urdf;  ///< optional: a hand's own URDF, mounted on `mount`
  std::string mount;                ///< the arm link the hand's URDF is mounted on
  Eigen::Vector3d mount_xyz = Eigen::Vector3d::Zero();  ///< the hand's root in the mount's frame
  Eigen::Vector3d mount_rpy = Eigen::Vector3d::Zero();  ///< and its turn (URDF roll, pitch, yaw)
  /// The hand's root link in `hand_urdf` (default: its root): a hand cut from a humanoid's URDF.
  std::string hand_urdf_root;
  std::vector<std::string> replaces;  ///< the arm's own gripper links, left out for the hand
  bool mesh_hulls = false;            ///< collide meshes as their convex hulls
  /// The fingers' mimic joints as adaptive joints (Joint::follows): an underactuated hand, whose
  /// fingers follow their motor until each stops on its own at contact.
  bool adaptive = false;
  /// The arm's home (the vendor's): written as arm.home, and link pairs in contact there are
  /// allowed. Default: every joint at 0 (within its limits), and nothing is allowed for it.
  std::vector<double> home;
  std::string hand_root;  ///< the hand's root link; default: the first link with 2+ moving branches
  std::string name;       ///< default: the URDFs' robot names
  /// Where the description will be written: its file paths are relative to this file's folder.
  std::filesystem::path out = "robot.yaml";
  int samples = 1000;      ///< random configurations for the allowed collision pairs
  std::uint64_t seed = 1;  ///< of those configurations
};

struct DescriptionDraft {
  std::string yaml;                  ///< the commented hand description
  std::vector<std::string> guesses;  ///< what was guessed and should be checked, one line each
  std::vector<std::string> allowed;  ///< the allowed pairs, "link_a / link_b (why)"
  int never_colliding_pairs = 0;     ///< pairs that never touched in the samples
  RobotModel model;                  ///< the description, loaded
};

/// Drafts the description. InputError for unreadable URDFs, an unknown link, or a robot without a
/// recognisable hand (no link with two or more branches holding moving joints: name --hand-root).
DescriptionDraft draft_description(const DraftOptions& options);

}  // namespace claspplan::robots
