// The pictures a run leaves in its output folder (like the paper's Fig. 5 and 7): the final clasp
// from two viewpoints, the tree's grasp-centre points with the solution path, and the poses at
// 20/40/60/80% of the path.
#pragma once

#include <string>
#include <vector>

#include <Eigen/Core>
#include <Eigen/Geometry>

#include "examples/scenario.hpp"
#include "examples/scene_render.hpp"
#include "robots/robot_model.hpp"
#include "tsrrt/clasp_setup.hpp"

namespace claspplan::cli {

struct SceneGeometry {
  const robots::RobotModel& model;
  TriangleMesh object;  ///< the object's collision mesh (K_d triangles)
  std::vector<EnvironmentBox> boxes;
  std::vector<Eigen::Vector3d> loop;  ///< the clasped loop
};

/// Draws the robot's collision shapes at q (only the hand's with `hand_only`), the object, the
/// environment and the loop.
void draw_scene(SceneImage& image, const SceneGeometry& scene, const Eigen::VectorXd& q,
                bool hand_only = false);

/// Whether the line of sight from the view's eye to its target passes through the box.
bool blocks_sight(const EnvironmentBox& box, const View& view);

/// The framing view of `frame` along the first of `directions` whose line of sight no environment
/// box blocks (a close-up looks past the table, not up through it); the one with the fewest
/// blocking boxes when every one is blocked.
View unobstructed_view(const std::vector<Eigen::Vector3d>& frame,
                       const std::vector<Eigen::Vector3d>& directions,
                       const std::vector<EnvironmentBox>& boxes);

/// clasp_front.png and clasp_side.png: the hand at the final pose, close up, seen along the loop's
/// tangent and across the closing plane (both square to the approach, so the arm is not between),
/// from the side of the hand where no environment box is in the way; a box that still is (every
/// side blocked) is left out of that picture.
void write_clasp_views(const SceneGeometry& scene, const Eigen::VectorXd& q,
                       const std::string& dir);

/// escape.png: how a clasp failed its check. The closed hand, the object where the first escaping
/// sequence left it (its loop in red) and the loop where it started (blue).
void write_escape_view(const SceneGeometry& scene, const Eigen::VectorXd& q,
                       const Eigen::Isometry3d& escape, const std::string& file);

/// The search tree's grasp-centre points (red), the solution's nodes (blue) and the pruned path's
/// hand centres (green), over the start pose.
void write_tree_picture(const SceneGeometry& scene, const Eigen::VectorXd& q_start,
                        const tsrrt::ClaspStatistics& search,
                        const std::vector<Eigen::VectorXd>& path, const std::string& file);

/// Four panels: the path at 20, 40, 60 and 80% of its joint-space length.
void write_path_poses(const SceneGeometry& scene, const std::vector<Eigen::VectorXd>& path,
                      const std::string& file);

}  // namespace claspplan::cli
