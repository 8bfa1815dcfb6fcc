#include "perception/cloud_filters.hpp"

#include <algorithm>
#include <cmath>
#include <cstring>
#include <numeric>
#include <random>
#include <stdexcept>
#include <thread>

#include <pcl/point_cloud.h>
#include <pcl/point_types.h>
#include <pcl/sample_consensus/method_types.h>
#include <pcl/sample_consensus/model_types.h>
#include <pcl/search/kdtree.h>
#include <pcl/segmentation/extract_clusters.h>
#include <pcl/segmentation/sac_segmentation.h>

#include "core/parallel.hpp"
#include "core/random_draws.hpp"
#include "perception/first_occurrences.hpp"
#include "perception/point_index.hpp"

namespace claspplan::perception {

namespace {

pcl::PointCloud<pcl::PointXYZ>::Ptr to_pcl(const PointCloud& cloud) {
  pcl::PointCloud<pcl::PointXYZ>::Ptr pc(new pcl::PointCloud<pcl::PointXYZ>);
  pc->reserve(cloud.size());
  for (const auto& p : cloud)
    pc->push_back(pcl::PointXYZ(static_cast<float>(p.x()), static_cast<float>(p.y()),
                                static_cast<float>(p.z())));
  pc->width = static_cast<std::uint32_t>(pc->size());
  pc->height = 1;
  pc->is_dense = true;
  return pc;
}

}  // namespace

PointCloud crop_to_box(const PointCloud& cloud, const Eigen::AlignedBox3d& box) {
  if (box.isEmpty()) return cloud;
  PointCloud out;
  out.reserve(cloud.size());
  for (const auto& p : cloud)
    if (box.contains(p)) out.push_back(p);
  return out;
}

namespace {

// The first `count` entries of a partial Fisher-Yates shuffle of 0 .. n-1, storing only the
// positions it touches (at most 2 count) in a hash table instead of all n: a few thousand draws
// from hundreds of thousands of depth points.
std::vector<int> shuffled_prefix(std::size_t n, int count, std::mt19937_64& rng) {
  std::size_t capacity = 16;
  while (capacity < 4 * static_cast<std::size_t>(count)) capacity *= 2;
  std::vector<std::int64_t> position(capacity, -1);
  std::vector<int> value(capacity);
  const auto slot = [&](std::size_t p) {
    std::size_t s = (p * 0x9e3779b97f4a7c15ULL >> 20) & (capacity - 1);
    while (position[s] >= 0 && static_cast<std::size_t>(position[s]) != p)
      s = (s + 1) & (capacity - 1);
    return s;
  };
  const auto get = [&](std::size_t p) {
    const std::size_t s = slot(p);
    return position[s] < 0 ? static_cast<int>(p) : value[s];
  };
  const auto set = [&](std::size_t p, int v) {
    const std::size_t s = slot(p);
    position[s] = static_cast<std::int64_t>(p);
    value[s] = v;
  };
  std::vector<int> prefix(count);
  for (int i = 0; i < count; ++i) {
    const std::size_t pick = i + uniform_index(rng(), n - i);
    const int at_pick = get(pick);
    set(pick, get(i));
    prefix[i] = at_pick;  // position i is never read again
  }
  return prefix;
}

}  // namespace

PointCloud random_subset(const PointCloud& cloud, int count, std::uint64_t seed) {
  if (count < 0) throw std::invalid_argument("random_subset: negative count");
  if (static_cast<int>(cloud.size()) <= count) return cloud;
  std::mt19937_64 rng(seed);
  // Marks instead of a sort: the picks in input order, in one pass.
  std::vector<char> picked(cloud.size(), 0);
  for (int i : shuffled_prefix(cloud.size(), count, rng)) picked[i] = 1;
  PointCloud out;
  out.reserve(count);
  for (std::size_t i = 0; i < cloud.size(); ++i)
    if (picked[i]) out.push_back(cloud[i]);
  return out;
}

namespace {

// The first point of each occupied grid cell of size `cell` (indices, in input order).
std::vector<int> one_per_cell(const PointCloud& cloud, const Eigen::Vector3d& origin, double cell) {
  std::vector<std::uint64_t> keys(cloud.size());
  for (std::size_t i = 0; i < cloud.size(); ++i) {
    const Eigen::Vector3d c = ((cloud[i] - origin) / cell).array().floor();
    const auto k = [&](int a) {
      return static_cast<std::uint64_t>(std::clamp(c[a], 0.0, 2097151.0));
    };
    keys[i] = k(0) << 42 | k(1) << 21 | k(2);
  }
  return first_occurrences(
      keys.size(), [&](std::size_t i) { return keys[i]; },
      [&](std::size_t i, std::size_t j) { return keys[i] == keys[j]; });
}

}  // namespace

PointCloud even_subset(const PointCloud& cloud, int count, std::uint64_t seed) {
  if (count < 0) throw std::invalid_argument("even_subset: negative count");
  if (static_cast<int>(cloud.size()) <= count) return cloud;
  Eigen::AlignedBox3d box;
  for (const auto& p : cloud) box.extend(p);
  // Occupied cells of a surface grow as 1 / cell^2: a few corrections reach the target.
  const double target = 1.5 * count;
  double cell = std::max(box.diagonal().norm() / std::sqrt(target), 1e-9);
  std::vector<int> picks;
  for (int pass = 0; pass < 8; ++pass) {
    picks = one_per_cell(cloud, box.min(), cell);
    const double found = static_cast<double>(picks.size());
    if (found >= count && found <= 2.0 * count) break;
    cell *= std::sqrt(found / target);
  }
  if (static_cast<int>(picks.size()) < count) return random_subset(cloud, count, seed);
  PointCloud even;
  even.reserve(picks.size());
  for (int i : picks) even.push_back(cloud[i]);
  return random_subset(even, count, seed);
}

SupportHeight::SupportHeight(const std::optional<Eigen::Vector4d>& plane) {
  if (!plane) return;
  const double length = plane->head<3>().norm();
  up = plane->head<3>() / length;
  offset = (*plane)[3] / length;
  known = true;
}

PlaneRemovalResult remove_supporting_plane(const PointCloud& cloud, const PlaneRemovalOptions& o) {
  const auto unchanged = [&cloud] {  // the cloud as it is: no plane removed
    PlaneRemovalResult u;
    u.kept = cloud;
    return u;
  };
  if (cloud.size() < 100) return unchanged();
  const PointCloud sample = random_subset(cloud, o.ransac_sample, o.seed);
  auto pc = to_pcl(sample);
  pcl::SACSegmentation<pcl::PointXYZ> seg;
  seg.setOptimizeCoefficients(true);
  // The largest plane within max_tilt of horizontal (a box's side faces are never candidates).
  seg.setModelType(pcl::SACMODEL_PERPENDICULAR_PLANE);
  seg.setAxis(Eigen::Vector3f::UnitZ());
  seg.setEpsAngle(o.max_tilt);
  seg.setMethodType(pcl::SAC_RANSAC);
  seg.setDistanceThreshold(o.distance);
  seg.setMaxIterations(300);
  seg.setInputCloud(pc);
  pcl::PointIndices inliers;
  pcl::ModelCoefficients coeffs;
  seg.segment(inliers, coeffs);
  if (coeffs.values.size() != 4 || inliers.indices.empty()) return unchanged();
  Eigen::Vector4d plane(coeffs.values[0], coeffs.values[1], coeffs.values[2], coeffs.values[3]);
  const double nn = plane.head<3>().norm();
  if (!(nn > 0) || !plane.allFinite()) return unchanged();
  plane /= nn;
  if (plane.z() < 0) plane = -plane;
  if (std::acos(std::min(1.0, plane.z())) > o.max_tilt) return unchanged();
  // Large, and the rest of the scene above it: a table, not an object's top face. One pass on all
  // cores counts the sides and keeps the points above (in chunk order: the input's).
  struct Side {
    int on = 0, below = 0;
    PointCloud above;
  };
  std::vector<Side> sides(std::max(1u, std::thread::hardware_concurrency()));
  const std::size_t n = cloud.size(), k = sides.size();
  parallel_chunks(k, 0, [&](std::size_t first, std::size_t last) {
    for (std::size_t c = first; c < last; ++c)
      for (std::size_t i = n * c / k; i < n * (c + 1) / k; ++i) {
        const double s = plane.head<3>().dot(cloud[i]) + plane.w();
        if (std::abs(s) <= o.distance)
          ++sides[c].on;
        else if (s > 0)
          sides[c].above.push_back(cloud[i]);
        else
          ++sides[c].below;
      }
  });
  int on = 0, above = 0, below = 0;
  for (const Side& side : sides)
    on += side.on, below += side.below, above += static_cast<int>(side.above.size());
  if (on < o.min_fraction * cloud.size()) return unchanged();
  if (above + below > 0 && above < o.above_fraction * (above + below)) return unchanged();
  PlaneRemovalResult r;
  r.kept.reserve(static_cast<size_t>(above));
  for (const Side& side : sides) r.kept.insert(r.kept.end(), side.above.begin(), side.above.end());
  r.removed = true;
  r.plane = plane;
  r.plane_points = static_cast<int>(cloud.size() - r.kept.size());
  return r;
}

PointCloud remove_statistical_outliers(const PointCloud& cloud, int k, double stddev_mult) {
  if (k <= 0 || static_cast<int>(cloud.size()) <= k) return cloud;
  // PCL's StatisticalOutlierRemoval statistics (each point's mean distance to its k nearest
  // neighbours; outliers lie more than stddev_mult sample deviations above the mean of those),
  // on the nanoflann k-d tree the rest of perception uses: about 4x faster than PCL's filter here
  // (6,000 points: 28 -> 6.5 ms, `BM_Outliers*`), and in double precision.
  const PointIndex index(cloud);
  std::vector<double> mean_distance(cloud.size());
  parallel_chunks(cloud.size(), 0, [&](std::size_t begin, std::size_t end) {
    std::vector<unsigned> near;
    std::vector<double> d2;
    for (std::size_t i = begin; i < end; ++i) {
      index.knn(cloud[i], k + 1, near, d2);
      double sum = 0.0;
      for (std::size_t j = 1; j < d2.size(); ++j) sum += std::sqrt(d2[j]);  // [0]: the point
      mean_distance[i] = sum / k;
    }
  });
  double sum = 0.0, sum2 = 0.0;
  for (double m : mean_distance) sum += m, sum2 += m * m;
  const double n = static_cast<double>(cloud.size());
  const double variance = std::max(0.0, (sum2 - sum * sum / n) / (n - 1.0));
  const double threshold = sum / n + stddev_mult * std::sqrt(variance);
  PointCloud out;
  out.reserve(cloud.size());
  for (std::size_t i = 0; i < cloud.size(); ++i)
    if (mean_distance[i] <= threshold) out.push_back(cloud[i]);
  return out;
}

namespace {

// Farthest-point sampling state: each point's squared distance to the nearest pick, in a binary
// tree of boxes over the points whose nodes keep the largest value below them (and its point).
// A new pick lowers only values larger than its distance, so a subtree whose box is at least
// its largest value away is skipped whole: most of the cloud, once the picks are dense.
class FarthestPoints {
 public:
  FarthestPoints(const PointCloud& cloud, int start)
      : slots_(cloud.size()), slot_of_(cloud.size()) {
    for (std::size_t i = 0; i < cloud.size(); ++i)
      slots_[i] = {cloud[i], (cloud[i] - cloud[start]).squaredNorm(), static_cast<int>(i)};
    build(0, static_cast<int>(cloud.size()));
    for (std::size_t k = 0; k < slots_.size(); ++k) slot_of_[slots_[k].index] = static_cast<int>(k);
  }

