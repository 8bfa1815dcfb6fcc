#include "examples/scene_render.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>

#include <Eigen/Geometry>
#include <opencv2/imgproc.hpp>

#include "core/png_files.hpp"

namespace claspplan::cli {
namespace {

constexpr double kPi = 3.14159265358979323846;

// A ring of `sides` vertices at height z.
void add_ring(TriangleMesh& m, double radius, double z, int sides) {
  for (int i = 0; i < sides; ++i) {
    const double t = 2.0 * kPi * i / sides;
    m.vertices.emplace_back(radius * std::cos(t), radius * std::sin(t), z);
  }
}

// Joins ring r0 (starting at vertex a) to ring r1 (at b).
void join_rings(TriangleMesh& m, int a, int b, int sides) {
  for (int i = 0; i < sides; ++i) {
    const int j = (i + 1) % sides;
    m.triangles.emplace_back(a + i, a + j, b + j);
    m.triangles.emplace_back(a + i, b + j, b + i);
  }
}

void cap(TriangleMesh& m, int ring, int sides, double z, bool up) {
  const int centre = static_cast<int>(m.vertices.size());
  m.vertices.emplace_back(0.0, 0.0, z);
  for (int i = 0; i < sides; ++i) {
    const int j = (i + 1) % sides;
    if (up) {
      m.triangles.emplace_back(centre, ring + i, ring + j);
    } else {
      m.triangles.emplace_back(centre, ring + j, ring + i);
    }
  }
}

}  // namespace

TriangleMesh cylinder_mesh(double radius, double length, int sides) {
  TriangleMesh m;
  add_ring(m, radius, -length / 2.0, sides);
  add_ring(m, radius, length / 2.0, sides);
  join_rings(m, 0, sides, sides);
  cap(m, 0, sides, -length / 2.0, false);
  cap(m, sides, sides, length / 2.0, true);
  return m;
}

TriangleMesh capsule_mesh(double radius, double length, int sides) {
  // Latitude rings from the bottom pole to the top pole; the two equators bound the cylinder.
  const int rings = 4;
  TriangleMesh m;
  std::vector<int> starts;
  const auto ring_at = [&](double latitude, double centre_z) {
    starts.push_back(static_cast<int>(m.vertices.size()));
    add_ring(m, radius * std::cos(latitude), centre_z + radius * std::sin(latitude), sides);
  };
  for (int r = -rings; r <= 0; ++r) ring_at(kPi / 2.0 * r / (rings + 1), -length / 2.0);
  for (int r = 0; r <= rings; ++r) ring_at(kPi / 2.0 * r / (rings + 1), length / 2.0);
  for (std::size_t k = 0; k + 1 < starts.size(); ++k)
    join_rings(m, starts[k], starts[k + 1], sides);
  cap(m, starts.front(), sides, -length / 2.0 - radius, false);
  cap(m, starts.back(), sides, length / 2.0 + radius, true);
  return m;
}

TriangleMesh sphere_mesh(double radius, int sides) {
  return capsule_mesh(radius, 0.0, sides);
}

SceneImage::SceneImage(const View& view) : view_(view) {
  const Eigen::Vector3d forward = (view.target - view.eye).normalized();
  Eigen::Vector3d right = forward.cross(Eigen::Vector3d::UnitZ());
  if (right.norm() < 1e-9) right = Eigen::Vector3d::UnitX();
  right.normalize();
  const Eigen::Vector3d down = forward.cross(right);
  rotation_.row(0) = right.transpose();
  rotation_.row(1) = down.transpose();
  rotation_.row(2) = forward.transpose();
  focal_ = 0.5 * view.height / std::tan(view.vertical_fov / 2.0);
  image_ = cv::Mat(view.height, view.width, CV_8UC3, cv::Scalar(255, 255, 255));
  depth_ =
      cv::Mat(view.height, view.width, CV_64F, cv::Scalar(std::numeric_limits<double>::infinity()));
}

bool SceneImage::project(const Eigen::Vector3d& world, Eigen::Vector3d& pixel) const {
  const Eigen::Vector3d c = rotation_ * (world - view_.eye);
  if (c.z() <= 1e-6) return false;
  pixel = Eigen::Vector3d(view_.width / 2.0 + focal_ * c.x() / c.z(),
                          view_.height / 2.0 + focal_ * c.y() / c.z(), c.z());
  return true;
}

void SceneImage::fill_triangle(const Eigen::Vector3d& a, const Eigen::Vector3d& b,
                               const Eigen::Vector3d& c, const cv::Vec3b& colour) {
  const int x0 = std::max(0, static_cast<int>(std::floor(std::min({a.x(), b.x(), c.x()}))));
  const int x1 =
      std::min(view_.width - 1, static_cast<int>(std::ceil(std::max({a.x(), b.x(), c.x()}))));
  const int y0 = std::max(0, static_cast<int>(std::floor(std::min({a.y(), b.y(), c.y()}))));
  const int y1 =
      std::min(view_.height - 1, static_cast<int>(std::ceil(std::max({a.y(), b.y(), c.y()}))));
  const double area = (b.x() - a.x()) * (c.y() - a.y()) - (c.x() - a.x()) * (b.y() - a.y());
  if (std::abs(area) < 1e-12) return;
  for (int y = y0; y <= y1; ++y) {
    for (int x = x0; x <= x1; ++x) {
      const double px = x + 0.5, py = y + 0.5;
      const double w0 = ((b.x() - px) * (c.y() - py) - (c.x() - px) * (b.y() - py)) / area;
      const double w1 = ((c.x() - px) * (a.y() - py) - (a.x() - px) * (c.y() - py)) / area;
      const double w2 = 1.0 - w0 - w1;
      if (w0 < 0.0 || w1 < 0.0 || w2 < 0.0) continue;
      // Perspective-correct depth: interpolate 1/z.
      const double z = 1.0 / (w0 / a.z() + w1 / b.z() + w2 / c.z());
      double& d = depth_.at<double>(y, x);
      if (z < d) {
        d = z;
        image_.at<cv::Vec3b>(y, x) = colour;
      }
    }
  }
}

void SceneImage::draw_mesh(const TriangleMesh& mesh, const Eigen::Matrix4d& pose,
                           const cv::Scalar& colour) {
  const Eigen::Matrix3d R = pose.topLeftCorner<3, 3>();
  const Eigen::Vector3d t = pose.topRightCorner<3, 1>();
  std::vector<Eigen::Vector3d> world(mesh.vertices.size()), pixel(mesh.vertices.size());
  std::vector<char> visible(mesh.vertices.size());
  for (std::size_t i = 0; i < mesh.vertices.size(); ++i) {
    world[i] = R * mesh.vertices[i] + t;
    visible[i] = project(world[i], pixel[i]);
  }
  for (const auto& tri : mesh.triangles) {
    if (!visible[tri[0]] || !visible[tri[1]] || !visible[tri[2]]) continue;
    const Eigen::Vector3d n =
        (world[tri[1]] - world[tri[0]]).cross(world[tri[2]] - world[tri[0]]).normalized();
    const Eigen::Vector3d to_eye = (view_.eye - world[tri[0]]).normalized();
    // Two-sided Lambert shading with an ambient floor.
    const double shade = 0.45 + 0.55 * std::abs(n.dot(to_eye));
    const cv::Vec3b c(cv::saturate_cast<uchar>(colour[0] * shade),
                      cv::saturate_cast<uchar>(colour[1] * shade),
                      cv::saturate_cast<uchar>(colour[2] * shade));
    fill_triangle(pixel[tri[0]], pixel[tri[1]], pixel[tri[2]], c);
  }
}

void SceneImage::draw_polyline(const std::vector<Eigen::Vector3d>& points, bool closed,
                               const cv::Scalar& colour, int thickness, bool on_top) {
  const std::size_t n = points.size();
  const std::size_t segments = closed ? n : (n > 0 ? n - 1 : 0);
  for (std::size_t i = 0; i < segments; ++i) {
    const Eigen::Vector3d& p = points[i];
    const Eigen::Vector3d& q = points[(i + 1) % n];
    // Short pieces, each drawn when its middle is not hidden behind a surface.
    const int pieces = 8;
    for (int k = 0; k < pieces; ++k) {
      Eigen::Vector3d a, b, m;
      if (!project(p + (q - p) * (double(k) / pieces), a) ||
          !project(p + (q - p) * (double(k + 1) / pieces), b) ||
          !project(p + (q - p) * ((k + 0.5) / pieces), m)) {
        continue;
      }
      const int mx = static_cast<int>(m.x()), my = static_cast<int>(m.y());
      if (!on_top && mx >= 0 && my >= 0 && mx < view_.width && my < view_.height &&
          depth_.at<double>(my, mx) < m.z() - 0.01) {
        continue;
      }
      cv::line(image_, cv::Point2d(a.x(), a.y()), cv::Point2d(b.x(), b.y()), colour, thickness,
               cv::LINE_AA);
    }
  }
}

void SceneImage::draw_points(const std::vector<Eigen::Vector3d>& points, const cv::Scalar& colour,
                             int radius, bool on_top) {
  for (const auto& p : points) {
    Eigen::Vector3d px;
    if (!project(p, px)) continue;
    const int x = static_cast<int>(px.x()), y = static_cast<int>(px.y());
    if (x < 0 || y < 0 || x >= view_.width || y >= view_.height) continue;
    if (!on_top && depth_.at<double>(y, x) < px.z() - 0.01) continue;
    cv::circle(image_, cv::Point(x, y), radius, colour, cv::FILLED, cv::LINE_AA);
  }
}

void SceneImage::draw_label(const std::string& text, int row) {
  cv::putText(image_, text, cv::Point(12, 28 + 26 * row), cv::FONT_HERSHEY_SIMPLEX, 0.65,
              cv::Scalar(40, 40, 40), 1, cv::LINE_AA);
}

void SceneImage::save(const std::string& path) const {
  write_png(path, image_);
}

View framing_view(const std::vector<Eigen::Vector3d>& points, const Eigen::Vector3d& direction,
                  int width, int height) {
  View v;
  v.width = width;
  v.height = height;
  Eigen::Vector3d lo = Eigen::Vector3d::Constant(std::numeric_limits<double>::infinity());
  Eigen::Vector3d hi = -lo;
  for (const auto& p : points) lo = lo.cwiseMin(p), hi = hi.cwiseMax(p);
  if (points.empty()) lo = hi = Eigen::Vector3d::Zero();
  v.target = 0.5 * (lo + hi);
  const double radius = std::max(0.05, 0.5 * (hi - lo).norm());
  const double distance = radius / std::sin(v.vertical_fov / 2.0) * 1.05;
  v.eye = v.target + direction.normalized() * distance;
  return v;
}

}  // namespace claspplan::cli
