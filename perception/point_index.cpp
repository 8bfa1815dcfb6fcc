#include "perception/point_index.hpp"

#include <limits>

namespace claspplan::perception {

PointIndex::PointIndex(const PointCloud& points) : points_(points), adaptor_{&points} {
  tree_ = std::make_unique<Tree>(3, adaptor_, nanoflann::KDTreeSingleIndexAdaptorParams(12));
  tree_->buildIndex();
}

std::pair<int, double> PointIndex::nearest(const Eigen::Vector3d& q) const {
  if (points_.empty()) return {-1, std::numeric_limits<double>::infinity()};
  unsigned idx = 0;
  double d2 = 0.0;
  tree_->knnSearch(q.data(), 1, &idx, &d2);
  return {static_cast<int>(idx), std::sqrt(d2)};
}

void PointIndex::knn(const Eigen::Vector3d& q, int k, std::vector<unsigned>& indices,
                     std::vector<double>& squared_distances) const {
  const size_t n = std::min<size_t>(k, points_.size());
  indices.resize(n);
  squared_distances.resize(n);
  if (n == 0) return;
  const size_t found = tree_->knnSearch(q.data(), n, indices.data(), squared_distances.data());
  indices.resize(found);
  squared_distances.resize(found);
}

void PointIndex::radius(const Eigen::Vector3d& q, double radius,
                        std::vector<std::pair<unsigned, double>>& out) const {
  out.clear();
  if (points_.empty()) return;
  nanoflann::SearchParams params(32, 0.0f, false);
  tree_->radiusSearch(q.data(), radius * radius, out, params);
}

namespace {
// Counts points within a squared radius and stops the search once `limit` are found.
struct CountingResult {
  double r2;
  int limit;
  int count = 0;
  void init() {}
  void clear() { count = 0; }
  size_t size() const { return static_cast<size_t>(count); }
  bool full() const { return true; }
  bool addPoint(double dist, unsigned) {
    if (dist < r2) ++count;
    return count < limit;
  }
  double worstDist() const { return r2; }
};
}  // namespace

int PointIndex::count_within(const Eigen::Vector3d& q, double radius, int limit) const {
  if (points_.empty() || limit <= 0) return 0;
  CountingResult result{radius * radius, limit};
  tree_->findNeighbors(result, q.data(), nanoflann::SearchParams());
  return result.count;
}

}  // namespace claspplan::perception