  /// The point with the largest value (ties: the larger index) and that value.
  std::pair<double, int> top() const { return {nodes_[0].best, nodes_[0].best_index}; }

  /// Picks point i: its value becomes 0, and every value above its distance to i that distance.
  void pick(int i) {
    slots_[slot_of_[i]].value = 0.0;
    update(0, slots_[slot_of_[i]].p);
  }

 private:
  // The points are kept in tree order, each leaf's contiguous: a leaf is scanned in sequence.
  struct Slot {
    Eigen::Vector3d p;
    double value;  // squared distance to the nearest pick
    int index;     // in the cloud
  };
  struct Node {
    Eigen::Vector3d lo, hi;
    int begin = 0, end = 0;     // the slots [begin, end)
    int left = -1, right = -1;  // children; -1 for a leaf
    double best = 0.0;
    int best_index = -1;
  };
  // Leaves of up to 32 points: a leaf scan is cheaper than more boxes to test and refresh
  // (`BM_FarthestPointSampling/10000` 40-42 -> 33-36 ms against leaves of 8).
  static constexpr int kLeaf = 32;

  static bool better(double v, int i, double w, int j) { return v > w || (v == w && i > j); }

  int build(int begin, int end) {
    const int index = static_cast<int>(nodes_.size());
    nodes_.emplace_back();
    Eigen::AlignedBox3d box;
    for (int k = begin; k < end; ++k) box.extend(slots_[k].p);
    nodes_[index].lo = box.min();
    nodes_[index].hi = box.max();
    nodes_[index].begin = begin;
    nodes_[index].end = end;
    if (end - begin > kLeaf) {
      int axis = 0;
      box.sizes().maxCoeff(&axis);
      const int mid = begin + (end - begin) / 2;
      std::nth_element(slots_.begin() + begin, slots_.begin() + mid, slots_.begin() + end,
                       [&](const Slot& a, const Slot& b) { return a.p[axis] < b.p[axis]; });
      const int left = build(begin, mid);
      const int right = build(mid, end);
      nodes_[index].left = left;
      nodes_[index].right = right;
    }
    refresh(nodes_[index]);
    return index;
  }

