#include "perception/sensed_space.hpp"

#include <algorithm>
#include <atomic>
#include <cmath>
#include <limits>
#include <mutex>
#include <optional>
#include <stdexcept>
#include <string>
#include <utility>

#include "core/parallel.hpp"
#include "perception/cloud_filters.hpp"

namespace claspplan::perception {

namespace {

// Range queries on a depth image: the nearest reading and the number of pixels with a reading in
// any pixel rectangle, exactly, in a few reads. Minima come from a sparse table (level k holds the
// minimum of each 2^k x 2^k square, so a rectangle is the union of a few overlapping squares),
// counts from a summed-area table. Pixels without a reading are left out of the minimum (a
// sensor's scattered dropouts would otherwise make every large footprint unknown) but counted: a
// footprint that is mostly without readings says nothing.
class DepthRanges {
 public:
  explicit DepthRanges(const DepthImage& image) : w_(image.width), h_(image.height) {
    std::vector<float> base(image.depth.size());
    sum_.assign(static_cast<std::size_t>(w_ + 1) * (h_ + 1), 0);
    for (int v = 0; v < h_; ++v) {
      std::uint32_t row = 0;
      for (int u = 0; u < w_; ++u) {
        const std::size_t i = static_cast<std::size_t>(v) * w_ + u;
        const float d = image.depth[i];
        const bool ok = std::isfinite(d) && d > 0.0f;
        base[i] = ok ? d : kNone;
        row += ok;
        sum_[static_cast<std::size_t>(v + 1) * (w_ + 1) + u + 1] =
            sum_[static_cast<std::size_t>(v) * (w_ + 1) + u + 1] + row;
      }
    }
    mins_.push_back(std::move(base));
    for (int k = 1; (1 << k) <= std::min(w_, h_); ++k) {
      const std::vector<float>& below = mins_.back();
      const int half = 1 << (k - 1);
      std::vector<float> up(below.size(), kNone);
      for (int v = 0; v + 2 * half <= h_; ++v)
        for (int u = 0; u + 2 * half <= w_; ++u) {
          const std::size_t i = static_cast<std::size_t>(v) * w_ + u;
          up[i] = std::min(std::min(below[i], below[i + half]),
                           std::min(below[i + static_cast<std::size_t>(half) * w_],
                                    below[i + static_cast<std::size_t>(half) * w_ + half]));
        }
      mins_.push_back(std::move(up));
    }
  }

  // Over pixels [u0, u1] x [v0, v1], inside the image: the nearest reading (infinity if none) and
  // the share of pixels that have one.
  std::pair<float, double> nearest(int u0, int u1, int v0, int v1) const {
    const int su = u1 - u0 + 1, sv = v1 - v0 + 1;
    int k = 0;
    while ((2 << k) <= std::min(su, sv) && k + 1 < static_cast<int>(mins_.size())) ++k;
    const int side = 1 << k;
    const std::vector<float>& level = mins_[k];
    float m = kNone;
    for (int v = v0;; v = std::min(v + side, v1 - side + 1)) {
      for (int u = u0;; u = std::min(u + side, u1 - side + 1)) {
        m = std::min(m, level[static_cast<std::size_t>(v) * w_ + u]);
        if (u + side > u1) break;
      }
      if (v + side > v1) break;
    }
    const auto at = [&](int u, int v) { return sum_[static_cast<std::size_t>(v) * (w_ + 1) + u]; };
    const double valid =
        static_cast<double>(at(u1 + 1, v1 + 1)) - at(u0, v1 + 1) - at(u1 + 1, v0) + at(u0, v0);
    return {m, valid / (static_cast<double>(su) * sv)};
  }

  // The reading at a pixel, 0 without one.
  float pixel(int u, int v) const {
    const float d = mins_[0][static_cast<std::size_t>(v) * w_ + u];
    return d == kNone ? 0.0f : d;
  }

