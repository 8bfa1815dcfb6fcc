// The paper's experiment scenes (Sec. V): each paper object in three poses within the KR5's reach
// (upright on the floor, turned, tipped over), and the chair whose seat hides the loop under it
// (Fig. 7); rendered once by the synthetic depth sensor into the committed example depth files.
#pragma once

#include <string>
#include <vector>

#include <Eigen/Geometry>

#include "examples/paper_objects.hpp"
#include "perception/camera.hpp"
#include "tsrrt/clasp_setup.hpp"

namespace claspplan::cli {

struct PaperScene {
  std::string name;                                ///< <object>_<pose> or chair_obstructed
  std::string object;                              ///< a paper_object_names() entry
  TriangleMesh mesh;                               ///< the object, world frame
  std::vector<tsrrt::EnvironmentBox> boxes;        ///< floor (and table)
  std::vector<perception::CameraModel> cameras;    ///< cropped to the object
  Eigen::AlignedBox3d workspace;                   ///< perception crop around the object
  Eigen::Vector3d near = Eigen::Vector3d::Zero();  ///< centre of the loop to clasp, world
  int loops = 1, targets = 9;                      ///< the paper's loop and target counts
};

/// The scene names: <object>_<1..3> for every paper object, then chair_obstructed.
std::vector<std::string> paper_scene_names();

/// Builds the named scene (meshes the object); std::invalid_argument for an unknown name.
PaperScene paper_scene(const std::string& name);

/// Renders the scene's depth views (Gaussian noise `sigma`, `dropout`) into `dir`: view_<i>.png and
/// view_<i>.yaml, and scene.json (near point, boxes, workspace, counts). Returns the files written.
std::vector<std::string> write_paper_scene(const PaperScene& scene, const std::string& dir,
                                           double sigma, double dropout);

}  // namespace claspplan::cli