  void refresh(Node& n) {
    n.best = -1.0;
    n.best_index = -1;
    if (n.left < 0) {
      for (int k = n.begin; k < n.end; ++k)
        if (better(slots_[k].value, slots_[k].index, n.best, n.best_index))
          n.best = slots_[k].value, n.best_index = slots_[k].index;
      return;
    }
    for (const Node* c : {&nodes_[n.left], &nodes_[n.right]})
      if (better(c->best, c->best_index, n.best, n.best_index))
        n.best = c->best, n.best_index = c->best_index;
  }

  // The box's squared distance is a lower bound of every point's in it, rounding included (the
  // same sum of terms, each no larger).
  void update(int index, const Eigen::Vector3d& p) {
    Node& n = nodes_[index];
    double box = 0.0;
    for (int k = 0; k < 3; ++k) {
      const double d = p[k] < n.lo[k] ? n.lo[k] - p[k] : (p[k] > n.hi[k] ? p[k] - n.hi[k] : 0.0);
      box += d * d;
    }
    if (box >= n.best) return;
    if (n.left >= 0) {
      update(n.left, p);
      update(n.right, p);
      refresh(n);
      return;
    }
    // A leaf: its values lowered and its best found in one pass.
    n.best = -1.0;
    n.best_index = -1;
    for (int k = n.begin; k < n.end; ++k) {
      Slot& s = slots_[k];
      double d2 = 0.0;
      for (int a = 0; a < 3; ++a) {
        const double d = p[a] - s.p[a];
        d2 += d * d;
      }
      if (d2 < s.value) s.value = d2;
      if (better(s.value, s.index, n.best, n.best_index)) n.best = s.value, n.best_index = s.index;
    }
  }

