// The TS-RRT's tree: configurations q with their task-space points x, joined by parent links, and
// nearest-neighbour queries in task space from a k-d tree (nanoflann).
#pragma once

#include <functional>
#include <memory>
#include <vector>

#include <Eigen/Core>

#include "tsrrt/problem.hpp"

namespace claspplan::tsrrt {

struct TreeNode {
  Eigen::VectorXd q;
  TaskPoint x;
  int parent = -1;  ///< -1 for the root
};

class TaskTree {
 public:
  /// `linking_scale`: metres that one unit of virtual linking counts as in the L2 task-space
  /// metric.
  explicit TaskTree(double linking_scale);
  ~TaskTree();
  TaskTree(const TaskTree&) = delete;
  TaskTree& operator=(const TaskTree&) = delete;

  /// Removes every node (a restarted search grows a new tree).
  void clear();

  /// Appends a node and returns its index.
  int add(const Eigen::VectorXd& q, const TaskPoint& x, int parent);

  /// TS-NEAREST-NEIGHBOR: the node nearest to x, among those `allowed` accepts (all when empty);
  /// -1 when none is allowed.
  int nearest(const TaskPoint& x, const std::function<bool(int)>& allowed = {}) const;

  const TreeNode& operator[](int i) const { return nodes_[i]; }
  int size() const { return static_cast<int>(nodes_.size()); }

  /// The configurations from the root to node i.
  std::vector<Eigen::VectorXd> path_to(int i) const;

 private:
  struct Index;
  double linking_scale_;
  std::vector<TreeNode> nodes_;
  std::vector<Eigen::Vector4d> keys_;  // (position, linking_scale · linking)
  std::unique_ptr<Index> index_;
};

}  // namespace claspplan::tsrrt
