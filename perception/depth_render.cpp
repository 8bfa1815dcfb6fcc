#include "perception/depth_render.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <random>
#include <stdexcept>

#include "core/input_error.hpp"
#include "core/random_draws.hpp"

namespace claspplan::perception {

namespace {

struct ScreenVertex {
  double u, v, inv_z;
};

// Rasterizes one camera-frame triangle (all z >= near) into the z-buffer. Pixel centres are at
// integer coordinates; the inclusive edge test (with a tiny tolerance) covers pixels on shared
// edges from both sides, so closed surfaces have no cracks.
void rasterize(const ScreenVertex& a, const ScreenVertex& b, const ScreenVertex& c,
               std::vector<double>& zbuf, int width, int height) {
  const double area = (b.u - a.u) * (c.v - a.v) - (b.v - a.v) * (c.u - a.u);
  if (!(std::abs(area) > 1e-12)) return;
  const double umin = std::min({a.u, b.u, c.u}), umax = std::max({a.u, b.u, c.u});
  const double vmin = std::min({a.v, b.v, c.v}), vmax = std::max({a.v, b.v, c.v});
  const int u0 = std::max(0, static_cast<int>(std::ceil(umin - 1e-9)));
  const int u1 = std::min(width - 1, static_cast<int>(std::floor(umax + 1e-9)));
  const int v0 = std::max(0, static_cast<int>(std::ceil(vmin - 1e-9)));
  const int v1 = std::min(height - 1, static_cast<int>(std::floor(vmax + 1e-9)));
  if (u0 > u1 || v0 > v1) return;
  const double inv_area = 1.0 / area;
  const double tol = -1e-9;
  for (int v = v0; v <= v1; ++v) {
    for (int u = u0; u <= u1; ++u) {
      const double w0 = ((b.u - u) * (c.v - v) - (b.v - v) * (c.u - u)) * inv_area;
      const double w1 = ((c.u - u) * (a.v - v) - (c.v - v) * (a.u - u)) * inv_area;
      const double w2 = 1.0 - w0 - w1;
      if (w0 < tol || w1 < tol || w2 < tol) continue;
      // 1/z is affine in screen space: perspective-correct depth.
      const double inv_z = w0 * a.inv_z + w1 * b.inv_z + w2 * c.inv_z;
      if (!(inv_z > 0)) continue;
      const double z = 1.0 / inv_z;
      double& cell = zbuf[static_cast<size_t>(v) * width + u];
      if (z < cell) cell = z;
    }
  }
}

// Clips a camera-frame polygon against z >= near (Sutherland-Hodgman, one plane).
std::vector<Eigen::Vector3d> clip_near(const std::array<Eigen::Vector3d, 3>& tri, double near) {
  std::vector<Eigen::Vector3d> out;
  for (int i = 0; i < 3; ++i) {
    const Eigen::Vector3d& p = tri[i];
    const Eigen::Vector3d& q = tri[(i + 1) % 3];
    const bool pin = p.z() >= near, qin = q.z() >= near;
    if (pin) out.push_back(p);
    if (pin != qin) {
      const double t = (near - p.z()) / (q.z() - p.z());
      Eigen::Vector3d r = p + t * (q - p);
      r.z() = near;
      out.push_back(r);
    }
  }
  return out;
}

}  // namespace

DepthImage render_depth(const TriangleMesh& mesh, const CameraModel& camera,
                        const DepthNoise& noise, double near) {
  validate_camera(camera, "render_depth camera");
  if (!(noise.sigma >= 0.0) || !(noise.dropout >= 0.0 && noise.dropout <= 1.0))
    throw InputError("render_depth: noise sigma must be >= 0 and dropout in [0, 1]");
  const int W = camera.width, H = camera.height;
  const double inf = std::numeric_limits<double>::infinity();
  std::vector<double> zbuf(static_cast<size_t>(W) * H, inf);
  const Eigen::Isometry3d T_cw = camera.T_world_camera.inverse();
  std::vector<Eigen::Vector3d> pc(mesh.vertices.size());
  for (size_t i = 0; i < pc.size(); ++i) pc[i] = T_cw * mesh.vertices[i];
  auto screen = [&](const Eigen::Vector3d& p) {
    return ScreenVertex{camera.fx * p.x() / p.z() + camera.cx,
                        camera.fy * p.y() / p.z() + camera.cy, 1.0 / p.z()};
  };
  for (const auto& t : mesh.triangles) {
    const std::array<Eigen::Vector3d, 3> tri{pc[t[0]], pc[t[1]], pc[t[2]]};
    if ((tri[1] - tri[0]).cross(tri[2] - tri[0]).squaredNorm() < 1e-36) continue;
    if (tri[0].z() < near && tri[1].z() < near && tri[2].z() < near) continue;
    if (tri[0].z() >= near && tri[1].z() >= near && tri[2].z() >= near) {
      rasterize(screen(tri[0]), screen(tri[1]), screen(tri[2]), zbuf, W, H);
      continue;
    }
    const auto poly = clip_near(tri, near);
    for (size_t k = 1; k + 1 < poly.size(); ++k)
      rasterize(screen(poly[0]), screen(poly[k]), screen(poly[k + 1]), zbuf, W, H);
  }
  DepthImage img(W, H);
  std::mt19937_64 rng(noise.seed);
  const bool noisy = noise.sigma > 0.0 || noise.dropout > 0.0;
  for (size_t i = 0; i < zbuf.size(); ++i) {
    double z = zbuf[i];
    if (noisy) {
      const double drop = uniform01(rng());
      const double n = standard_normal(rng);
      if (z < inf) {
        if (drop < noise.dropout)
          z = inf;
        else
          z += noise.sigma * n;
      }
    }
    img.depth[i] = z < inf && z > 0.0 ? static_cast<float>(z) : 0.0f;
  }
  return img;
}

PointCloud sample_visible_surface(const TriangleMesh& mesh, const std::vector<DepthView>& views,
                                  int count, std::uint64_t seed) {
  if (views.empty()) return sample_surface(mesh, count, seed);
  PointCloud out;
  out.reserve(count);
  std::uint64_t batch_seed = seed;
  const long max_tries = 60L * std::max(count, 100);
  long tried = 0;
  while (static_cast<int>(out.size()) < count && tried < max_tries) {
    const int batch = std::max(2 * (count - static_cast<int>(out.size())), 1000);
    const PointCloud cand = sample_surface(mesh, batch, batch_seed++);
    tried += batch;
    for (const auto& p : cand) {
      bool seen = false;
      for (const auto& view : views) {
        const Eigen::Vector3d uvz = view.camera.project(p);
        if (uvz.z() <= 0) continue;
        const int u0 = static_cast<int>(std::floor(uvz.x())),
                  v0 = static_cast<int>(std::floor(uvz.y()));
        if (u0 < 0 || v0 < 0 || u0 + 1 >= view.image.width || v0 + 1 >= view.image.height) continue;
        // Visible if not behind the nearest surface, bilinearly interpolated between the four
        // surrounding pixel centres (the max of the valid ones at a silhouette).
        const double fu = uvz.x() - u0, fv = uvz.y() - v0;
        double z[4], zmax = 0.0;
        int valid = 0;
        for (int k = 0; k < 4; ++k) {
          z[k] = view.image.at(u0 + (k & 1), v0 + (k >> 1));
          if (z[k] > 0) ++valid, zmax = std::max(zmax, z[k]);
        }
        const double surface = valid == 4 ? (1 - fv) * ((1 - fu) * z[0] + fu * z[1]) +
                                                fv * ((1 - fu) * z[2] + fu * z[3])
                                          : zmax;
        if (valid == 0 || uvz.z() <= surface + 1e-3) {
          seen = true;
          break;
        }
      }
      if (seen && static_cast<int>(out.size()) < count) out.push_back(p);
    }
  }
  if (out.empty()) throw InputError("no part of the mesh is visible from the --view positions");
  return out;
}

std::vector<DepthView> render_views(const TriangleMesh& mesh,
                                    const std::vector<Eigen::Vector3d>& positions) {
  const Eigen::AlignedBox3d box = bounds(mesh);
  const Eigen::Vector3d target = box.center();
  const double radius = 0.5 * box.diagonal().norm();
  std::vector<DepthView> views;
  for (const auto& p : positions) {
    if ((p - target).norm() <= radius)
      throw InputError("view position is inside the mesh's bounding sphere");
    DepthView view;
    view.camera = look_at_camera(p, target, radius);
    view.image = render_depth(mesh, view.camera);
    view.camera.no_reading_is_free = true;  // the mesh is the whole scene
    views.push_back(std::move(view));
  }
  return views;
}

}  // namespace claspplan::perception
