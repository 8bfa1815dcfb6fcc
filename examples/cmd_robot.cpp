// `claspplan robot NAME [--q Q1,Q2,...] [--json]`: a robot's actuated joints, the pose of tool0
// and the finger curves at q (default: the arm's home pose with the hand's open pre-shape).
#include <cerrno>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <sstream>

#include "core/input_error.hpp"
#include "examples/command.hpp"
#include "perception/loops.hpp"
#include "robots/collision_world.hpp"
#include "robots/hand_size.hpp"
#include "robots/kinematics.hpp"
#include "robots/robot_model.hpp"
#include "robots/start_pose.hpp"

namespace claspplan::cli {
namespace {

struct RobotOptions {
  std::string robot;
  std::string q;
  bool q_given = false;
  std::string start_above;  // "x,y,z": find a start with the tcp above this point
  double height = 0.25;
  bool json = false;
};

// "0.1,-1.5,2" -> numbers. Every entry must be a complete finite number.
std::vector<double> parse_numbers(const std::string& text, const std::string& flag) {
  std::vector<double> values;
  std::stringstream ss(text);
  std::string token;
  int index = 0;
  while (std::getline(ss, token, ',')) {
    ++index;
    const size_t a = token.find_first_not_of(" \t");
    const size_t b = token.find_last_not_of(" \t");
    token = a == std::string::npos ? "" : token.substr(a, b - a + 1);
    if (token.empty()) throw InputError(flag + ": value " + std::to_string(index) + " is empty");
    char* end = nullptr;
    errno = 0;
    const double v = std::strtod(token.c_str(), &end);
    if (end != token.c_str() + token.size() || errno == ERANGE)
      throw InputError(flag + ": value " + std::to_string(index) + " '" + token +
                       "' is not a number");
    if (!std::isfinite(v))
      throw InputError(flag + ": value " + std::to_string(index) + " '" + token +
                       "' is not finite");
    values.push_back(v);
  }
  if (values.empty() || (!text.empty() && text.back() == ','))
    throw InputError(flag + ": expected comma-separated numbers, got '" + text + "'");
  return values;
}

// A finger thicker than this is likely a palm or a thumb's base listed among its links.
constexpr double kThickFinger = 0.04;

// What the hand can clasp (robots::hand_size, perception's ranking rules), and a warning when a
// finger link is implausibly thick.
struct ClaspRange {
  robots::HandSize size;
  double narrowest_hole = 0.0, widest_bar = 0.0;
  std::string warning;
};

ClaspRange clasp_range(const robots::RobotModel& m) {
  ClaspRange r;
  r.size = robots::hand_size(m);
  r.narrowest_hole = perception::narrowest_hole(r.size.finger_thickness);
  r.widest_bar = perception::widest_bar(r.size.closed_aperture);
  if (r.size.finger_thickness > kThickFinger) {
    char text[300];
    std::snprintf(text, sizeof text,
                  "finger thickness %.1f cm comes from link '%s': implausibly thick for a "
                  "finger; if it is a palm or a thumb's base, leave it out of its finger's links",
                  100.0 * r.size.finger_thickness, m.links[r.size.thickest_link].name.c_str());
    r.warning = text;
  }
  return r;
}

nlohmann::json vec(const Eigen::Vector3d& v) {
  return {v.x(), v.y(), v.z()};
}

// --start-above: the start found, or nothing (exit 1, the reason on stderr).
std::optional<robots::StartPose> find_start(const robots::RobotModel& m, const RobotOptions& o) {
  const std::vector<double> p = parse_numbers(o.start_above, "--start-above");
  if (p.size() != 3) throw InputError("--start-above: expected x,y,z in metres");
  robots::StartPoseOptions options;
  options.height = o.height;
  auto found = robots::find_start_above(m, Eigen::Vector3d(p[0], p[1], p[2]), options);
  if (!found)
    std::fprintf(stderr,
                 "claspplan: no start with the tcp %.3f m above (%g, %g, %g) and v_fwd down: out "
                 "of reach, or in self-collision or the floor at every one of %d tries\n",
                 o.height, p[0], p[1], p[2], options.restarts);
  return found;
}

int run_robot(const RobotOptions& o) {
  const robots::RobotModel m = robots::load_robot(o.robot);
  std::optional<robots::StartPose> start;
  if (!o.start_above.empty() && !(start = find_start(m, o))) return kNoAnswer;
  const Eigen::VectorXd q = start       ? start->q
                            : o.q_given ? m.complete_q(parse_numbers(o.q, "--q"))
                                        : m.home;
  robots::RobotData data(m);
  robots::FingerCurvesData curves;
  robots::finger_curves(m, q, data, curves, false);
  robots::CollisionWorld world(m);
  robots::CollisionReport contact;
  const bool self_collision = world.in_collision(data, &contact);
  const auto self_contacts = world.self_contacts(data);
  const Eigen::Isometry3d& tool0 = data.link_poses[m.tool_link];
  const ClaspRange range = clasp_range(m);
  std::size_t meshes = 0, triangles = 0;
  for (const auto& s : m.shapes)
    if (s.type == robots::CollisionShape::Type::kMesh) {
      ++meshes;
      triangles += s.mesh->triangles.size();
    }

  if (o.json) {
    nlohmann::json joints = nlohmann::json::array();
    for (const auto& j : m.joints) {
      joints.push_back({{"name", j.name},
                        {"lower", j.lower},
                        {"upper", j.upper},
                        {"hand", j.hand},
                        {"open", j.open},
                        {"closing", j.closing}});
      if (j.follows >= 0) joints.back()["follows"] = m.joints[j.follows].name;
    }
    nlohmann::json rotation = nlohmann::json::array();
    for (int r = 0; r < 3; ++r)
      rotation.push_back({tool0.linear()(r, 0), tool0.linear()(r, 1), tool0.linear()(r, 2)});
    nlohmann::json finger_curves = nlohmann::json::array(), names = nlohmann::json::array();
    for (size_t c = 0; c < curves.points.size(); ++c) {
      nlohmann::json curve = nlohmann::json::array();
      for (const auto& p : curves.points[c]) curve.push_back(vec(p));
      finger_curves.push_back(curve);
      names.push_back(m.curves[c].name);
    }
    nlohmann::json fingers = nlohmann::json::array();
    for (const auto& f : m.fingers) {
      nlohmann::json fj = nlohmann::json::array();
      for (int j : f.joints) fj.push_back(m.joints[j].name);
      fingers.push_back({{"name", f.name}, {"thumb", f.thumb}, {"joints", fj}});
    }
    nlohmann::json out = {
        {"name", m.name},
        {"source", m.source},
        {"dof", m.dof()},
        {"arm_dof", m.arm_dof},
        {"hand_dof", m.hand_dof},
        {"joints", joints},
        {"q", std::vector<double>(q.data(), q.data() + q.size())},
        {"tool0", {{"position", vec(tool0.translation())}, {"rotation", rotation}}},
        {"finger_curves", finger_curves},
        {"finger_curve_names", names},
        {"fingers", fingers},
        {"tcp", vec(robots::point_position(data, m.tcp))},
        {"v_fwd", vec(robots::vector_direction(data, m.v_fwd))},
        {"v_swd", vec(robots::vector_direction(data, m.v_swd))},
        {"vlink_goal", m.vlink_goal},
        {"self_collision", self_collision},
        {"shapes", m.shapes.size()},
        {"mesh_shapes", meshes},
        {"mesh_triangles", triangles},
        {"warnings", m.warnings},
        {"hand",
         {{"finger_thickness", range.size.finger_thickness},
          {"thickest_link",
           range.size.thickest_link >= 0 ? m.links[range.size.thickest_link].name : ""},
          {"closed_aperture", range.size.closed_aperture},
          {"narrowest_hole", range.narrowest_hole},
          {"widest_bar", range.widest_bar},
          {"warning", range.warning}}},
    };
    if (self_collision) out["self_collision_pair"] = {contact.first, contact.second};
    if (start)
      out["start"] = {{"q", std::vector<double>(q.data(), q.data() + m.arm_dof)},
                      {"position_error", start->position_error},
                      {"angle_error", start->angle_error},
                      {"restart", start->restart}};
    nlohmann::json pairs = nlohmann::json::array();
    for (const auto& [a, b] : self_contacts) pairs.push_back({a, b});
    out["self_collision_pairs"] = pairs;
    print_json(out);
    return kOk;
  }

  std::printf("%s (%s): %d actuated joints, %d arm + %d hand\n", m.name.c_str(), m.source.c_str(),
              m.dof(), m.arm_dof, m.hand_dof);
  for (const auto& w : m.warnings) std::printf("warning: %s\n", w.c_str());
  std::printf("collision shapes: %zu (%zu meshes, %zu triangles)\n", m.shapes.size(), meshes,
              triangles);
  std::printf(
      "hand: fingers %.1f cm thick, closed aperture %.1f cm at vlink_goal %.2f: clasps holes from "
      "%.1f cm wide and bars up to %.1f cm thick\n",
      100.0 * range.size.finger_thickness, 100.0 * range.size.closed_aperture, m.vlink_goal,
      100.0 * range.narrowest_hole, 100.0 * range.widest_bar);
  if (!range.warning.empty()) std::printf("warning: %s\n", range.warning.c_str());
  std::printf("  %-3s %-20s %-4s %10s %10s %10s\n", "#", "joint", "part", "lower", "upper", "q");
  for (int i = 0; i < m.dof(); ++i) {
    const auto& j = m.joints[i];
    std::printf("  %-3d %-20s %-4s %10.4f %10.4f %10.4f%s\n", i + 1, j.name.c_str(),
                j.hand ? "hand" : "arm", j.lower, j.upper, q[i],
                j.follows >= 0 ? ("  adaptive: follows " + m.joints[j.follows].name).c_str() : "");
  }
  if (start) {
    std::printf(
        "start found (restart %d; tcp %.1f mm from its target, v_fwd %.2f deg from down):\n"
        "start: [",
        start->restart, 1000.0 * start->position_error, start->angle_error * 180.0 / M_PI);
    for (int i = 0; i < m.arm_dof; ++i)  // no "-0.000000"
      std::printf("%s%.6f", i ? ", " : "", std::abs(q[i]) < 5e-7 ? 0.0 : q[i]);
    std::printf("]\n");
  }
  const Eigen::Vector3d t = tool0.translation();
  std::printf("tool0 position (m): %.4f %.4f %.4f\n", t.x(), t.y(), t.z());
  for (int r = 0; r < 3; ++r) {
    std::printf("%s %8.4f %8.4f %8.4f\n", r == 0 ? "tool0 rotation:    " : "                   ",
                tool0.linear()(r, 0), tool0.linear()(r, 1), tool0.linear()(r, 2));
  }
  for (size_t c = 0; c < curves.points.size(); ++c) {
    std::printf("finger curve %s (%zu points):\n", m.curves[c].name.c_str(),
                curves.points[c].size());
    for (const auto& p : curves.points[c]) std::printf("  %.4f %.4f %.4f\n", p.x(), p.y(), p.z());
  }
  std::printf("self-collision: %s\n",
              self_collision ? (contact.first + " / " + contact.second).c_str() : "none");
  if (self_contacts.size() > 1 || (!self_contacts.empty() && !self_collision)) {
    std::printf("all links in contact with each other (%zu pairs):\n", self_contacts.size());
    for (const auto& [a, b] : self_contacts) std::printf("  %s / %s\n", a.c_str(), b.c_str());
  }
  return kOk;
}

}  // namespace

void add_robot_command(CLI::App& app, Action& action) {
  auto o = std::make_shared<RobotOptions>();
  CLI::App* cmd = app.add_subcommand("robot", command_description("robot"));
  cmd->add_option("NAME", o->robot, "built-in robot or hand-description file")->required();
  cmd->add_option(
      "--q", o->q,
      "joint values in radians (metres for prismatic joints), arm joints then hand joints in "
      "the order listed; a shorter list leaves the rest at the home pose / open pre-shape. "
      "Values outside a joint's limits are an error. Use --q=-1.5,... for a leading minus.");
  cmd->add_option("--start-above", o->start_above,
                  "x,y,z (m): find a start with the hand open, its tcp --height above this point "
                  "and v_fwd pointing down, free of self-collision and the floor (exit 1 if none); "
                  "prints it as a scenario's start")
      ->excludes("--q");
  cmd->add_option("--height", o->height, "metres of the tcp above --start-above's point")
      ->check(CLI::Range(0.0, 5.0));
  cmd->add_flag("--json", o->json, "print one JSON object instead of the summary");
  cmd->callback([o, cmd, &action] {
    o->q_given = cmd->count("--q") > 0;
    action = [o] { return run_robot(*o); };
  });
}

}  // namespace claspplan::cli
