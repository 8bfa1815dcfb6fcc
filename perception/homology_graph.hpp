// Internal to the homology code: the 1-skeleton of K_d as a graph, and a bounded Dijkstra over it
// that carries prefix annotations (perception/homology.cpp). Not installed.
#pragma once

#include <cstdint>
#include <limits>
#include <vector>

#include "perception/complex.hpp"

namespace claspplan::perception::homology_detail {

using Word = std::uint64_t;
constexpr double kInf = std::numeric_limits<double>::infinity();

// The 1-skeleton in CSR form (arcs of a vertex contiguous, for cache-friendly Dijkstra runs).
struct Graph {
  struct Arc {
    int to;
    int edge;
    double len;
  };
  int n = 0;
  std::vector<int> start;  // n + 1
  std::vector<Arc> arcs;

  explicit Graph(const SimplicialComplex& k) : n(k.vertex_count()), start(n + 1, 0) {
    for (const auto& e : k.edges) ++start[e[0] + 1], ++start[e[1] + 1];
    for (int i = 0; i < n; ++i) start[i + 1] += start[i];
    arcs.resize(start[n]);
    std::vector<int> fill(start.begin(), start.end() - 1);
    for (size_t e = 0; e < k.edges.size(); ++e) {
      const int a = k.edges[e][0], b = k.edges[e][1];
      arcs[fill[a]++] = {b, static_cast<int>(e), k.edge_length[e]};
      arcs[fill[b]++] = {a, static_cast<int>(e), k.edge_length[e]};
    }
  }
  /// The edge joining u and w, or -1 (also for a vertex outside the graph).
  int edge_between(int u, int w) const {
    if (u < 0 || u >= n) return -1;
    for (int k = start[u]; k < start[u + 1]; ++k)
      if (arcs[k].to == w) return arcs[k].edge;
    return -1;
  }
};

// Dijkstra with a radius bound and reusable buffers (an indexed 4-ary heap with decrease-key).
// Vertices are settled in (distance, index) order, so a run with a smaller bound is an exact
// prefix of a run with a larger one (the loops are rebuilt from such re-runs).
class Dijkstra {
 public:
  Dijkstra(const Graph& g, int words)
      : g_(g),
        words_(words),
        dist_(g.n, kInf),
        parent_(g.n, -1),
        parent_vertex_(g.n, -1),
        stamp_(g.n, 0),
        state_(g.n, 0),
        pos_(g.n, -1),
        pa_(size_t(g.n) * words) {
    heap_.reserve(g.n);
  }

  // Runs from `root` settling vertices with distance <= radius. For each edge closing a cycle
  // (both ends settled, not a tree edge) calls on_cycle(u, w, edge, length_through_edge). With
  // `ann` non-null, prefix annotations pa are maintained. Stops early once stop_a and stop_b are
  // settled (when given).
  template <class OnCycle>
  void run(int root, double radius, const Word* ann, OnCycle&& on_cycle, int stop_a = -1,
           int stop_b = -1) {
    ++epoch_;
    order_.clear();
    heap_.clear();
    touch(root);
    dist_[root] = 0.0;
    push(root);
    int stops_left = (stop_a >= 0) + (stop_b >= 0 && stop_b != stop_a);
    const Graph::Arc* arcs = g_.arcs.data();
    while (!heap_.empty()) {
      const int u = heap_[0];
      const double d = dist_[u];
      if (d > radius) break;
      pop();
      state_[u] = kSettled;
      order_.push_back(u);
      const int pe = parent_[u];
      if (ann) {
        Word* pu = pa(u);
        if (pe < 0) {
          std::fill(pu, pu + words_, Word(0));
        } else {
          const Word* pp = pa(parent_vertex_[u]);
          const Word* ae = ann + size_t(pe) * words_;
          for (int w = 0; w < words_; ++w) pu[w] = pp[w] ^ ae[w];
        }
      }
      for (int k = g_.start[u], end = g_.start[u + 1]; k < end; ++k) {
        const Graph::Arc& a = arcs[k];
        const int w = a.to;
        if (stamp_[w] == epoch_ && state_[w] == kSettled) {
          if (a.edge != pe) on_cycle(w, u, a.edge, dist_[w] + a.len + d);
          continue;
        }
        const double nd = d + a.len;
        if (nd > radius) continue;
        touch(w);
        if (nd < dist_[w]) {
          dist_[w] = nd;
          parent_[w] = a.edge;
          parent_vertex_[w] = u;
          if (state_[w] == kQueued)
            up(pos_[w]);
          else
            push(w);
        }
      }
      if (u == stop_a || u == stop_b) {
        if (--stops_left <= 0 && stop_a >= 0) break;
      }
    }
  }

  // The lowest common vertex of u and w on their tree paths (distances grow along the paths).
  int common_ancestor(int u, int w) const {
    while (u != w) {
      if (dist_[u] > dist_[w])
        u = parent_vertex_[u];
      else if (dist_[w] > dist_[u])
        w = parent_vertex_[w];
      else
        u = parent_vertex_[u], w = parent_vertex_[w];
    }
    return u;
  }
  const Word* pa(int v) const { return pa_.data() + size_t(v) * words_; }
  Word* pa(int v) { return pa_.data() + size_t(v) * words_; }
  double dist(int v) const { return stamp_[v] == epoch_ ? dist_[v] : kInf; }
  int parent_edge(int v) const { return parent_[v]; }
  int parent_vertex(int v) const { return parent_vertex_[v]; }
  const std::vector<int>& order() const { return order_; }

 private:
  enum : unsigned char { kNew = 0, kQueued = 1, kSettled = 2 };
  void touch(int v) {
    if (stamp_[v] != epoch_) {
      stamp_[v] = epoch_;
      dist_[v] = kInf;
      parent_[v] = -1;
      parent_vertex_[v] = -1;
      state_[v] = kNew;
    }
  }
  bool less(int a, int b) const { return dist_[a] < dist_[b] || (dist_[a] == dist_[b] && a < b); }
  void place(int i, int v) {
    heap_[i] = v;
    pos_[v] = i;
  }
  void up(int i) {
    const int v = heap_[i];
    while (i > 0) {
      const int p = (i - 1) / 4;
      if (!less(v, heap_[p])) break;
      place(i, heap_[p]);
      i = p;
    }
    place(i, v);
  }
  void down(int i) {
    const int v = heap_[i];
    const int n = static_cast<int>(heap_.size());
    while (true) {
      const int c0 = 4 * i + 1;
      if (c0 >= n) break;
      int best = c0;
      for (int c = c0 + 1; c < std::min(c0 + 4, n); ++c)
        if (less(heap_[c], heap_[best])) best = c;
      if (!less(heap_[best], v)) break;
      place(i, heap_[best]);
      i = best;
    }
    place(i, v);
  }
  void push(int v) {
    state_[v] = kQueued;
    heap_.push_back(v);
    up(static_cast<int>(heap_.size()) - 1);
  }
  void pop() {
    const int last = heap_.back();
    heap_.pop_back();
    if (!heap_.empty()) {
      heap_[0] = last;
      down(0);
    }
  }

  const Graph& g_;
  int words_;
  std::vector<double> dist_;
  std::vector<int> parent_;
  std::vector<int> parent_vertex_;
  std::vector<unsigned> stamp_;
  std::vector<unsigned char> state_;
  std::vector<int> pos_;
  std::vector<int> heap_;
  std::vector<Word> pa_;
  std::vector<int> order_;
  unsigned epoch_ = 0;
};

}  // namespace claspplan::perception::homology_detail