 private:
  static constexpr float kNone = std::numeric_limits<float>::infinity();
  int w_, h_;
  std::vector<std::vector<float>> mins_;
  std::vector<std::uint32_t> sum_;  // (w + 1) x (h + 1) summed-area table of valid pixels
};

// A footprint with readings on fewer of its pixels says nothing (see DepthRanges).
constexpr double kMinValidShare = 0.5;

// One view's rays, cast backwards. Before cast_all() a voxel's footprint is scanned pixel by
// pixel (a few queries of loop ranking); for the whole grid the image's range tables are built
// first. Both read the same rectangle the same way: the same answers.
class ViewCaster {
 public:
  ViewCaster(const DepthView& view, double half_edge)
      : view_(view),
        half_edge_(half_edge),
        R_(view.camera.T_world_camera.linear().transpose()),
        t_(-R_ * view.camera.T_world_camera.translation()) {
    for (int c = 0; c < 8; ++c)
      corner_[c] = R_ * Eigen::Vector3d((c & 1 ? 1 : -1) * half_edge, (c & 2 ? 1 : -1) * half_edge,
                                        (c & 4 ? 1 : -1) * half_edge);
  }

  void build_ranges() { ranges_.emplace(view_.image); }
  const DepthView& view() const { return view_; }

  // What this view says of the voxel centred at p. Its footprint is the pixel rectangle around its
  // 8 corners' projections (the cube's image lies inside it), its depth span their z range.
  Sensed classify(const Eigen::Vector3d& p, double tolerance) const {
    const CameraModel& camera = view_.camera;
    const Eigen::Vector3d q = R_ * p + t_;
    double u0 = INFINITY, u1 = -INFINITY, v0 = INFINITY, v1 = -INFINITY;
    double z0 = INFINITY, z1 = -INFINITY;
    for (const auto& c : corner_) {
      const Eigen::Vector3d k = q + c;
      if (k.z() <= 1e-6) return Sensed::kUnknown;  // reaches behind the camera
      const double u = camera.fx * k.x() / k.z() + camera.cx;
      const double v = camera.fy * k.y() / k.z() + camera.cy;
      u0 = std::min(u0, u), u1 = std::max(u1, u), v0 = std::min(v0, v), v1 = std::max(v1, v);
      z0 = std::min(z0, k.z()), z1 = std::max(z1, k.z());
    }
    // Pixels are centred at integer coordinates: those whose centres the footprint covers.
    const double pu0 = std::floor(u0 + 0.5), pu1 = std::floor(u1 + 0.5);
    const double pv0 = std::floor(v0 + 0.5), pv1 = std::floor(v1 + 0.5);
    if (pu1 < 0 || pv1 < 0 || pu0 >= camera.width || pv0 >= camera.height) return Sensed::kUnknown;
    const double u = camera.fx * q.x() / q.z() + camera.cx;
    const double v = camera.fy * q.y() / q.z() + camera.cy;
    const int iu = static_cast<int>(std::floor(u + 0.5)),
              iv = static_cast<int>(std::floor(v + 0.5));
    if (iu >= 0 && iv >= 0 && iu < camera.width && iv < camera.height) {
      const float d = reading(iu, iv);
      if (d > 0.0f && d >= z0 - tolerance && d <= z1 + tolerance) return Sensed::kOccupied;
    }
    // Free only when the whole footprint is in the image and every ray through the voxel went past
    // it: at once when every ray of the footprint did, else ray by ray.
    if (pu0 < 0 || pv0 < 0 || pu1 >= camera.width || pv1 >= camera.height) return Sensed::kUnknown;
    const int iu0 = static_cast<int>(pu0), iu1 = static_cast<int>(pu1);
    const int iv0 = static_cast<int>(pv0), iv1 = static_cast<int>(pv1);
    const auto [nearest, valid] = footprint(iu0, iu1, iv0, iv1);
    if (!camera.no_reading_is_free && valid < kMinValidShare) return Sensed::kUnknown;
    if (nearest > z1) return Sensed::kFree;
    return rays_pass(q, iu0, iu1, iv0, iv1) ? Sensed::kFree : Sensed::kUnknown;
  }

 private:
  float reading(int u, int v) const {
    const float d = view_.image.at(u, v);
    return std::isfinite(d) && d > 0.0f ? d : 0.0f;
  }

