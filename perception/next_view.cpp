#include "perception/next_view.hpp"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <limits>

#include "perception/cloud_filters.hpp"

namespace claspplan::perception {
namespace {

constexpr int kMaxVoxels = 600;  // the unknown voxels scored per camera: a stride over them
constexpr int kAzimuths = 24, kElevations = 6;

// Where the ray p + t d leaves `box` (t >= 0, p inside).
double exit_distance(const Eigen::AlignedBox3d& box, const Eigen::Vector3d& p,
                     const Eigen::Vector3d& d) {
  double t = std::numeric_limits<double>::infinity();
  for (int a = 0; a < 3; ++a) {
    if (d[a] > 0) t = std::min(t, (box.max()[a] - p[a]) / d[a]);
    if (d[a] < 0) t = std::min(t, (box.min()[a] - p[a]) / d[a]);
  }
  return t;
}

// The chance that the straight ray from voxel centre v reaches the camera: none through an
// occupied voxel of the region, halved by every `half_depth` of unknown space it crosses (a thin
// shadow is likely empty; a thick one may hide a solid, the unseen inside of a box). Beyond the
// region nothing was mapped, and nothing is assumed there.
double ray_chance(const SensedSpace& space, const Eigen::Vector3d& v, const Eigen::Vector3d& camera,
                  double half_depth) {
  const Eigen::Vector3d d = (camera - v).normalized();
  const double h = space.resolution(), step = 0.5 * h;
  const double end = std::min(exit_distance(space.region(), v, d), (camera - v).norm());
  // Half-voxel steps from the voxel's own edge: no occupied voxel is stepped over.
  double unknown = 0.0;
  for (double t = h; t < end; t += step) {
    const Sensed s = space.at(v + t * d);
    if (s == Sensed::kOccupied) return 0.0;
    if (s == Sensed::kUnknown) unknown += step;
  }
  return std::exp2(-unknown / half_depth);
}

}  // namespace

std::optional<ViewSuggestion> view_into_unknown(const SensedSpace& space,
                                                const std::vector<Eigen::Vector3d>& points,
                                                const std::optional<Eigen::Vector4d>& support,
                                                const ViewOptions& o) {
  if (space.empty() || points.empty()) return std::nullopt;
  const SupportHeight height(support);
  const Eigen::Vector3d& up = height.up;

  // The unknown voxels near the points, above the support (below it is the table's inside), in
  // grid order: the same set whatever the points' order.
  const Eigen::Vector3i dims = space.dims();
  const double h = space.resolution();
  std::vector<std::uint8_t> near(static_cast<std::size_t>(dims.prod()), 0);
  const auto index = [&](int i, int j, int k) {
    return (static_cast<std::size_t>(k) * dims.y() + j) * dims.x() + i;
  };
  // Points in one voxel count as its centre: thousands of contacts often share a few voxels.
  std::vector<std::uint8_t> walked(near.size(), 0);
  for (const Eigen::Vector3d& contact : points) {
    const Eigen::Vector3i v = ((contact - space.region().min()) / h).array().floor().cast<int>();
    Eigen::Vector3d p = contact;
    if ((v.array() >= 0).all() && (v.array() < dims.array()).all()) {
      std::uint8_t& seen = walked[index(v.x(), v.y(), v.z())];
      if (seen) continue;
      seen = 1;
      p = space.centre(v.x(), v.y(), v.z());
    }
    const Eigen::Vector3d lo = (p.array() - o.radius - space.region().min().array()) / h;
    const Eigen::Vector3d hi = (p.array() + o.radius - space.region().min().array()) / h;
    const Eigen::Vector3i a = lo.array().floor().cast<int>().max(0);
    const Eigen::Vector3i b = hi.array().floor().cast<int>().min(dims.array() - 1);
    for (int k = a.z(); k <= b.z(); ++k)
      for (int j = a.y(); j <= b.y(); ++j)
        for (int i = a.x(); i <= b.x(); ++i) {
          const Eigen::Vector3d c = space.centre(i, j, k);
          if ((c - p).norm() <= o.radius && height(c) > 0.5 * h &&
              space.cell(i, j, k) == Sensed::kUnknown)
            near[index(i, j, k)] = 1;
        }
  }
  std::vector<Eigen::Vector3d> unknown;
  for (int k = 0; k < dims.z(); ++k)
    for (int j = 0; j < dims.y(); ++j)
      for (int i = 0; i < dims.x(); ++i)
        if (near[index(i, j, k)]) unknown.push_back(space.centre(i, j, k));
  if (unknown.empty()) return std::nullopt;
  const std::size_t stride = (unknown.size() + kMaxVoxels - 1) / kMaxVoxels;
  std::vector<Eigen::Vector3d> voxels;
  Eigen::Vector3d target = Eigen::Vector3d::Zero();
  for (std::size_t n = 0; n < unknown.size(); n += stride) {
    voxels.push_back(unknown[n]);
    target += unknown[n];
  }
  target /= static_cast<double>(voxels.size());

  std::optional<ViewSuggestion> best;
  const Eigen::Vector3d a = up.unitOrthogonal(), b = up.cross(a);
  const double cos_fov = std::cos(o.half_fov);
  for (int e = kElevations; e >= 0; --e) {  // from above first: ties keep the higher camera
    const double elevation = e * M_PI / (2 * kElevations);
    for (int az = 0; az < (e == kElevations ? 1 : kAzimuths); ++az) {
      const double phi = 2.0 * M_PI * az / kAzimuths;
      const Eigen::Vector3d dir =
          std::cos(elevation) * (std::cos(phi) * a + std::sin(phi) * b) + std::sin(elevation) * up;
      const Eigen::Vector3d camera = target + o.distance * dir;
      if (height(camera) < o.above || (o.allowed && !o.allowed(camera))) continue;
      double visible = 0.0;
      for (const Eigen::Vector3d& v : voxels) {
        if ((v - camera).normalized().dot(-dir) >= cos_fov)
          visible += ray_chance(space, v, camera, o.unknown_half_depth);
      }
      if (visible > o.min_share * voxels.size() && (!best || visible > best->visible))
        best = ViewSuggestion{camera, target, visible, static_cast<int>(voxels.size())};
    }
  }
  return best;
}

std::string view_text(const ViewSuggestion& v) {
  const Eigen::Vector3d& p = v.position;
  const Eigen::Vector3d& t = v.target;
  char text[200];
  std::snprintf(text, sizeof text,
                "a camera {position: [%.2f, %.2f, %.2f], target: [%.2f, %.2f, %.2f]} (m) would "
                "see about %d%% of it",
                p.x(), p.y(), p.z(), t.x(), t.y(), t.z(),
                static_cast<int>(std::lround(100.0 * v.visible / std::max(v.unknown, 1))));
  return text;
}

}  // namespace claspplan::perception
