#include "perception/sensor_cloud.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>
#include <utility>
#include <vector>

#include "core/file_io_detail.hpp"

namespace claspplan::perception {

using namespace file_io_detail;

namespace {

// The VIEWPOINT line's "tx ty tz qw qx qy qz".
Eigen::Isometry3d parse_viewpoint(const std::vector<std::string>& tok, const std::string& path) {
  if (tok.size() != 7) fail(path, "VIEWPOINT must have 7 numbers (tx ty tz qw qx qy qz)");
  double v[7];
  for (int i = 0; i < 7; ++i)
    if (!parse_double(tok[i], v[i]) || !std::isfinite(v[i]))
      fail(path, "VIEWPOINT value '" + tok[i].substr(0, 20) + "' is not a finite number");
  Eigen::Quaterniond q(v[3], v[4], v[5], v[6]);
  // PCL writes the quaternion with float precision: tolerate that rounding, refuse anything else.
  if (std::abs(q.norm() - 1.0) > 1e-3) fail(path, "VIEWPOINT quaternion (qw qx qy qz) is not unit");
  q.normalize();
  Eigen::Isometry3d T = Eigen::Isometry3d::Identity();
  T.linear() = q.toRotationMatrix();
  T.translation() = Eigen::Vector3d(v[0], v[1], v[2]);
  return T;
}

PointCloud without_nan(PointCloud points) {
  points.erase(std::remove_if(points.begin(), points.end(),
                              [](const Eigen::Vector3d& p) { return p.hasNaN(); }),
               points.end());
  return points;
}

std::string metres(double x) {
  char buf[64];
  std::snprintf(buf, sizeof buf, "%.1f", x);
  return buf;
}

// Metres per 16-bit PNG unit: 0.1 mm, coarser only if the farthest depth would not fit.
double depth_scale_for(double max_z) {
  return std::max(1e-4, max_z / 65000.0);
}

// Least-squares line pix = f t + c over (t, pix); returns {f, c, rms residual}.
struct LineFit {
  double f = 0.0, c = 0.0, rms = 0.0;
};

LineFit fit_line(const std::vector<double>& t, const std::vector<double>& pix) {
  const double n = static_cast<double>(t.size());
  double mt = 0.0, mp = 0.0;
  for (size_t i = 0; i < t.size(); ++i) mt += t[i], mp += pix[i];
  mt /= n;
  mp /= n;
  double stt = 0.0, stp = 0.0;  // centred sums: no cancellation at 300k pixels
  for (size_t i = 0; i < t.size(); ++i) {
    stt += (t[i] - mt) * (t[i] - mt);
    stp += (t[i] - mt) * (pix[i] - mp);
  }
  LineFit l;
  if (!(stt > 0.0)) return l;  // f = 0: refused by the caller
  l.f = stp / stt;
  l.c = mp - l.f * mt;
  double ss = 0.0;
  for (size_t i = 0; i < t.size(); ++i) {
    const double r = l.f * t[i] + l.c - pix[i];
    ss += r * r;
  }
  l.rms = std::sqrt(ss / n);
  return l;
}

void check_grid(const SensorCloud& c, const std::string& name) {
  if (!c.organized())
    fail(name, "not an organized cloud (HEIGHT 1): it has no pixel grid to fit a camera to");
  if (c.width < 1 ||
      static_cast<long long>(c.width) * c.height != static_cast<long long>(c.points.size()))
    fail(name, "the grid " + std::to_string(c.width) + " x " + std::to_string(c.height) +
                   " does not match its " + std::to_string(c.points.size()) + " points");
}

constexpr double kPi = 3.14159265358979323846;

constexpr double kMaxRms = 1.0;  // pixels: real captures fit far better (float rounding only)

// Both line fits of a grid whose points are moved into a candidate camera frame by `to_camera`.
struct GridFit {
  LineFit u, v;
  int pixels = 0;
  double max_z = 0.0;
  bool acceptable() const {
    return pixels >= 100 && u.rms <= kMaxRms && v.rms <= kMaxRms && u.f > 0.0 && v.f > 0.0;
  }
};

GridFit fit_grid(const SensorCloud& c, const Eigen::Isometry3d& to_camera) {
  std::vector<double> a, b, u, v;
  GridFit fit;
  for (size_t i = 0; i < c.points.size(); ++i) {
    if (!c.points[i].allFinite()) continue;
    const Eigen::Vector3d p = to_camera * c.points[i];
    if (!(p.z() > 0.0)) continue;
    a.push_back(p.x() / p.z());
    b.push_back(p.y() / p.z());
    u.push_back(static_cast<double>(i % c.width));
    v.push_back(static_cast<double>(i / c.width));
    fit.max_z = std::max(fit.max_z, p.z());
  }
  fit.pixels = static_cast<int>(a.size());
  if (fit.pixels >= 100) {
    fit.u = fit_line(a, u);
    fit.v = fit_line(b, v);
  }
  return fit;
}

}  // namespace

PointCloud SensorCloud::valid_points() const {
  return organized() ? without_nan(points) : points;
}

SensorCloud read_sensor_cloud(const std::string& path) {
  const std::string ext = extension(path);
  if (ext != ".pcd" && ext != ".ply" && ext != ".xyz")
    fail(path, "unknown cloud file type '" + ext + "' (expected .pcd, .ply or .xyz)");
  return parse_sensor_cloud(read_all(path), path);
}

SensorCloud parse_sensor_cloud(const std::string& data, const std::string& name) {
  const std::string ext = extension(name);
  SensorCloud c;
  if (ext == ".pcd") {
    PcdPoints pcd = parse_pcd_points(data, name);
    if (pcd.has_viewpoint) c.viewpoint = parse_viewpoint(pcd.viewpoint, name);
    if (pcd.height > 1) {
      c.width = static_cast<int>(pcd.width);
      c.height = static_cast<int>(pcd.height);
      c.points = std::move(pcd.points);
    } else {
      c.points = without_nan(std::move(pcd.points));
    }
  } else if (ext == ".ply") {
    GeometryFile g = parse_ply_file(data, name, true);
    c.points = without_nan(g.is_mesh ? std::move(g.mesh.vertices) : std::move(g.cloud));
  } else if (ext == ".xyz") {
    c.points = parse_xyz_points(data, name, true);
  } else {
    fail(name, "unknown cloud file type '" + ext + "' (expected .pcd, .ply or .xyz)");
  }
  if (!c.organized()) c.width = static_cast<int>(c.points.size());
  const bool any = std::any_of(c.points.begin(), c.points.end(),
                               [](const Eigen::Vector3d& p) { return !p.hasNaN(); });
  if (!any) fail(name, "no valid point (every point is NaN or the file has none)");
  return c;
}

void check_metric_units(const PointCloud& cloud, const std::string& name) {
  if (cloud.empty()) return;
  const size_t n = cloud.size();
  const size_t lo = (n - 1) / 100, hi = (n - 1) - (n - 1) / 100;
  std::vector<double> v(n);
  double diagonal2 = 0.0;
  for (int a = 0; a < 3; ++a) {
    for (size_t i = 0; i < n; ++i) v[i] = cloud[i][a];
    std::nth_element(v.begin(), v.begin() + lo, v.end());
    const double low = v[lo];
    std::nth_element(v.begin(), v.begin() + hi, v.end());
    const double extent = v[hi] - low;
    diagonal2 += extent * extent;
  }
  const char* hint = ": it looks like millimetres; scale it to metres (x 0.001)";
  const double diagonal = std::sqrt(diagonal2);
  if (diagonal > 20.0) fail(name, "the cloud spans " + metres(diagonal) + " m" + hint);
  for (size_t i = 0; i < n; ++i) v[i] = cloud[i].norm();
  std::nth_element(v.begin(), v.begin() + n / 2, v.end());
  if (v[n / 2] > 20.0)
    fail(name, "the points lie a median " + metres(v[n / 2]) + " m from the sensor" + hint);
}

CameraModel fit_pinhole(const SensorCloud& organized, const std::string& name,
                        PinholeResiduals* residuals) {
  check_grid(organized, name);
  // The sensor's pose in the cloud's frame: the VIEWPOINT, unless the points are no pinhole grid
  // from there. Real files break the rule both ways: PCL's table_scene_mug_stereo_textured.pcd has
  // a VIEWPOINT turned 180 degrees about x over points in the sensor frame, and
  // milk_cartoon_all_small_clorox.pcd an identity VIEWPOINT over points turned 180 degrees about x
  // (y up, z backwards, as in OpenGL). So the cloud's own frame and that turn are tried next. A
  // rigid motion of a (non-planar) pinhole grid is again one, with positive focal lengths and the
  // points in front, only if it is the identity: at most one candidate fits, none is wrong.
  std::vector<Eigen::Isometry3d> candidates;
  if (organized.viewpoint) candidates.push_back(*organized.viewpoint);
  candidates.push_back(Eigen::Isometry3d::Identity());
  candidates.emplace_back(Eigen::AngleAxisd(kPi, Eigen::Vector3d::UnitX()));
  GridFit fit;
  Eigen::Isometry3d T_cloud_camera = candidates.front();
  for (size_t k = 0; k < candidates.size(); ++k) {
    GridFit f = fit_grid(organized, candidates[k].inverse());
    if (k == 0) fit = f;  // a failure is reported for the first candidate
    if (f.acceptable()) {
      fit = f;
      T_cloud_camera = candidates[k];
      break;
    }
  }
  if (fit.pixels < 100)
    fail(name, "only " + std::to_string(fit.pixels) +
                   " valid pixels in front of the sensor: at least 100 are needed to fit its "
                   "camera");
  if (residuals) *residuals = {fit.pixels, fit.u.rms, fit.v.rms};
  if (!(fit.u.rms <= kMaxRms && fit.v.rms <= kMaxRms))
    fail(name, "the points are not a pinhole projection of the pixel grid (RMS residual " +
                   metres(fit.u.rms) + " px in u, " + metres(fit.v.rms) +
                   " px in v): an organized cloud must be in the sensor frame, not transformed "
                   "to another frame");
  if (!(fit.u.f > 0.0 && fit.v.f > 0.0))
    fail(name, "the fitted focal lengths (fx " + metres(fit.u.f) + ", fy " + metres(fit.v.f) +
                   ") are not positive: the cloud must be in the sensor frame (x right, y down, "
                   "z forward)");
  CameraModel c;
  c.width = organized.width;
  c.height = organized.height;
  c.fx = fit.u.f;
  c.fy = fit.v.f;
  c.cx = fit.u.c;
  c.cy = fit.v.c;
  c.depth_scale = depth_scale_for(fit.max_z);
  c.T_world_camera = T_cloud_camera;
  validate_camera(c, name);
  return c;
}

DepthView organized_cloud_view(const SensorCloud& organized,
                               const Eigen::Isometry3d& T_world_sensor, const std::string& name) {
  DepthView view;
  view.camera = fit_pinhole(organized, name);
  const Eigen::Isometry3d to_camera = view.camera.T_world_camera.inverse();  // the fitted frame
  view.image = DepthImage(organized.width, organized.height);
  for (size_t i = 0; i < organized.points.size(); ++i) {
    if (!organized.points[i].allFinite()) continue;
    const double z = (to_camera * organized.points[i]).z();
    if (z > 0.0) view.image.depth[i] = static_cast<float>(z);  // z <= 0: not fitted, no reading
  }
  view.camera.T_world_camera = T_world_sensor * view.camera.T_world_camera;
  validate_camera(view.camera, name);
  return view;
}

DepthView unorganized_cloud_view(const PointCloud& points_in_world,
                                 const Eigen::Vector3d& sensor_origin_world,
                                 const std::string& name) {
  if (points_in_world.empty()) fail(name, "no points");
  Eigen::Vector3d centroid = Eigen::Vector3d::Zero();
  for (size_t i = 0; i < points_in_world.size(); ++i) {
    if (!points_in_world[i].allFinite())
      fail(name, "point " + std::to_string(i) + " has a NaN or infinite coordinate");
    centroid += points_in_world[i];
  }
  centroid /= static_cast<double>(points_in_world.size());
  if (!sensor_origin_world.allFinite()) fail(name, "the sensor origin is not finite");
  if (!((centroid - sensor_origin_world).norm() > 1e-9))
    fail(name, "the points' centroid is at the sensor origin: no direction to look in");
  // Only the pose of look_at_camera is used ("up" as every other view); intrinsics follow below.
  DepthView view;
  view.camera = look_at_camera(sensor_origin_world, centroid, 1.0);
  const Eigen::Isometry3d to_camera = view.camera.T_world_camera.inverse();

  // Each point's ray (x/z, y/z); the view must hold all of them.
  const double max_tan = std::tan(80.0 / 180.0 * kPi);
  std::vector<Eigen::Vector3d> rays(points_in_world.size());  // (x/z, y/z, z)
  double amin = std::numeric_limits<double>::infinity(), amax = -amin, bmin = amin, bmax = -amin;
  double max_z = 0.0;
  for (size_t i = 0; i < points_in_world.size(); ++i) {
    const Eigen::Vector3d p = to_camera * points_in_world[i];
    if (!(p.z() > 1e-9 * p.norm()) || !(p.z() > 0.0))
      fail(name, "point " + std::to_string(i) +
                     " is not in front of the sensor: one depth view cannot see it");
    const double a = p.x() / p.z(), b = p.y() / p.z();
    if (std::abs(a) > max_tan || std::abs(b) > max_tan)
      fail(name,
           "the points spread over more than 160 degrees as seen from the sensor: one depth "
           "view cannot hold them");
    rays[i] = {a, b, p.z()};
    amin = std::min(amin, a), amax = std::max(amax, a);
    bmin = std::min(bmin, b), bmax = std::max(bmax, b);
    max_z = std::max(max_z, p.z());
  }
  const double span_a = amax - amin, span_b = bmax - bmin;
  if (!(std::max(span_a, span_b) > 1e-12))
    fail(name, "all points lie at one spot as seen from the sensor");

  // About one pixel per point at 4:3, i.e. 4k x 3k pixels.
  const double k = std::sqrt(static_cast<double>(points_in_world.size()) / 12.0);
  const int k_clamped = static_cast<int>(std::clamp(std::round(k), 16.0, 320.0));
  CameraModel& c = view.camera;
  c.width = 4 * k_clamped;
  c.height = 3 * k_clamped;
  // Square pixels; the larger angular extent fills its side, the box of rays is centred.
  const double inf = std::numeric_limits<double>::infinity();
  const double f = std::min(span_a > 0.0 ? (c.width - 1) / span_a : inf,
                            span_b > 0.0 ? (c.height - 1) / span_b : inf);
  c.fx = c.fy = f;
  c.cx = (c.width - 1) / 2.0 - f * (amin + amax) / 2.0;
  c.cy = (c.height - 1) / 2.0 - f * (bmin + bmax) / 2.0;
  c.depth_scale = depth_scale_for(max_z);
  validate_camera(c, name);

  view.image = DepthImage(c.width, c.height);
  for (const Eigen::Vector3d& r : rays) {
    const int u = std::clamp(static_cast<int>(std::lround(f * r.x() + c.cx)), 0, c.width - 1);
    const int v = std::clamp(static_cast<int>(std::lround(f * r.y() + c.cy)), 0, c.height - 1);
    float& z = view.image.at(u, v);
    const float rz = static_cast<float>(r.z());
    if (z == 0.0f || rz < z) z = rz;  // z-buffer: the nearest point along the pixel's ray
  }
  return view;
}

}  // namespace claspplan::perception
