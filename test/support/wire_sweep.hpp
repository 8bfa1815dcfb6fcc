// A 4 mm wire that a coarse motion check steps over: the iCub's fingers sweep ±5° about the
// first joint at HOME, and the wire stands across that sweep 0.65 m out. At 0.2 rad per check
// only the sweep's two ends are checked, 11 cm apart at the fingers, both clear of the wire.
#pragma once

#include <cmath>

#include <Eigen/Geometry>

#include "robots/collision_world.hpp"
#include "robots/robot_model.hpp"

namespace claspplan::test {

struct WireSweep {
  Eigen::VectorXd q0, q1;  ///< the sweep's ends, HOME with joint 0 at +5° and -5°
};

/// Adds the wire to `world` (box 0 of a world with no other boxes) and returns the sweep across it.
inline WireSweep add_wire_across_sweep(robots::CollisionWorld& world, const robots::RobotModel& m) {
  Eigen::Isometry3d wire = Eigen::Isometry3d::Identity();
  wire.translation() = Eigen::Vector3d(0.65, 0.0, 0.79);
  world.add_box(wire, {0.004, 0.004, 0.3});
  const double deg = M_PI / 180.0;
  WireSweep s{m.home, m.home};
  s.q0[0] = 5 * deg;
  s.q1[0] = -5 * deg;
  return s;
}

}  // namespace claspplan::test
