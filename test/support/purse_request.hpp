// The purse of the purse_1 scenarios as an in-memory clasp request: seen by two synthetic depth
// cameras on the floor, bounded by cycles so that the result is the same on any machine.
#pragma once

#include <memory>
#include <string>

#include "examples/objects.hpp"
#include "test/support/floor_scene.hpp"
#include "tsrrt/clasp_setup.hpp"

namespace claspplan::test {

inline TriangleMesh purse() {
  objects::Purse p;
  p.body = Eigen::Vector3d(0.30, 0.14, 0.18);
  p.handle_radius = 0.12;
  p.handle_tube = 0.012;
  return objects::purse(p);
}

/// A request for `object` on the floor, for the built-in robot `robot` from the scenarios' start.
inline tsrrt::ClaspRequest floor_request(const TriangleMesh& object,
                                         const std::string& robot = "kr5_sdh",
                                         std::uint64_t seed = 1) {
  tsrrt::ClaspRequest r;
  r.robot = std::make_shared<const robots::RobotModel>(robots::load_robot(robot));
  r.start = (Eigen::VectorXd(6) << 0, -1.5707963, 1.5707963, 0, 1.5707963, 0).finished();
  r.object = seen_on_floor(object);
  tsrrt::EnvironmentBox floor;
  floor.pose.translation() = Eigen::Vector3d(0.5, 0, -0.025);
  floor.size = Eigen::Vector3d(2.0, 2.0, 0.05);
  r.environment = {floor};
  r.perception.targets = 9;
  r.perception.workspace =
      Eigen::AlignedBox3d(Eigen::Vector3d(0.2, -0.4, 0.01), Eigen::Vector3d(0.95, 0.4, 0.7));
  r.planning.planner.pre_expansions = 200;
  r.seed = seed;
  r.max_cycles = 300;  // bounded by cycles: the same result on any machine
  return r;
}

}  // namespace claspplan::test
