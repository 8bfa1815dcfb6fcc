// A k-d tree over a point cloud (nanoflann), for nearest-neighbour and radius queries.
#pragma once

#include <memory>
#include <utility>
#include <vector>

#include <nanoflann.hpp>

#include "core/mesh.hpp"

namespace claspplan::perception {

class PointIndex {
 public:
  /// Keeps a reference to `points`: they must outlive the index and not change.
  explicit PointIndex(const PointCloud& points);

  /// Index and distance of the nearest point (-1 and +inf when empty).
  std::pair<int, double> nearest(const Eigen::Vector3d& q) const;
  /// Indices and squared distances of the k nearest points, nearest first.
  void knn(const Eigen::Vector3d& q, int k, std::vector<unsigned>& indices,
           std::vector<double>& squared_distances) const;
  /// (index, squared distance) of all points strictly within `radius`, unsorted.
  void radius(const Eigen::Vector3d& q, double radius,
              std::vector<std::pair<unsigned, double>>& out) const;
  /// Number of points within `radius` (stops counting at `limit`).
  int count_within(const Eigen::Vector3d& q, double radius, int limit) const;

  const PointCloud& points() const { return points_; }

 private:
  struct Adaptor {
    const PointCloud* pts;
    size_t kdtree_get_point_count() const { return pts->size(); }
    double kdtree_get_pt(size_t i, size_t dim) const { return (*pts)[i][static_cast<int>(dim)]; }
    template <class BBox>
    bool kdtree_get_bbox(BBox&) const {
      return false;
    }
  };
  using Tree = nanoflann::KDTreeSingleIndexAdaptor<nanoflann::L2_Simple_Adaptor<double, Adaptor>,
                                                   Adaptor, 3, unsigned>;
  const PointCloud& points_;
  Adaptor adaptor_;
  std::unique_ptr<Tree> tree_;
};

}  // namespace claspplan::perception
