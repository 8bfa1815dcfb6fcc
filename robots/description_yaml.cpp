// The drafted hand description as YAML, with what was guessed said beside it.
#include <cmath>
#include <cstdio>
#include <sstream>

#include "robots/description_draft_detail.hpp"

namespace claspplan::robots::draft_detail {

std::string draft_number(double v, bool exact) {
  char buf[32];
  std::snprintf(buf, sizeof buf, exact ? "%.9g" : "%.4g", std::abs(v) < 5e-9 ? 0.0 : v);
  return buf;
}

namespace {

std::string vec(const Eigen::Vector3d& v, const char* format = "%.4g") {
  std::string out = "[";
  for (int i = 0; i < 3; ++i) {
    char buf[32];
    std::snprintf(buf, sizeof buf, format, std::abs(v[i]) < 5e-9 ? 0.0 : v[i]);
    out += (i ? ", " : "") + std::string(buf);
  }
  return out + "]";
}

std::string point(const CurvePoint& p) {
  return "{link: " + p.link + (p.offset ? ", xyz: " + vec(p.xyz) : "") + "}";
}

}  // namespace

std::string to_yaml(const Draft& d) {
  std::ostringstream y;
  y << "# Drafted by `claspplan describe` from the URDF(s) below: check every line marked\n"
       "# 'guessed' (`claspplan robot` prints what the hand can clasp), then plan on the ring\n"
       "# (README, \"Your own robot\").\n";
  y << "name: " << d.name << "\nurdf: " << d.urdf << "\n";
  if (!d.hand_urdf.empty()) {
    y << "hand_urdf: {file: " << d.hand_urdf;
    if (!d.hand_urdf_root.empty()) y << ", root: " << d.hand_urdf_root;
    y << ", parent: " << d.mount << ", xyz: " << vec(d.mount_xyz);
    if (!d.mount_rpy.isZero()) y << ", rpy: " << vec(d.mount_rpy, "%.9g");
    if (!d.replaces.empty()) {
      y << ", replaces: [";
      for (std::size_t i = 0; i < d.replaces.size(); ++i) y << (i ? ", " : "") << d.replaces[i];
      y << "]";
    }
    y << "}\n";
  }
  y << "arm:\n  joints: [";
  for (std::size_t i = 0; i < d.arm.size(); ++i) y << (i ? ", " : "") << d.arm[i].name;
  y << "]\n  home: [";
  for (std::size_t i = 0; i < d.arm.size(); ++i)
    y << (i ? ", " : "") << draft_number(d.arm[i].open, true);
  y << (d.home_given ? "]\n"
                     : "]  # guessed: every joint at 0 (within its limits): put the vendor's home "
                       "here\n");
  y << "  tool_link: " << d.tool_link << "\nhand:\n  base_link: " << d.base_link << "\n";
  y << "  # guessed: open at 0 (within the limits); closing moves each fingertip toward the\n"
       "  # opposing finger (+1 / -1), 0 for a joint that moves it sideways (an abduction)\n"
       "  joints:\n";
  for (const auto& j : d.hand) {
    if (j.follows.empty())
      y << "    - {name: " << j.name << ", open: " << draft_number(j.open, true)
        << ", closing: " << j.closing << "}\n";
    else
      y << "    - {name: " << j.name << ", closing: " << j.closing << "}  # adaptive: follows "
        << j.follows << "\n";
  }
  y << "  fingers:  # guessed: the thumb is the finger set apart from the others\n";
  for (const auto& f : d.fingers) {
    y << "    - {name: " << f.name << (f.thumb ? ", thumb: true" : "") << ", joints: [";
    for (std::size_t i = 0; i < f.joints.size(); ++i) y << (i ? ", " : "") << f.joints[i];
    y << "], links: [";
    for (std::size_t i = 0; i < f.links.size(); ++i) y << (i ? ", " : "") << f.links[i];
    y << "]}\n";
  }
  y << "  # One curve per finger against the thumb: tip, finger links, the palm between their\n"
       "  # bases, thumb links, tip (guessed tips: the far end of the last link's shapes).\n"
       "  curves:\n";
  for (const auto& [name, points] : d.curves) {
    y << "    - name: " << name << "\n      points: [";
    for (std::size_t i = 0; i < points.size(); ++i)
      y << (i ? ",\n               " : "") << point(points[i]);
    y << "]\n";
  }
  y << "  tcp: " << point(d.tcp) << "  # guessed: the middle of the closed hand\n";
  y << "  v_fwd: {link: " << d.base_link << ", vector: " << vec(d.v_fwd, "%.9g")
    << "}  # guessed: along the straight fingers\n";
  y << "  v_swd: {link: " << d.base_link << ", vector: " << vec(d.v_swd, "%.9g")
    << "}  # guessed: the normal of the fingers' closing plane\n";
  y << "  vlink_goal: " << draft_number(d.vlink_goal) << "  # " << d.vlink_note << "\n";
  if (!d.allowed.empty() || d.mesh_hulls) y << "collision:\n";
  if (d.mesh_hulls) y << "  mesh_hulls: true\n";
  if (!d.allowed.empty()) {
    y << "  # In contact at the home pose or in 95% of random configurations\n"
         "  allowed_pairs:\n";
    for (const auto& [a, b] : d.allowed) y << "    - [" << a << ", " << b << "]\n";
  }
  return y.str();
}

}  // namespace claspplan::robots::draft_detail