  // The exact test behind the footprint's: every ray through the voxel's cube (centre q, camera
  // frame) read a depth beyond where it leaves the cube. A pixel's ray is its centre's, (u', v', 1)
  // z in the camera frame (z is the depth), as a depth camera measures along it. The footprint's
  // rectangle also holds pixels whose rays pass beside the cube (its image is a hexagon), and the
  // far corner's depth z1 lies beyond where most rays leave it: beside a silhouette or over a
  // slanted surface the footprint test alone leaves a free voxel unknown, a skin of up to a voxel
  // around what was seen. Pixels without a reading are left out as in the footprint; a voxel
  // that no ray with a reading crosses stays unknown.
  bool rays_pass(const Eigen::Vector3d& q, int u0, int u1, int v0, int v1) const {
    constexpr int kMaxPixels = 1024;  // a voxel this large in the image is left unknown
    if ((u1 - u0 + 1) * (v1 - v0 + 1) > kMaxPixels) return false;
    const CameraModel& camera = view_.camera;
    const double half = half_edge_;
    const Eigen::Matrix3d to_cube = R_.transpose();  // camera -> the cube's (world) axes
    const Eigen::Vector3d origin = -(to_cube * q);   // the camera, from the cube's centre
    int crossing = 0;
    for (int v = v0; v <= v1; ++v)
      for (int u = u0; u <= u1; ++u) {
        const Eigen::Vector3d ray = to_cube * Eigen::Vector3d((u - camera.cx) / camera.fx,
                                                              (v - camera.cy) / camera.fy, 1.0);
        double in = 0.0, out = INFINITY;
        for (int i = 0; i < 3 && in < out; ++i) {
          if (std::abs(ray[i]) < 1e-12) {
            if (std::abs(origin[i]) > half) out = -INFINITY;
            continue;
          }
          double t0 = (-half - origin[i]) / ray[i], t1 = (half - origin[i]) / ray[i];
          if (t0 > t1) std::swap(t0, t1);
          in = std::max(in, t0), out = std::min(out, t1);
        }
        if (!(in < out)) continue;  // this ray passes beside the cube
        const float d = reading(u, v);
        if (d == 0.0f) {
          if (!camera.no_reading_is_free) continue;
        } else if (d <= out) {
          return false;
        }
        ++crossing;
      }
    return crossing > 0;
  }

  // The nearest reading and the share of pixels with one over [u0, u1] x [v0, v1].
  std::pair<float, double> footprint(int u0, int u1, int v0, int v1) const {
    if (ranges_) return ranges_->nearest(u0, u1, v0, v1);
    float m = std::numeric_limits<float>::infinity();
    int valid = 0;
    for (int v = v0; v <= v1; ++v)
      for (int u = u0; u <= u1; ++u) {
        const float d = reading(u, v);
        if (d > 0.0f) m = std::min(m, d), ++valid;
      }
    return {m, valid / (static_cast<double>(u1 - u0 + 1) * (v1 - v0 + 1))};
  }

  DepthView view_;
  double half_edge_;
  Eigen::Matrix3d R_;  // camera <- world
  Eigen::Vector3d t_;
  std::array<Eigen::Vector3d, 8> corner_;  // the voxel's corners from its centre, camera frame
  std::optional<DepthRanges> ranges_;
};

}  // namespace

struct SensedSpace::Casting {
  std::vector<ViewCaster> views;
  // A finer grid's coarser one (refined()): every part of a voxel seen free there is free. The
  // finer voxel's own rays may not say so: one between two pixels' rays is crossed by none.
  std::shared_ptr<const SensedSpace> coarser;
  std::once_flag once;
  std::atomic<bool> done{false};
  std::vector<std::uint8_t> cells;  // x fastest, then y, then z

