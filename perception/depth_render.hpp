// The synthetic depth sensor: renders a triangle mesh into a depth image (z-buffer), with optional
// per-pixel Gaussian noise and dropout. It makes the example depth files and the tests' inputs.
#pragma once

#include <cstdint>

#include "core/mesh.hpp"
#include "perception/camera.hpp"

namespace claspplan::perception {

struct DepthNoise {
  double sigma = 0.0;      ///< standard deviation of additive Gaussian depth noise, metres
  double dropout = 0.0;    ///< probability that a pixel reads 0 (no reading)
  std::uint64_t seed = 1;  ///< std::mt19937_64 seed: same seed, same image
};

/// Z-depth along the optical axis of the nearest surface at each pixel centre (perspective-correct,
/// exact for planes up to float rounding); 0 where no triangle is seen. Triangles crossing the near
/// plane (z = `near` metres) are clipped; degenerate triangles are skipped. Noise is drawn per
/// pixel in row-major order (one uniform and one normal draw per pixel), so images are
/// reproducible.
DepthImage render_depth(const TriangleMesh& mesh, const CameraModel& camera,
                        const DepthNoise& noise = {}, double near = 0.01);

/// Points sampled uniformly by area on the part of the surface visible from the cameras' centres
/// (front-facing and not hidden in the camera's z-buffer), as a depth camera would see it.
/// Throws std::invalid_argument if nothing is visible.
PointCloud sample_visible_surface(const TriangleMesh& mesh, const std::vector<DepthView>& views,
                                  int count, std::uint64_t seed);

/// Renders the mesh from each view position with look_at_camera() towards the mesh's bounding-box
/// centre (640x480), giving the views sample_visible_surface() and the loop ranking use.
std::vector<DepthView> render_views(const TriangleMesh& mesh,
                                    const std::vector<Eigen::Vector3d>& positions);

}  // namespace claspplan::perception
