// Internals of draft_description() (not installed): the draft as it is built, its YAML, and the
// rules that read the hand's geometry (hand_draft.cpp).
#pragma once

#include <string>
#include <utility>
#include <vector>

#include <Eigen/Core>

#include "robots/robot_model.hpp"

namespace claspplan::robots::draft_detail {

struct JointDraft {
  std::string name;
  double lower = 0.0, upper = 0.0, open = 0.0;
  int closing = 0;
  std::string follows;  // an adaptive joint: the joint it follows (and opens with)
};

struct CurvePoint {
  std::string link;
  Eigen::Vector3d xyz = Eigen::Vector3d::Zero();
  bool offset = false;
};

struct FingerDraft {
  std::string name;
  bool thumb = false;
  std::vector<int> chain;  // tree links, the hand's root side first
  std::vector<std::string> links, joints;
  CurvePoint tip;
};

// Everything the description says, as drafted so far.
struct Draft {
  std::string name, urdf, hand_urdf, hand_urdf_root, mount, tool_link, base_link;
  std::vector<std::string> replaces;
  bool mesh_hulls = false, home_given = false;
  Eigen::Vector3d mount_xyz = Eigen::Vector3d::Zero(), mount_rpy = Eigen::Vector3d::Zero();
  std::vector<JointDraft> arm, hand;
  std::vector<FingerDraft> fingers;
  std::vector<std::pair<std::string, std::vector<CurvePoint>>> curves;
  CurvePoint tcp;
  Eigen::Vector3d v_fwd = Eigen::Vector3d::UnitZ(), v_swd = Eigen::Vector3d::UnitY();
  double vlink_goal = 0.8;
  std::string vlink_note;
  std::vector<std::pair<std::string, std::string>> allowed;
};

/// A number as the description writes it: lengths to 0.1 mm; joint values (`exact`) to the digit,
/// as a limit they may sit on is written.
std::string draft_number(double v, bool exact = false);

/// The commented hand description.
std::string to_yaml(const Draft& d);

/// The part of the draft the hand's geometry at its open pre-shape decides (`m`: the draft
/// loaded): the thumb, its turn, closing directions, finger links, v_fwd, v_swd and the curves.
void shape_hand(Draft& d, const RobotModel& m, std::vector<std::string>& guesses);

}  // namespace claspplan::robots::draft_detail