  // Every view's verdict on the voxel centred at p: occupied if any saw a surface in it, else
  // free if any saw through it, else unknown (a finer grid's voxel: free in a free coarser one).
  Sensed classify(const Eigen::Vector3d& p, double tolerance) const {
    if (coarser && coarser->at(p) == Sensed::kFree) return Sensed::kFree;
    Sensed s = Sensed::kUnknown;
    for (const auto& v : views) {
      const Sensed here = v.classify(p, tolerance);
      if (here == Sensed::kOccupied) return here;
      if (here == Sensed::kFree) s = here;
    }
    return s;
  }
};

SensedSpace::SensedSpace(const std::vector<DepthView>& views, const Eigen::AlignedBox3d& region,
                         const SensedSpaceOptions& o) {
  if (region.isEmpty() || !region.min().allFinite() || !region.max().allFinite())
    throw std::invalid_argument("sensed space: the region is empty or not finite");
  if (!(o.resolution > 0) || !std::isfinite(o.resolution) || !(o.surface_tolerance >= 0) ||
      o.max_voxels < 1)
    throw std::invalid_argument("sensed space: the resolution must be > 0");
  for (std::size_t i = 0; i < views.size(); ++i)
    validate_camera(views[i].camera, "sensed space view " + std::to_string(i));
  // Coarsen the grid until it fits; snap it to multiples of the resolution (so that it lines up
  // with an OcTree's keys at that resolution).
  resolution_ = o.resolution;
  for (;;) {
    const Eigen::Vector3d lo = (region.min() / resolution_).array().floor() * resolution_;
    const Eigen::Vector3d hi = (region.max() / resolution_).array().ceil() * resolution_;
    dims_ = ((hi - lo) / resolution_).array().round().cast<int>().max(1);
    box_ = Eigen::AlignedBox3d(lo, lo + resolution_ * dims_.cast<double>());
    if (static_cast<double>(dims_.x()) * dims_.y() * dims_.z() <= o.max_voxels) break;
    resolution_ *= 1.25;
  }
  tolerance_ = o.surface_tolerance;
  casting_ = std::make_shared<Casting>();
  for (const auto& view : views) casting_->views.emplace_back(view, 0.5 * resolution_);
}

SensedSpace SensedSpace::refined(const Eigen::AlignedBox3d& box, double resolution,
                                 long max_voxels) const {
  if (!(resolution > 0) || !std::isfinite(resolution) || max_voxels < 1)
    throw std::invalid_argument("sensed space: a finer grid needs an edge > 0 and voxels");
  if (empty()) return {};
  const Eigen::AlignedBox3d part = box.intersection(box_);
  if (part.isEmpty()) return {};
  // Whole voxels of this grid (a box on a voxel face may take one more layer, never one less).
  const Eigen::Vector3d first = ((part.min() - box_.min()) / resolution_).array() - 1e-9;
  const Eigen::Vector3d last = ((part.max() - box_.min()) / resolution_).array() + 1e-9;
  const Eigen::Vector3d lo = box_.min() + first.array().floor().max(0.0).matrix() * resolution_;
  const Eigen::Vector3d hi =
      box_.min() + last.array().ceil().min(dims_.cast<double>().array()).matrix() * resolution_;
  const Eigen::Vector3i coarse = ((hi - lo) / resolution_).array().round().cast<int>().max(1);
  int split = static_cast<int>(std::floor(resolution_ / resolution + 1e-9));
  const auto voxels = [&](int n) { return coarse.cast<double>().prod() * n * n * n; };
  while (split >= 2 && voxels(split) > static_cast<double>(max_voxels)) --split;
  if (split < 2) return {};
  SensedSpace fine;
  fine.resolution_ = resolution_ / split;
  fine.tolerance_ = tolerance_;
  fine.box_ = Eigen::AlignedBox3d(lo, hi);
  fine.dims_ = coarse * split;
  fine.casting_ = std::make_shared<Casting>();
  fine.casting_->coarser = std::make_shared<const SensedSpace>(*this);
  for (const ViewCaster& v : casting_->views)
    fine.casting_->views.emplace_back(v.view(), 0.5 * fine.resolution_);
  return fine;
}

const std::vector<std::uint8_t>& SensedSpace::cells() const {
  Casting& c = *casting_;
  std::call_once(c.once, [&] {
    c.cells.assign(static_cast<std::size_t>(dims_.x()) * dims_.y() * dims_.z(),
                   static_cast<std::uint8_t>(Sensed::kUnknown));
    if (!c.views.empty()) {
      parallel_chunks(c.views.size(), 0, [&](std::size_t b, std::size_t e) {
        for (std::size_t i = b; i < e; ++i) c.views[i].build_ranges();
      });
      parallel_chunks(static_cast<std::size_t>(dims_.z()), 0, [&](std::size_t k0, std::size_t k1) {
        for (std::size_t k = k0; k < k1; ++k)
          for (int j = 0; j < dims_.y(); ++j)
            for (int i = 0; i < dims_.x(); ++i)
              c.cells[(k * dims_.y() + j) * dims_.x() + i] = static_cast<std::uint8_t>(
                  c.classify(centre(i, j, static_cast<int>(k)), tolerance_));
      });
    }
    c.done.store(true, std::memory_order_release);
  });
  return c.cells;
}

Sensed SensedSpace::cell(int i, int j, int k) const {
  const Casting& c = *casting_;
  if (c.done.load(std::memory_order_acquire))
    return static_cast<Sensed>(
        c.cells[(static_cast<std::size_t>(k) * dims_.y() + j) * dims_.x() + i]);
  return c.classify(centre(i, j, k), tolerance_);
}

Sensed SensedSpace::at(const Eigen::Vector3d& p) const {
  if (empty() || !box_.contains(p)) return Sensed::kUnknown;
  const Eigen::Vector3i c = voxel_of(p);
  return cell(c.x(), c.y(), c.z());
}

Eigen::Vector3i SensedSpace::voxel_of(const Eigen::Vector3d& p) const {
  const Eigen::Vector3i idx = ((p - box_.min()) / resolution_).array().floor().cast<int>();
  return idx.cwiseMax(0).cwiseMin(dims_ - Eigen::Vector3i::Ones());
}

bool SensedSpace::free_for_robot(const Eigen::Vector3d& p) const {
  if (empty() || !box_.contains(p)) return true;
  return at(p) == Sensed::kFree;
}

std::array<long, 3> SensedSpace::counts() const {
  std::array<long, 3> n{0, 0, 0};
  if (empty()) return n;
  for (std::uint8_t c : cells()) ++n[c];
  return n;
}

std::vector<Eigen::Vector3d> SensedSpace::blocked_voxels(
    const std::optional<Eigen::Vector4d>& support, double margin) const {
  const SupportHeight height(support);
  std::vector<Eigen::Vector3d> out;
  if (empty()) return out;
  cells();  // the whole grid, cast once
  for (int k = 0; k < dims_.z(); ++k)
    for (int j = 0; j < dims_.y(); ++j)
      for (int i = 0; i < dims_.x(); ++i) {
        const Sensed s = cell(i, j, k);
        if (s == Sensed::kFree) continue;
        const Eigen::Vector3d p = centre(i, j, k);
        if (s == Sensed::kUnknown || height(p) <= margin) out.push_back(p);
      }
  return out;
}

std::vector<Eigen::Vector3d> SensedSpace::voxels_holding(
    const std::vector<Eigen::Vector3d>& points) const {
  std::vector<std::array<int, 3>> voxels;  // (k, j, i): grid order when sorted
  for (const Eigen::Vector3d& p : points) {
    if (!box_.contains(p)) continue;
    const Eigen::Vector3i v = voxel_of(p);
    voxels.push_back({v.z(), v.y(), v.x()});
  }
  std::sort(voxels.begin(), voxels.end());
  voxels.erase(std::unique(voxels.begin(), voxels.end()), voxels.end());
  std::vector<Eigen::Vector3d> out;
  for (const auto& [k, j, i] : voxels) out.push_back(centre(i, j, k));
  return out;
}

Sensed sensed_at(const SensedSpace& space, const SensedSpace* finer, const Eigen::Vector3d& p) {
  return finer && finer->region().contains(p) ? finer->at(p) : space.at(p);
}

Eigen::AlignedBox3d object_region(const Eigen::AlignedBox3d& bounds, double margin) {
  if (bounds.isEmpty()) return bounds;
  const Eigen::Vector3d m = Eigen::Vector3d::Constant(margin);
  return Eigen::AlignedBox3d(bounds.min() - m, bounds.max() + m);
}

}  // namespace claspplan::perception
