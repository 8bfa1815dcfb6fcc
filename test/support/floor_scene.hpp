// An object on the floor in front of the robot, seen like the purse_1 scenarios: three synthetic
// depth cameras, two above the robot's shoulders and one behind the object (1 mm noise), the floor
// in the images.
#pragma once

#include <Eigen/Geometry>

#include "examples/objects.hpp"
#include "perception/depth_render.hpp"
#include "perception/pipeline.hpp"

namespace claspplan::test {

/// `object` (standing on z = 0, centred in x and y) turned by `yaw` about z and put at x = 0.55.
inline perception::PerceptionInputs seen_on_floor(const TriangleMesh& object, double yaw = 0.0) {
  Eigen::Isometry3d pose = Eigen::Isometry3d::Identity();
  pose.translate(Eigen::Vector3d(0.55, 0, 0));
  pose.rotate(Eigen::AngleAxisd(yaw, Eigen::Vector3d::UnitZ()));
  TriangleMesh scene = transformed(object, pose);
  append_mesh(scene, objects::ground_plane(2.0, 0.0, {0.5, 0.0}));
  perception::PerceptionInputs in;
  perception::DepthNoise noise;
  noise.sigma = 0.001;
  for (const Eigen::Vector3d& position :
       {Eigen::Vector3d(0.2, -0.6, 0.85), Eigen::Vector3d(0.2, 0.6, 0.85),
        Eigen::Vector3d(1.0, 0.0, 0.85)}) {
    perception::DepthView v;
    v.camera = objects::kinect_camera(position, {0.55, 0, 0.15});
    v.image = perception::render_depth(scene, v.camera, noise);
    in.depth_views.push_back(v);
    ++noise.seed;
  }
  return in;
}

/// The workspace crop of those scenarios: above the floor, in front of the robot.
inline Eigen::AlignedBox3d floor_workspace() {
  return {Eigen::Vector3d(0.2, -0.4, 0.003), Eigen::Vector3d(0.95, 0.4, 0.7)};
}

}  // namespace claspplan::test
