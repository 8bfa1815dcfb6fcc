#include "tsrrt/task_tree.hpp"

#include <algorithm>

// nanoflann 1.4's dynamic index trips GCC's -Wmaybe-uninitialized in its own header (clang has
// no such warning, and warns of the unknown name).
#if defined(__GNUC__) && !defined(__clang__)
#pragma GCC diagnostic push
#pragma GCC diagnostic ignored "-Wmaybe-uninitialized"
#endif
#include <nanoflann.hpp>
#if defined(__GNUC__) && !defined(__clang__)
#pragma GCC diagnostic pop
#endif

namespace claspplan::tsrrt {

// nanoflann reads the points through this adaptor.
struct TaskTree::Index {
  struct Points {
    const std::vector<Eigen::Vector4d>* keys;
    std::size_t kdtree_get_point_count() const { return keys->size(); }
    double kdtree_get_pt(std::size_t i, std::size_t d) const { return (*keys)[i][d]; }
    template <class Box>
    bool kdtree_get_bbox(Box&) const {
      return false;
    }
  };
  using KdTree =
      nanoflann::KDTreeSingleIndexDynamicAdaptor<nanoflann::L2_Simple_Adaptor<double, Points>,
                                                 Points, 4, std::uint32_t>;

  explicit Index(const std::vector<Eigen::Vector4d>* keys)
      : points{keys}, tree(4, points, nanoflann::KDTreeSingleIndexAdaptorParams(10)) {}
  Points points;
  KdTree tree;
};

TaskTree::TaskTree(double linking_scale)
    : linking_scale_(linking_scale), index_(std::make_unique<Index>(&keys_)) {}

TaskTree::~TaskTree() = default;

void TaskTree::clear() {
  nodes_.clear();
  keys_.clear();
  index_ = std::make_unique<Index>(&keys_);
}

int TaskTree::add(const Eigen::VectorXd& q, const TaskPoint& x, int parent) {
  nodes_.push_back({q, x, parent});
  keys_.emplace_back(x.position.x(), x.position.y(), x.position.z(), linking_scale_ * x.linking);
  const auto i = static_cast<std::uint32_t>(nodes_.size() - 1);
  index_->tree.addPoints(i, i);
  return static_cast<int>(i);
}

int TaskTree::nearest(const TaskPoint& x, const std::function<bool(int)>& allowed) const {
  if (nodes_.empty()) return -1;
  const Eigen::Vector4d key(x.position.x(), x.position.y(), x.position.z(),
                            linking_scale_ * x.linking);
  // Ask for more neighbours until one is allowed; the whole tree at the end.
  for (std::size_t k = 1;; k = std::min(nodes_.size(), k * 8)) {
    std::vector<std::uint32_t> ids(k);
    std::vector<double> d2(k);
    nanoflann::KNNResultSet<double, std::uint32_t> result(k);
    result.init(ids.data(), d2.data());
    index_->tree.findNeighbors(result, key.data(), nanoflann::SearchParams());
    // Sorted by distance; the tree's layout, and so the order of ties, depends only on the
    // insertion order, which keeps plans deterministic.
    for (std::size_t i = 0; i < result.size(); ++i) {
      if (!allowed || allowed(static_cast<int>(ids[i]))) return static_cast<int>(ids[i]);
    }
    if (k == nodes_.size()) return -1;
  }
}

std::vector<Eigen::VectorXd> TaskTree::path_to(int i) const {
  std::vector<Eigen::VectorXd> path;
  for (; i >= 0; i = nodes_[i].parent) path.push_back(nodes_[i].q);
  std::reverse(path.begin(), path.end());
  return path;
}

}  // namespace claspplan::tsrrt
