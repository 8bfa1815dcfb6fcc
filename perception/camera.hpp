// Pinhole depth cameras and depth images.
//
// Camera file (YAML), as in the design notes:
//   width: 640            # pixels
//   height: 480
//   fx: 525.0             # focal lengths and principal point, pixels
//   fy: 525.0
//   cx: 319.5             # pixel centres are at integer coordinates (OpenCV convention)
//   cy: 239.5
//   depth_scale: 0.0002   # metres per PNG unit; depth is z along the optical axis
//   T_world_camera: [r00, r01, r02, tx,  r10, r11, r12, ty,  r20, r21, r22, tz,  0, 0, 0, 1]
//   no_reading: free      # optional: a rendered complete scene (CameraModel::no_reading_is_free)
// T_world_camera is 4x4 row-major (16 numbers, or 4 rows of 4); the optical frame has z forward,
// x right, y down. Depth images are 16-bit single-channel PNGs; 0 means "no reading".
#pragma once

#include <string>
#include <vector>

#include <Eigen/Core>
#include <Eigen/Geometry>

#include "core/input_error.hpp"

namespace claspplan::perception {

struct CameraModel {
  int width = 640;
  int height = 480;
  double fx = 525.0, fy = 525.0;
  double cx = 319.5, cy = 239.5;
  double depth_scale = 0.0002;  ///< metres per PNG unit
  Eigen::Isometry3d T_world_camera = Eigen::Isometry3d::Identity();
  /// A pixel without a reading saw nothing up to any range: true for a rendering of a complete
  /// synthetic scene (nothing exists but what was rendered); false for a real sensor, where a
  /// missing reading may be a dark or shiny surface, the projector's shadow or a far wall, and
  /// the space along its ray is unknown (sensed_space.hpp). Camera file: `no_reading: free` (or
  /// `unknown`, the default).
  bool no_reading_is_free = false;

  Eigen::Vector3d position() const { return T_world_camera.translation(); }
  /// Pixel coordinates (u right, v down) and z-depth of a world point; z <= 0 is behind.
  Eigen::Vector3d project(const Eigen::Vector3d& p_world) const;
  /// World point seen at pixel (u, v) with z-depth z.
  Eigen::Vector3d back_project(double u, double v, double z) const;
};

/// Throws InputError("<what>: fx must be > 0, got -3") for any invalid field.
void validate_camera(const CameraModel& camera, const std::string& what);

/// Reads and validates a camera file (format above).
CameraModel read_camera_yaml(const std::string& path);
/// The same from the file's text; `name` stands for the path in messages.
CameraModel parse_camera_yaml(const std::string& text, const std::string& name);
void write_camera_yaml(const CameraModel& camera, const std::string& path);

/// A camera at `position` looking at `target`, image "up" towards world +z (or +x when looking
/// straight down/up), with the focal length chosen so that a sphere of `radius` around `target`
/// fills about 90% of the shorter image side.
CameraModel look_at_camera(const Eigen::Vector3d& position, const Eigen::Vector3d& target,
                           double radius, int width = 640, int height = 480);

/// Depth in metres per pixel (row-major, 0 = no reading).
struct DepthImage {
  int width = 0;
  int height = 0;
  std::vector<float> depth;

  DepthImage() = default;
  DepthImage(int w, int h) : width(w), height(h), depth(static_cast<size_t>(w) * h, 0.0f) {}
  float& at(int u, int v) { return depth[static_cast<size_t>(v) * width + u]; }
  float at(int u, int v) const { return depth[static_cast<size_t>(v) * width + u]; }
  int valid_count() const;
};

/// A depth image with the camera that took it.
struct DepthView {
  CameraModel camera;
  DepthImage image;
};

/// Reads a 16-bit PNG (libpng) and scales it by the camera's depth_scale. The size must match the
/// camera. Throws InputError for missing, non-PNG, truncated, 8-bit or colour files.
/// An all-zero image is read (it is the pipeline that rejects an empty cloud).
DepthImage read_depth_png(const std::string& path, const CameraModel& camera);
/// The same from the file's bytes; `name` stands for the path in messages.
DepthImage decode_depth_png(const std::string& data, const CameraModel& camera,
                            const std::string& name);
/// Writes depth / depth_scale rounded to 16 bits; depths beyond 65535 units become 0.
void write_depth_png(const DepthImage& image, const CameraModel& camera, const std::string& path);

/// Every valid pixel back-projected to the world frame.
std::vector<Eigen::Vector3d> depth_to_points(const DepthView& view);
/// The same, appended to `out` (several views into one cloud without copies), only those inside
/// `keep` when it is not empty (a crop that never stores the rest). Returns the valid pixels.
int append_depth_points(const DepthView& view, std::vector<Eigen::Vector3d>& out,
                        const Eigen::AlignedBox3d& keep = {});

struct DepthPixels {
  int valid = 0;         ///< pixels with a reading
  std::size_t kept = 0;  ///< of those, the points written (inside the box)
};
/// The same into out[0, kept), which must have room for view.image.valid_count() points: several
/// views written side by side into one buffer, each by its own thread.
DepthPixels back_project(const DepthView& view, const Eigen::AlignedBox3d& keep,
                         Eigen::Vector3d* out);

}  // namespace claspplan::perception