  std::vector<Slot> slots_;
  std::vector<int> slot_of_;
  std::vector<Node> nodes_;
};

}  // namespace

std::vector<int> farthest_point_indices(const PointCloud& cloud, int count, std::uint64_t seed) {
  return farthest_point_indices(cloud, count, seed, {}, count);
}

std::vector<int> farthest_point_indices(const PointCloud& cloud, int count, std::uint64_t seed,
                                        const std::vector<int>& labels, int limit) {
  const int m = static_cast<int>(cloud.size());
  if (!labels.empty() && labels.size() != cloud.size())
    throw std::invalid_argument("farthest_point_indices: one label per point");
  std::vector<int> picked;
  if (m == 0 || count <= 0) return picked;
  limit = std::max(limit, count);
  if (limit >= m) {
    picked.resize(m);
    std::iota(picked.begin(), picked.end(), 0);
    return picked;
  }
  std::vector<int> per_object(
      labels.empty() ? 1 : *std::max_element(labels.begin(), labels.end()) + 1, 0);
  int most = 0;
  const auto take = [&](int i) {
    picked.push_back(i);
    const int object = labels.empty() ? 0 : labels[i];
    if (object >= 0) most = std::max(most, ++per_object[object]);
  };
  std::mt19937_64 rng(seed);
  const int start = static_cast<int>(uniform_index(rng(), m));
  FarthestPoints state(cloud, start);
  picked.reserve(limit);
  take(start);  // its value is already 0
  while (most < count && static_cast<int>(picked.size()) < limit) {
    const auto [d2, i] = state.top();
    if (d2 <= 0.0) break;  // only duplicates of picked points remain
    take(i);
    state.pick(i);
  }
  return picked;
}

std::vector<int> object_labels(const PointCloud& cloud, double gap, double min_share) {
  if (!(gap > 0) || !std::isfinite(gap))
    throw std::invalid_argument("object_labels: gap must be > 0");
  std::vector<int> labels(cloud.size(), -1);
  if (cloud.empty()) return labels;
  auto tree = std::make_shared<pcl::search::KdTree<pcl::PointXYZ>>();
  pcl::EuclideanClusterExtraction<pcl::PointXYZ> extract;
  extract.setClusterTolerance(gap);
  extract.setMinClusterSize(std::max(1, static_cast<int>(std::ceil(min_share * cloud.size()))));
  extract.setMaxClusterSize(static_cast<int>(cloud.size()));
  extract.setSearchMethod(tree);
  extract.setInputCloud(to_pcl(cloud));
  std::vector<pcl::PointIndices> clusters;
  extract.extract(clusters);  // largest first
  for (std::size_t c = 0; c < clusters.size(); ++c)
    for (int i : clusters[c].indices) labels[i] = static_cast<int>(c);
  return labels;
}

PointCloud farthest_point_sample(const PointCloud& cloud, int count, std::uint64_t seed) {
  return farthest_point_sample(cloud, count, seed, {}, count);
}

PointCloud farthest_point_sample(const PointCloud& cloud, int count, std::uint64_t seed,
                                 const std::vector<int>& labels, int limit) {
  PointCloud out;
  for (int i : farthest_point_indices(cloud, count, seed, labels, limit)) out.push_back(cloud[i]);
  return out;
}

double mean_spacing(const PointCloud& cloud) {
  if (cloud.size() < 2) throw std::invalid_argument("mean spacing needs at least 2 points");
  PointIndex index(cloud);
  std::vector<unsigned> idx;
  std::vector<double> d2;
  double sum = 0.0;
  for (const auto& p : cloud) {
    index.knn(p, 2, idx, d2);
    sum += std::sqrt(d2.size() > 1 ? d2[1] : 0.0);
  }
  return sum / cloud.size();
}

PointCloud spatial_order(const PointCloud& cloud) {
  const Eigen::AlignedBox3d box = bounds(cloud);
  if (box.isEmpty()) return cloud;
  const double size = std::max(box.sizes().maxCoeff(), 1e-300);
  auto spread = [](std::uint64_t x) {  // 21 bits -> every third bit
    x &= 0x1fffff;
    x = (x | x << 32) & 0x1f00000000ffffULL;
    x = (x | x << 16) & 0x1f0000ff0000ffULL;
    x = (x | x << 8) & 0x100f00f00f00f00fULL;
    x = (x | x << 4) & 0x10c30c30c30c30c3ULL;
    x = (x | x << 2) & 0x1249249249249249ULL;
    return x;
  };
  std::vector<std::pair<std::uint64_t, int>> keys(cloud.size());
  for (size_t i = 0; i < cloud.size(); ++i) {
    const Eigen::Vector3d q = (cloud[i] - box.min()) / size * 2097151.0;
    keys[i] = {spread(static_cast<std::uint64_t>(q.x())) |
                   spread(static_cast<std::uint64_t>(q.y())) << 1 |
                   spread(static_cast<std::uint64_t>(q.z())) << 2,
               static_cast<int>(i)};
  }
  std::sort(keys.begin(), keys.end());
  PointCloud out;
  out.reserve(cloud.size());
  for (const auto& k : keys) out.push_back(cloud[k.second]);
  return out;
}

PointCloud unique_points(const PointCloud& cloud) {
  const auto bits = [](double x) {
    std::uint64_t b;
    x += 0.0;  // -0 == +0: one bit pattern
    std::memcpy(&b, &x, sizeof b);
    return b;
  };
  const auto hash = [&](std::size_t i) {
    const Eigen::Vector3d& p = cloud[i];
    return bits(p.x()) ^ (bits(p.y()) * 0x9e3779b97f4a7c15ULL) ^
           (bits(p.z()) * 0xc2b2ae3d27d4eb4fULL);
  };
  PointCloud out;
  const std::vector<int> firsts = first_occurrences(
      cloud.size(), hash, [&](std::size_t i, std::size_t j) { return cloud[i] == cloud[j]; });
  out.reserve(firsts.size());
  for (int i : firsts) out.push_back(cloud[i]);
  return out;
}

}  // namespace claspplan::perception
