// Point clouds as sensor data (issue 33): a cloud file read with its pixel grid and sensor pose, so
// that the depth stages (crop, plane, outliers, occlusion tests, the depth surface mesh) apply to
// it as to a depth image.
//
// An *organized* cloud (a PCD with HEIGHT > 1, as PCL writes a depth camera's frame) is a pixel
// grid: point i is pixel (u, v) = (i % width, i / width). Its points and grid imply its camera
// exactly (fit_pinhole), which makes it a depth view (organized_cloud_view). A cloud without a grid
// but with a known sensor origin becomes a synthetic depth view (unorganized_cloud_view).
#pragma once

#include <optional>
#include <string>

#include <Eigen/Geometry>

#include "core/mesh.hpp"
#include "perception/camera.hpp"

namespace claspplan::perception {

/// A cloud as the sensor gave it.
struct SensorCloud {
  /// Organized (height > 1): width x height points, row-major, with NaN points where the sensor
  /// had no reading (kept in place: the grid is the information). Otherwise only the valid points
  /// (width = points.size(), height = 1): NaN never appears in an unorganized cloud.
  PointCloud points;
  int width = 0, height = 1;
  /// The PCD VIEWPOINT (tx ty tz qw qx qy qz): the sensor's pose in the cloud's frame. Absent when
  /// the header has none (then the file gives no sensor origin) and for .ply and .xyz.
  std::optional<Eigen::Isometry3d> viewpoint;

  bool organized() const { return height > 1; }
  /// The points with a reading (all points of an unorganized cloud).
  PointCloud valid_points() const;
};

/// Reads a .pcd, .ply (its vertices; faces are ignored) or .xyz file by its extension. Points
/// with a NaN coordinate are skipped (kept in place in an organized PCD), infinite coordinates are
/// an InputError, and so is a file without a valid point ("no valid point"); malformed files give
/// the one-line InputErrors of file_io.hpp. read_geometry() keeps its own rules (it rejects NaN
/// outside organized PCDs).
SensorCloud read_sensor_cloud(const std::string& path);
/// The same on the file's contents; `name` stands for the path in messages and gives the format.
SensorCloud parse_sensor_cloud(const std::string& data, const std::string& name);

/// Refuses (InputError with a hint to scale by 0.001) a cloud whose size suggests millimetres: the
/// diagonal of the box between the 1st and 99th percentile of each coordinate (robust to a few
/// stray points) exceeds 20 m, or the median distance of the points from the frame's origin (the
/// sensor, for a cloud in the sensor frame) exceeds 20 m. A tabletop scene in metres spans a few
/// metres at most; the same scene in millimetres spans hundreds of "metres".
void check_metric_units(const PointCloud& cloud, const std::string& name);

/// The intrinsics of an organized cloud, fitted to its grid by linear least squares:
/// u = fx x/z + cx and v = fy y/z + cy over the valid pixels with z > 0 (two independent fits),
/// with the points first moved into the camera frame by viewpoint^-1. width and height are the
/// grid's, T_world_camera is the viewpoint (identity without one), depth_scale 1e-4 m (or coarser
/// if the farthest point would not fit a 16-bit PNG). When the points are no pinhole grid seen from
/// the VIEWPOINT, the cloud's own frame and then that frame turned 180 degrees about x (y up, z
/// backwards) are tried, and T_world_camera is the pose that fits: real PCL files have a VIEWPOINT
/// that contradicts their points either way (examples/clouds/README.md). InputError when the
/// cloud is not organized, has fewer than 100 valid pixels in front of the sensor, the fit leaves
/// more than 1 px RMS (not a pinhole projection of its grid: a cloud transformed out of the sensor
/// frame) or gives fx or fy <= 0.
/// `residuals`, when given, receives the fit's quality.
struct PinholeResiduals {
  int pixels = 0;                   ///< valid pixels with z > 0 that were fitted
  double rms_u = 0.0, rms_v = 0.0;  ///< RMS residuals, pixels
};
CameraModel fit_pinhole(const SensorCloud& organized, const std::string& name,
                        PinholeResiduals* residuals = nullptr);

/// The depth view of an organized cloud whose frame has the pose T_world_sensor in the world: the
/// fitted camera at T_world_sensor * T_world_camera of fit_pinhole (the viewpoint, normally), and
/// an image holding each valid point's z in that
/// camera's frame (0 = no reading). depth_to_points() of it gives the valid points in the world.
DepthView organized_cloud_view(const SensorCloud& organized,
                               const Eigen::Isometry3d& T_world_sensor, const std::string& name);

/// A synthetic depth view of a cloud without a grid, seen from a known sensor origin: a virtual
/// pinhole camera at the origin looking at the points' centroid (image "up" as look_at_camera),
/// square pixels, its field of view just covering all points, about as many pixels as points at
/// 4:3 (between 64x48 and 1280x960); each point is splatted into its pixel keeping the nearest z.
/// InputError when a point is not in front of the camera, the points spread over more than 160
/// degrees, or all of them lie at one spot as seen from the origin.
DepthView unorganized_cloud_view(const PointCloud& points_in_world,
                                 const Eigen::Vector3d& sensor_origin_world,
                                 const std::string& name);

}  // namespace claspplan::perception
