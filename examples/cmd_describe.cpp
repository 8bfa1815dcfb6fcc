// `claspplan describe URDF [--hand-urdf FILE --mount LINK] [--out FILE]`: a first hand
// description for a robot from its URDF(s) (robots/description_draft.hpp), written to --out, with
// what was guessed and what the drafted hand can clasp.
#include <cmath>
#include <cstdio>
#include <fstream>

#include "core/input_error.hpp"
#include "examples/command.hpp"
#include "perception/loops.hpp"
#include "robots/description_draft.hpp"
#include "robots/hand_size.hpp"

namespace claspplan::cli {
namespace {

struct DescribeOptions {
  robots::DraftOptions draft;
  std::vector<double> mount_xyz, mount_rpy;
  bool json = false;
};

// A flag of three numbers (CLI11 checks the count) as a vector: finite, or exit 2.
Eigen::Vector3d finite_vector3(const std::vector<double>& v, const std::string& flag) {
  for (double x : v)
    if (!std::isfinite(x)) throw InputError(flag + ": values must be finite");
  return {v[0], v[1], v[2]};
}

int run_describe(DescribeOptions o) {
  if (!o.mount_xyz.empty()) o.draft.mount_xyz = finite_vector3(o.mount_xyz, "--mount-xyz");
  if (!o.mount_rpy.empty()) o.draft.mount_rpy = finite_vector3(o.mount_rpy, "--mount-rpy");
  progress("drafting the description of " + o.draft.urdf.string() + " (sampling " +
           std::to_string(o.draft.samples) + " configurations for the allowed pairs) ...");
  const robots::DescriptionDraft d = robots::draft_description(o.draft);
  std::ofstream file(o.draft.out, std::ios::binary);
  if (!(file << d.yaml) || !file.flush())
    throw InputError(o.draft.out.string() + ": cannot write the description");
  const robots::RobotModel& m = d.model;
  const robots::HandSize size = robots::hand_size(m);
  if (o.json) {
    nlohmann::json fingers = nlohmann::json::array();
    for (const auto& f : m.fingers) fingers.push_back({{"name", f.name}, {"thumb", f.thumb}});
    print_json({{"file", o.draft.out.string()},
                {"name", m.name},
                {"arm_dof", m.arm_dof},
                {"hand_dof", m.hand_dof},
                {"fingers", fingers},
                {"guesses", d.guesses},
                {"allowed_pairs", d.allowed},
                {"never_colliding_pairs", d.never_colliding_pairs},
                {"vlink_goal", m.vlink_goal},
                {"hand",
                 {{"finger_thickness", size.finger_thickness},
                  {"closed_aperture", size.closed_aperture},
                  {"narrowest_hole", perception::narrowest_hole(size.finger_thickness)},
                  {"widest_bar", perception::widest_bar(size.closed_aperture)}}}});
    return kOk;
  }
  std::printf("wrote %s: %s, %d arm joints, %d hand joints, %zu fingers\n",
              o.draft.out.string().c_str(), m.name.c_str(), m.arm_dof, m.hand_dof,
              m.fingers.size());
  std::printf("guessed (check these lines of the file):\n");
  for (const auto& g : d.guesses) std::printf("  %s\n", g.c_str());
  std::printf("allowed collision pairs: %zu; %d pairs never touched in %d configurations\n",
              d.allowed.size(), d.never_colliding_pairs, o.draft.samples);
  for (const auto& a : d.allowed) std::printf("  %s\n", a.c_str());
  std::printf(
      "hand: fingers %.1f cm thick, closed aperture %.1f cm at vlink_goal %.2f: clasps holes from "
      "%.1f cm wide and bars up to %.1f cm thick\n",
      100.0 * size.finger_thickness, 100.0 * size.closed_aperture, m.vlink_goal,
      100.0 * perception::narrowest_hole(size.finger_thickness),
      100.0 * perception::widest_bar(size.closed_aperture));
  std::printf("next: claspplan robot %s --start-above X,Y,Z, then plan on a ring (README)\n",
              o.draft.out.string().c_str());
  return kOk;
}

}  // namespace

void add_describe_command(CLI::App& app, Action& action) {
  auto o = std::make_shared<DescribeOptions>();
  CLI::App* cmd = app.add_subcommand("describe", command_description("describe"));
  cmd->add_option("URDF", o->draft.urdf, "the arm's URDF (or the whole robot's), xacro expanded")
      ->required();
  cmd->add_option("--hand-urdf", o->draft.hand_urdf, "a hand's own URDF, mounted on --mount");
  cmd->add_option("--mount", o->draft.mount, "the arm link the hand's URDF is mounted on");
  cmd->add_option("--mount-xyz", o->mount_xyz,
                  "x,y,z (m): the hand's root in the mount link's frame (default 0,0,0)")
      ->delimiter(',')
      ->expected(3);
  cmd->add_option("--mount-rpy", o->mount_rpy,
                  "r,p,y (rad): the hand's root's turn in the mount link's frame (default 0,0,0)")
      ->delimiter(',')
      ->expected(3);
  cmd->add_option("--hand-urdf-root", o->draft.hand_urdf_root,
                  "take the hand from --hand-urdf's subtree below this link (a hand cut from a "
                  "whole robot's URDF; default: its root)");
  cmd->add_option("--home", o->draft.home,
                  "Q1,Q2,...: the arm's home (the vendor's, radians); link pairs in contact there "
                  "are allowed (default: all 0, nothing allowed for it)")
      ->delimiter(',');
  cmd->add_option("--replaces", o->draft.replaces,
                  "links of the arm's own gripper to leave out for --hand-urdf's hand (each with "
                  "its subtree)");
  cmd->add_flag("--mesh-hulls", o->draft.mesh_hulls,
                "collide mesh links as their convex hulls (faster, for large meshes)");
  cmd->add_flag("--adaptive", o->draft.adaptive,
                "an underactuated hand: the fingers' mimic joints become joints of their own that "
                "follow their motor until each finger stops at contact");
  cmd->add_option("--hand-root", o->draft.hand_root,
                  "the hand's root link (default: the first link with two or more branches of "
                  "moving joints)");
  cmd->add_option("--name", o->draft.name, "the robot's name (default: the URDFs' names)");
  cmd->add_option("-o,--out", o->draft.out, "the description file to write")->capture_default_str();
  cmd->add_option("--samples", o->draft.samples,
                  "random configurations for the allowed collision pairs")
      ->check(CLI::Range(0, 1000000))
      ->capture_default_str();
  cmd->add_option("--seed", o->draft.seed, "seed of those configurations")->capture_default_str();
  cmd->add_flag("--json", o->json, "print one JSON object instead of the summary");
  cmd->callback([o, &action] { action = [o] { return run_describe(*o); }; });
}

}  // namespace claspplan::cli
