#include "perception/depth_surface.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstddef>
#include <stdexcept>
#include <string>

#include "core/input_error.hpp"
#include "perception/cloud_filters.hpp"

namespace claspplan::perception {

namespace {

void require(bool ok, const std::string& message) {
  if (!ok) throw std::invalid_argument("depth surface: " + message);
}

bool finite_non_negative(double x) {
  return std::isfinite(x) && x >= 0.0;
}

}  // namespace

void validate_depth_surface_options(const DepthSurfaceOptions& o) {
  require(o.stride >= 1, "stride must be >= 1, got " + std::to_string(o.stride));
  require(finite_non_negative(o.jump_slope), "jump_slope must be finite and >= 0");
  require(finite_non_negative(o.min_jump), "min_jump must be finite and >= 0");
  require(finite_non_negative(o.edge_factor), "edge_factor must be finite and >= 0");
  require(finite_non_negative(o.min_edge), "min_edge must be finite and >= 0");
  require(std::isfinite(o.max_view_angle) && o.max_view_angle > 0.0 &&
              o.max_view_angle <= 3.14159265358979323846,
          "max_view_angle must be in (0, pi] radians");
  require(!o.workspace.min().hasNaN() && !o.workspace.max().hasNaN(),
          "the workspace box has a NaN bound");
  require(std::isfinite(o.plane_margin), "plane_margin must be finite");
  if (o.support_plane) {
    const Eigen::Vector4d& p = *o.support_plane;
    require(p.allFinite() && p.head<3>().norm() > 1e-12,
            "the support plane must be finite with a non-zero normal");
  }
}

namespace {

// One view's grid: node (i, j) is pixel (i * stride, j * stride).
class Grid {
 public:
  Grid(const DepthView& view, const DepthSurfaceOptions& o)
      : cam_(view.camera), o_(o), s_(o.stride) {
    const DepthImage& img = view.image;
    nu_ = (img.width - 1) / s_ + 1;
    nv_ = (img.height - 1) / s_ + 1;
    const size_t n = static_cast<size_t>(nu_) * nv_;
    z_.assign(n, 0.0);
    p_.resize(n);
    usable_.assign(n, false);
    const bool crop = !o.workspace.isEmpty();
    const SupportHeight height(o.support_plane);
    for (int j = 0; j < nv_; ++j)
      for (int i = 0; i < nu_; ++i) {
        const size_t k = index(i, j);
        const double z = img.at(i * s_, j * s_);
        if (!std::isfinite(z) || !(z > 0.0)) continue;
        z_[k] = z;
        p_[k] = cam_.back_project(i * s_, j * s_, z);
        if (crop && !o.workspace.contains(p_[k])) continue;
        if (height(p_[k]) < o.plane_margin) continue;
        usable_[k] = true;
      }
    cos_view_ = std::cos(o.max_view_angle);
  }

  int nu() const { return nu_; }
  int nv() const { return nv_; }
  size_t index(int i, int j) const { return static_cast<size_t>(j) * nu_ + i; }
  bool usable(size_t k) const { return usable_[k]; }
  const Eigen::Vector3d& point(size_t k) const { return p_[k]; }

  // The continuity rule for the grid edge a-b, (du, dv) grid steps apart.
  bool continuous(size_t a, size_t b, int du, int dv) const {
    const double zm = 0.5 * (z_[a] + z_[b]);
    const double ru = du * s_ / cam_.fx, rv = dv * s_ / cam_.fy;
    const double w = zm * std::sqrt(ru * ru + rv * rv);
    if (std::abs(z_[a] - z_[b]) > std::max(o_.min_jump, o_.jump_slope * w)) return false;
    const double limit = std::max(o_.min_edge, o_.edge_factor * w);
    return (p_[a] - p_[b]).squaredNorm() <= limit * limit;
  }

  // Triangle a, b, c (grid coordinates), counter-clockwise seen from the camera.
  bool accept(int ia, int ja, int ib, int jb, int ic, int jc) const {
    const size_t a = index(ia, ja), b = index(ib, jb), c = index(ic, jc);
    if (!continuous(a, b, ib - ia, jb - ja) || !continuous(b, c, ic - ib, jc - jb) ||
        !continuous(c, a, ia - ic, ja - jc))
      return false;
    const Eigen::Vector3d n = (p_[b] - p_[a]).cross(p_[c] - p_[a]);
    const Eigen::Vector3d to_camera = cam_.position() - (p_[a] + p_[b] + p_[c]) / 3.0;
    const double scale = n.norm() * to_camera.norm();
    return scale > 0.0 && n.dot(to_camera) >= cos_view_ * scale;
  }

