// The surface a depth camera saw, as a triangle mesh: the object's collision model for planning.
//
// Why: K_d (complex.hpp) is built for topology. With a few thousand points its triangles reach
// centimetres and web across parts of a handle's hole, which would thicken the handle if the
// planner collided with them. Collisions therefore use the surface the sensor measured: each depth
// image's pixel grid, triangulated only where the depth is continuous.
//
// Unseen space: the mesh models only seen surface. For the robot's motions the space near the
// object that no camera saw is blocked separately (sensed_space.hpp's unknown voxels); for the
// secure-clasp check the object is only what was seen (an unseen part cannot hold it). The planner
// adds a tube along the clasped loop (tsrrt::loop_tube), so the loop itself is always material.
// This keeps the secure-clasp check conservative: missing geometry only makes the object easier
// to escape from the hand, and a finger can never pass through the loop.
//
// Continuity rule (per grid edge between pixels a and b, a pixel step (Δu, Δv) apart, with depths
// z_a and z_b; footprint w = (z_a + z_b)/2 · √((Δu/fx)² + (Δv/fy)²), the lateral size of the step
// at that depth):
//   depth jump    |z_a − z_b| <= max(min_jump, jump_slope · w)
//   edge length   |p_a − p_b| <= max(min_edge, edge_factor · w)
// A surface whose normal is θ from the ray changes depth by about w·tan θ per step, so with the
// defaults surfaces up to ~72° (tan θ = 3) stay connected, and a step of more than
// max(4 mm, 3 footprints) is an occlusion boundary that is never bridged: 8 mm for a Kinect
// (f = 525) at 0.7 m with stride 2 (w = 2.7 mm). The edge length test (≤ 4 footprints, ≥ 5 mm)
// bounds the triangles' size in 3D, the floors absorb sensor noise at short range. A triangle is
// also dropped when seen nearly edge-on, i.e. when the angle between its normal and the camera ray
// through its centroid exceeds max_view_angle (80°): at silhouettes a depth change is more likely
// a jump than a steep surface, and noise folds such triangles over.
#pragma once

#include <optional>
#include <vector>

#include <Eigen/Core>
#include <Eigen/Geometry>

#include "core/mesh.hpp"
#include "perception/camera.hpp"

namespace claspplan::perception {

struct DepthSurfaceOptions {
  /// Grid step in pixels: stride 2 on a 640x480 image gives at most 153,600 triangles, and a few
  /// tens of thousands for a 30 cm object at ~0.8 m.
  int stride = 2;
  double jump_slope = 3.0;        ///< max |Δz| per footprint (tan of ~72°)
  double min_jump = 0.004;        ///< metres: |Δz| always accepted (sensor noise, ~3σ of 1 mm)
  double edge_factor = 4.0;       ///< max edge length per footprint
  double min_edge = 0.005;        ///< metres: edge length always accepted
  double max_view_angle = 1.40;   ///< radians (80°) between triangle normal and camera ray
  Eigen::AlignedBox3d workspace;  ///< world-frame crop (all vertices inside); empty = no crop
  /// Supporting plane n·p + c = 0 with n pointing up (towards the object), as found by
  /// remove_supporting_plane(); n need not be unit length.
  std::optional<Eigen::Vector4d> support_plane;
  /// Triangles with any vertex less than this above the plane (or below it) are dropped: the
  /// support is modelled separately, as an environment box.
  double plane_margin = 0.005;
};

/// Throws std::invalid_argument for a non-positive stride, a negative, NaN or infinite threshold,
/// a NaN box or a plane with a zero or non-finite normal.
void validate_depth_surface_options(const DepthSurfaceOptions& options);

/// The triangulated surface seen in one depth image, in the world frame. Grid pixels (multiples of
/// `stride`) with a valid depth (finite, > 0) are back-projected (CameraModel::back_project); each
/// grid cell gives up to two triangles (split along its shorter 3D diagonal, or the one triangle
/// of its three valid corners), kept only if every edge passes the continuity rule above, the view
/// angle test, the crop box and the plane margin. Triangles face the camera (counter-clockwise
/// seen from it). Only used vertices are returned, in row-major pixel order; the result is
/// deterministic. An image with no valid pixel gives an empty mesh. Throws std::invalid_argument
/// for an invalid camera (validate_camera), an image whose size differs from the camera's, or
/// invalid options.
TriangleMesh depth_surface_mesh(const DepthView& view, const DepthSurfaceOptions& options = {});

/// The meshes of all views appended in order (vertices are shared only within a view).
TriangleMesh depth_surface_mesh(const std::vector<DepthView>& views,
                                const DepthSurfaceOptions& options = {});

}  // namespace claspplan::perception
