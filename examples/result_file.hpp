// A result.json written by `claspplan run`, read back: what `claspplan verify` needs to check the
// clasp again (the robot, its final configuration, the loop, the object's collision mesh, the
// seed) and, on request, the planned path in its environment (for the tests). Every problem is a
// InputError naming the file and the key.
#pragma once

#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include <Eigen/Core>

#include "core/input_error.hpp"
#include "robots/robot_model.hpp"
#include "servo/linking.hpp"
#include "tsrrt/clasp_setup.hpp"

namespace claspplan::cli {

struct ResultFile {
  std::string robot;         ///< the built-in robot's name or the description's path
  robots::RobotModel model;  ///< load_robot(robot)
  Eigen::VectorXd final_q;   ///< model.dof() values
  servo::Points loop;        ///< the clasped loop, closed
  std::vector<Eigen::Vector3d> object_vertices;  ///< the object's collision mesh
  std::vector<Eigen::Vector3i> object_triangles;
  std::optional<std::uint64_t> seed;  ///< the run's seed, when it has one
  // Only with with_path:
  std::vector<tsrrt::EnvironmentBox> environment;  ///< environment.boxes
  std::vector<Eigen::VectorXd> waypoints;          ///< the path, model.dof() values each
};

/// Reads the file (and loads its robot). with_path: also the environment and the waypoints.
ResultFile read_result_file(const std::string& path, bool with_path = false);
/// The same from the file's text; `name` stands for the path in messages.
ResultFile parse_result_file(const std::string& text, const std::string& name,
                             bool with_path = false);

}  // namespace claspplan::cli