 private:
  const CameraModel& cam_;
  const DepthSurfaceOptions& o_;
  int s_;
  int nu_ = 0, nv_ = 0;
  std::vector<double> z_;
  std::vector<Eigen::Vector3d> p_;
  std::vector<bool> usable_;
  double cos_view_ = 0.0;
};

void check_view(const DepthView& view, const std::string& what) {
  validate_camera(view.camera, what);
  const DepthImage& img = view.image;
  if (img.width != view.camera.width || img.height != view.camera.height ||
      img.depth.size() != static_cast<size_t>(img.width) * img.height)
    throw InputError(what + ": the depth image is " + std::to_string(img.width) + "x" +
                     std::to_string(img.height) + " (" + std::to_string(img.depth.size()) +
                     " values) but the camera is " + std::to_string(view.camera.width) + "x" +
                     std::to_string(view.camera.height));
}

TriangleMesh surface_of(const DepthView& view, const DepthSurfaceOptions& options) {
  const Grid g(view, options);
  // Triangles as grid indices first; cells in row-major order.
  std::vector<std::array<size_t, 3>> tris;
  auto add = [&](int ia, int ja, int ib, int jb, int ic, int jc) {
    if (g.accept(ia, ja, ib, jb, ic, jc))
      tris.push_back({g.index(ia, ja), g.index(ib, jb), g.index(ic, jc)});
  };
  for (int j = 0; j + 1 < g.nv(); ++j)
    for (int i = 0; i + 1 < g.nu(); ++i) {
      const bool u00 = g.usable(g.index(i, j)), u10 = g.usable(g.index(i + 1, j));
      const bool u01 = g.usable(g.index(i, j + 1)), u11 = g.usable(g.index(i + 1, j + 1));
      const int count = u00 + u10 + u01 + u11;
      if (count < 3) continue;
      if (count == 4) {
        const double d_a = (g.point(g.index(i, j)) - g.point(g.index(i + 1, j + 1))).squaredNorm();
        const double d_b = (g.point(g.index(i + 1, j)) - g.point(g.index(i, j + 1))).squaredNorm();
        if (d_a <= d_b) {  // split along 00-11
          add(i, j, i + 1, j + 1, i + 1, j);
          add(i, j, i, j + 1, i + 1, j + 1);
        } else {  // split along 10-01
          add(i, j, i, j + 1, i + 1, j);
          add(i + 1, j, i, j + 1, i + 1, j + 1);
        }
      } else if (!u00) {
        add(i + 1, j, i, j + 1, i + 1, j + 1);
      } else if (!u10) {
        add(i, j, i, j + 1, i + 1, j + 1);
      } else if (!u01) {
        add(i, j, i + 1, j + 1, i + 1, j);
      } else {
        add(i, j, i, j + 1, i + 1, j);
      }
    }
  // Only used vertices, in grid (row-major pixel) order.
  std::vector<int> remap(static_cast<size_t>(g.nu()) * g.nv(), -1);
  for (const auto& t : tris)
    for (size_t k : t) remap[k] = 0;
  TriangleMesh mesh;
  for (size_t k = 0; k < remap.size(); ++k) {
    if (remap[k] < 0) continue;
    remap[k] = static_cast<int>(mesh.vertices.size());
    mesh.vertices.push_back(g.point(k));
  }
  mesh.triangles.reserve(tris.size());
  for (const auto& t : tris) mesh.triangles.push_back({remap[t[0]], remap[t[1]], remap[t[2]]});
  return mesh;
}

}  // namespace

TriangleMesh depth_surface_mesh(const DepthView& view, const DepthSurfaceOptions& options) {
  validate_depth_surface_options(options);
  check_view(view, "depth surface view");
  return surface_of(view, options);
}

TriangleMesh depth_surface_mesh(const std::vector<DepthView>& views,
                                const DepthSurfaceOptions& options) {
  validate_depth_surface_options(options);
  for (size_t i = 0; i < views.size(); ++i)
    check_view(views[i], "depth surface view " + std::to_string(i));
  TriangleMesh all;
  for (const auto& view : views) append_mesh(all, surface_of(view, options));
  return all;
}

}  // namespace claspplan::perception
