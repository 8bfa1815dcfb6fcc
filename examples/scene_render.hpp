// A small z-buffered renderer for result pictures: flat-shaded triangle meshes, polylines and
// points seen by a pinhole camera, drawn with OpenCV into a colour image.
#pragma once

#include <string>
#include <vector>

#include <Eigen/Core>
#include <opencv2/core.hpp>

#include "core/mesh.hpp"

namespace claspplan::cli {

/// Triangulated primitives (centred at the origin, along z; the box is core's box_mesh).
TriangleMesh cylinder_mesh(double radius, double length, int sides = 16);
TriangleMesh sphere_mesh(double radius, int sides = 16);
TriangleMesh capsule_mesh(double radius, double length, int sides = 16);

/// Where the camera is and what it looks at (world frame, z up).
struct View {
  Eigen::Vector3d eye = Eigen::Vector3d(2.0, -1.5, 1.5);
  Eigen::Vector3d target = Eigen::Vector3d::Zero();
  double vertical_fov = 0.7;  ///< radians
  int width = 800;
  int height = 600;
};

class SceneImage {
 public:
  explicit SceneImage(const View& view);

  /// Colours are BGR in 0–255. Meshes are shaded by the angle to the viewing direction.
  void draw_mesh(const TriangleMesh& mesh, const Eigen::Matrix4d& pose, const cv::Scalar& colour);
  /// Depth-tested unless `on_top`.
  void draw_polyline(const std::vector<Eigen::Vector3d>& points, bool closed,
                     const cv::Scalar& colour, int thickness, bool on_top = false);
  void draw_points(const std::vector<Eigen::Vector3d>& points, const cv::Scalar& colour, int radius,
                   bool on_top = true);
  void draw_label(const std::string& text, int row = 0);

  const cv::Mat& image() const { return image_; }
  /// Writes a PNG; throws std::runtime_error when the file cannot be written.
  void save(const std::string& path) const;

 private:
  // Pixel coordinates (x, y) and camera depth; false when behind the camera.
  bool project(const Eigen::Vector3d& world, Eigen::Vector3d& pixel) const;
  void fill_triangle(const Eigen::Vector3d& a, const Eigen::Vector3d& b, const Eigen::Vector3d& c,
                     const cv::Vec3b& colour);

  View view_;
  Eigen::Matrix3d rotation_;  // world → camera (x right, y down, z forward)
  double focal_;
  cv::Mat image_;
  cv::Mat depth_;
};

/// A view that frames the given points from a direction (unit, from target toward the eye).
View framing_view(const std::vector<Eigen::Vector3d>& points, const Eigen::Vector3d& direction,
                  int width = 800, int height = 600);

}  // namespace claspplan::cli
