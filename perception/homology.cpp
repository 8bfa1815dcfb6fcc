#include "perception/homology.hpp"

#include <algorithm>
#include <array>
#include <cstdint>
#include <iterator>
#include <limits>
#include <memory>
#include <numeric>
#include <queue>
#include <stdexcept>
#include <string>
#include <unordered_map>
#include <utility>

#include "core/input_error.hpp"
#include "core/parallel.hpp"
#include "perception/counting_sort.hpp"
#include "perception/homology_graph.hpp"
#include "perception/shortest_cycles.hpp"

namespace claspplan::perception {

namespace {

using homology_detail::Dijkstra;
using homology_detail::Graph;
using homology_detail::is_zero;
using homology_detail::kInf;
using homology_detail::shortest_cycles;
using homology_detail::Word;

// Columns of a Z2 matrix reduced left to right (sorted entries, the lowest last): each column
// kept is stored one after another in `pool`, column j at pool[first[j] .. first[j+1]).
struct Z2Columns {
  std::vector<int> pivot_of;  // per row: the kept column whose lowest entry it is, or -1
  std::vector<int> pool, first{0};
  std::vector<int> sum;
  explicit Z2Columns(std::size_t rows) : pivot_of(rows, -1) {}
  int kept() const { return static_cast<int>(first.size()) - 1; }
  // Reduces c by the kept columns; keeps it when non-zero. Returns its lowest row, or -1.
  int reduce_and_add(std::vector<int>& c) {
    while (!c.empty() && pivot_of[c.back()] >= 0) {
      const int j = pivot_of[c.back()];
      sum.clear();
      std::set_symmetric_difference(c.begin(), c.end(), pool.begin() + first[j],
                                    pool.begin() + first[j + 1], std::back_inserter(sum));
      c.swap(sum);
    }
    if (c.empty()) return -1;
    pivot_of[c.back()] = kept();
    pool.insert(pool.end(), c.begin(), c.end());
    first.push_back(static_cast<int>(pool.size()));
    return c.back();
  }
};

// Step 1: annotations.
struct Annotation {
  int beta1 = 0;
  int words = 0;
  std::vector<Word> edge_ann;  // m x words; zero for tree edges and null fundamental cycles
  std::vector<int> component;  // per vertex
};

// A shortest-path spanning forest: fundamental cycles stay tight, so few edges carry a non-zero
// annotation (the roots of the fast path). Per vertex its component and distance from its root;
// per edge whether it is a tree edge.
struct Forest {
  std::vector<int> component;
  std::vector<double> dist;
  std::vector<char> tree;
};

Forest shortest_path_forest(const Graph& g, int edges) {
  Forest f;
  f.component.assign(g.n, -1);
  f.dist.assign(g.n, kInf);
  f.tree.assign(edges, 0);
  Dijkstra dj(g, 0);
  int comp = 0;
  for (int r = 0; r < g.n; ++r) {
    if (f.component[r] >= 0) continue;
    dj.run(r, kInf, nullptr, [](int, int, int, double) {});
    for (int v : dj.order()) {
      f.component[v] = comp;
      f.dist[v] = dj.dist(v);
      if (dj.parent_edge(v) >= 0) f.tree[dj.parent_edge(v)] = 1;
    }
    ++comp;
  }
  return f;
}

// A triangle's boundary in non-tree coordinates (at most three, ascending).
struct Boundary {
  int size = 0;
  std::array<int, 3> c{};
  int triangle = -1;
  int low() const { return c[size - 1]; }
};

// The non-zero triangle boundaries (all, unless a triangle repeats an edge) in reduction order:
// by low, then lexicographically, then by triangle. The lows are coordinates below kc, so the
// columns are bucketed by low first (a counting sort) and only each bucket's few columns are
// compared. The columns are moved into that order, so that the reduction reads them in sequence
// (reading them through an index was a quarter of annotate()'s time).
std::vector<Boundary> boundary_columns(const SimplicialComplex& k, const std::vector<int>& coord_of,
                                       int kc) {
  std::vector<Boundary> columns;
  columns.reserve(k.triangles.size());
  for (size_t t = 0; t < k.triangles.size(); ++t) {
    Boundary b;
    b.triangle = static_cast<int>(t);
    for (int e : k.triangles[t])
      if (coord_of[e] >= 0) b.c[b.size++] = coord_of[e];
    if (b.size == 0) continue;
    for (int i = 1; i < b.size; ++i)  // at most three entries: insertion sort
      for (int j = i; j > 0 && b.c[j - 1] > b.c[j]; --j) std::swap(b.c[j - 1], b.c[j]);
    columns.push_back(b);
  }
  std::vector<int> start;
  columns = detail::sorted_by_key(
      columns, kc, [](const Boundary& b) { return b.low(); }, &start);
  const auto lexicographic = [](const Boundary& x, const Boundary& y) {
    if (std::lexicographical_compare(x.c.begin(), x.c.begin() + x.size, y.c.begin(),
                                     y.c.begin() + y.size))
      return true;
    if (std::lexicographical_compare(y.c.begin(), y.c.begin() + y.size, x.c.begin(),
                                     x.c.begin() + x.size))
      return false;
    return x.triangle < y.triangle;
  };
  for (int l = 0; l < kc; ++l)
    if (start[l + 1] - start[l] > 1)
      std::sort(columns.begin() + start[l], columns.begin() + start[l + 1], lexicographic);
  return columns;
}

// Clearing (the "twist" of Chen and Kerber): a tetrahedron's boundary is a 2-cycle, so once the
// tetrahedra's boundaries are reduced, the lowest triangle of each non-zero reduced column is a
// sum of triangles reduced before it: its column would reduce to zero, and is skipped. The same
// pivots; nearly all the work where K_d is thick went into columns reaching zero (the purse at
// 40,000 points, K_d': 1.7 M of 1.74 M column additions with only each tetrahedron's last face
// skipped). Tetrahedra are taken in the order of their last face, so their columns stay short.
// (A face with a zero column drops out of its tetrahedron's relation.) Per column: skip it?
std::vector<char> cleared_columns(const SimplicialComplex& k,
                                  const std::vector<Boundary>& columns) {
  std::vector<int> position(k.triangles.size(), -1);
  for (size_t i = 0; i < columns.size(); ++i) position[columns[i].triangle] = static_cast<int>(i);
  std::vector<char> dependent(columns.size(), 0);
  std::vector<std::array<int, 4>> faces;
  faces.reserve(k.tetrahedra.size());
  for (const auto& tet : k.tetrahedra) {
    std::array<int, 4> f;
    for (int q = 0; q < 4; ++q) f[q] = position[tet[q]];
    std::sort(f.begin(), f.end());
    if (f[3] >= 0) faces.push_back(f);
  }
  faces = detail::sorted_by_key(faces, static_cast<int>(columns.size()),
                                [](const std::array<int, 4>& f) { return f[3]; });
  Z2Columns tets(columns.size());
  std::vector<int> col;
  for (const auto& f : faces) {
    col.clear();
    for (int x : f)
      if (x >= 0) col.push_back(x);
    const int low = tets.reduce_and_add(col);
    if (low >= 0) dependent[low] = 1;
  }
  return dependent;
}

// Annotation of coordinate i: e_i reduced by the pivots, read on the beta1 free coordinates
// (W words each). A pivot column's entries are all below its pivot, so one increasing pass
// suffices.
std::vector<Word> coordinate_annotations(const Z2Columns& reduced, int kc, int W) {
  std::vector<Word> coord_ann(size_t(kc) * W, 0);
  int free_index = 0;
  for (int i = 0; i < kc; ++i) {
    Word* ai = coord_ann.data() + size_t(i) * W;
    if (reduced.pivot_of[i] < 0) {
      ai[free_index / 64] |= Word(1) << (free_index % 64);
      ++free_index;
      continue;
    }
    const int p = reduced.pivot_of[i];
    for (int q = reduced.first[p]; q < reduced.first[p + 1]; ++q) {
      const int j = reduced.pool[q];
      if (j == i) continue;
      const Word* aj = coord_ann.data() + size_t(j) * W;
      for (int w = 0; w < W; ++w) ai[w] ^= aj[w];
    }
  }
  return coord_ann;
}

Annotation annotate(const SimplicialComplex& k, const Graph& g, bool need_annotations,
                    int max_beta1) {
  const int m = static_cast<int>(k.edges.size());
  Annotation a;
  Forest forest = shortest_path_forest(g, m);
  a.component = std::move(forest.component);
  // Coordinates: the non-tree edges, ordered by distance from their component's root so that the
  // reduction behaves like a persistence computation along a sweep (short chains, little fill).
  // (Keys sorted beside their edges: the sort then reads memory in order.)
  std::vector<std::pair<double, int>> coords;
  for (int e = 0; e < m; ++e)
    if (!forest.tree[e])
      coords.emplace_back(std::max(forest.dist[k.edges[e][0]], forest.dist[k.edges[e][1]]), e);
  std::sort(coords.begin(), coords.end());
  std::vector<int> coord_of(m, -1);
  for (size_t i = 0; i < coords.size(); ++i) coord_of[coords[i].second] = static_cast<int>(i);
  const int kc = static_cast<int>(coords.size());
  // Triangle boundaries in non-tree coordinates, reduced over Z2 (low-pivot reduction).
  const std::vector<Boundary> columns = boundary_columns(k, coord_of, kc);
  const std::vector<char> dependent = cleared_columns(k, columns);
  Z2Columns reduced(kc);
  std::vector<int> col;
  for (size_t i = 0; i < columns.size(); ++i) {
    if (dependent[i]) continue;
    const Boundary& b = columns[i];
    col.assign(b.c.begin(), b.c.begin() + b.size);
    reduced.reduce_and_add(col);
  }
  a.beta1 = kc - reduced.kept();
  if (a.beta1 > max_beta1)
    throw InputError("K_d has beta1 = " + std::to_string(a.beta1) + " (more than " +
                     std::to_string(max_beta1) + " loops): d = " + std::to_string(k.d) +
                     " m is too small for these points; use a larger d");
  if (!need_annotations || a.beta1 == 0) return a;
  a.words = (a.beta1 + 63) / 64;
  const int W = a.words;
  const std::vector<Word> coord_ann = coordinate_annotations(reduced, kc, W);
  a.edge_ann.assign(size_t(m) * W, 0);
  for (int e = 0; e < m; ++e)
    if (coord_of[e] >= 0)
      std::copy_n(coord_ann.data() + size_t(coord_of[e]) * W, W, a.edge_ann.data() + size_t(e) * W);
  return a;
}

}  // namespace

int betti_1(const SimplicialComplex& complex) {
  const Graph g(complex);
  return annotate(complex, g, false, std::numeric_limits<int>::max()).beta1;
}

std::vector<bool> bounds_in(const SimplicialComplex& larger,
                            const std::vector<std::vector<int>>& cycles) {
  std::vector<bool> out(cycles.size(), true);
  if (cycles.empty()) return out;
  const Graph g(larger);
  const Annotation a = annotate(larger, g, true, std::numeric_limits<int>::max());
  if (a.beta1 == 0) return out;
  const int W = a.words;
  std::vector<Word> cls(W);
  for (std::size_t c = 0; c < cycles.size(); ++c) {
    std::fill(cls.begin(), cls.end(), 0);
    const auto& vs = cycles[c];
    for (std::size_t i = 0; i < vs.size(); ++i) {
      const int u = vs[i], w = vs[(i + 1) % vs.size()];
      const int edge = g.edge_between(u, w);
      if (edge < 0)
        throw std::invalid_argument("bounds_in: the cycle's edge " + std::to_string(u) + "-" +
                                    std::to_string(w) + " is not in the larger complex");
      for (int k = 0; k < W; ++k) cls[k] ^= a.edge_ann[size_t(edge) * W + k];
    }
    out[c] = is_zero(cls.data(), W);
  }
  return out;
}

namespace {

// K_d' annotations restricted to K_d are supported where K_d''s spanning tree closed its cycles,
// which can be a long seam across a surface. Adding a coboundary, ann(uw) ^= pa(u) ^ pa(w), keeps
// every cycle's class (the pa terms cancel around it); with pa the prefix annotations of a
// shortest-path tree of K_d, the support becomes where that tree's fronts met around each hole.
// Of a few roots per component the tree with the fewest support edges is kept: every support edge
// costs a Dijkstra root later (the purse at 40,000 points: 1,235 support edges before, 178 after).
void regauge(const Graph& g, int W, const std::vector<int>& component, int threads,
             std::vector<Word>& ann) {
  std::vector<std::vector<int>> members;
  for (int v = 0; v < g.n; ++v) {
    if (component[v] >= static_cast<int>(members.size())) members.resize(component[v] + 1);
    members[component[v]].push_back(v);
  }
  // The four trees of a component are grown side by side (each with its own search and prefix
  // annotations); the first with the fewest support edges wins, as in sequence.
  constexpr int kTrees = 4;
  std::vector<std::unique_ptr<Dijkstra>> dj;
  std::vector<std::vector<Word>> pa(kTrees, std::vector<Word>(size_t(g.n) * W));
  for (int q = 0; q < kTrees; ++q) dj.push_back(std::make_unique<Dijkstra>(g, W));
  std::vector<Word> best_pa(size_t(g.n) * W, 0);
  // Each edge of the vertices vs once, from its lower end: f(v, w, its annotation).
  const auto for_each_edge = [&](const std::vector<int>& vs, auto&& f) {
    for (int v : vs)
      for (int k = g.start[v]; k < g.start[v + 1]; ++k)
        if (g.arcs[k].to > v) f(v, g.arcs[k].to, ann.data() + size_t(g.arcs[k].edge) * W);
  };
  // The edges whose annotation plus the coboundary of p is non-zero.
  const auto support_of = [&](const std::vector<int>& vs, const std::vector<Word>& p) {
    int count = 0;
    for_each_edge(vs, [&](int v, int w, const Word* a) {
      bool zero = true;
      for (int j = 0; j < W; ++j)
        zero = zero && !(a[j] ^ p[size_t(v) * W + j] ^ p[size_t(w) * W + j]);
      count += !zero;
    });
    return count;
  };
  for (const auto& vs : members) {
    int best = support_of(vs, best_pa);  // the gauge as it is
    std::array<int, kTrees> count{};
    const auto grow = [&](std::size_t first, std::size_t last) {
      for (std::size_t q = first; q < last; ++q) {
        dj[q]->run(vs[vs.size() * q / kTrees], kInf, ann.data(), [](int, int, int, double) {});
        for (int v : vs) std::copy_n(dj[q]->pa(v), W, pa[q].begin() + size_t(v) * W);
        count[q] = support_of(vs, pa[q]);
      }
    };
    // Small components (noise clusters, many of them) are not worth a thread each.
    parallel_chunks(kTrees, vs.size() < 2000 ? 1 : threads, grow);
    for (int q = 0; q < kTrees; ++q)
      if (count[q] < best) {
        best = count[q];
        for (int v : vs)
          std::copy_n(pa[q].begin() + size_t(v) * W, W, best_pa.begin() + size_t(v) * W);
      }
  }
  for (const auto& vs : members)
    for_each_edge(vs, [&](int v, int w, Word* a) {
      for (int j = 0; j < W; ++j) a[j] ^= best_pa[size_t(v) * W + j] ^ best_pa[size_t(w) * W + j];
    });
}

}  // namespace

HomologyBasis shortest_homology_basis(const SimplicialComplex& complex,
                                      const HomologyOptions& options) {
  const Graph g(complex);
  const Annotation a = annotate(complex, g, true, options.max_beta1);
  HomologyBasis out;
  out.beta1 = a.beta1;
  if (a.beta1 > 0)
    shortest_cycles(complex, g, a.edge_ann.data(), a.words, a.component, a.beta1, options, out);
  return out;
}

HomologyBasis persistent_homology_basis(const SimplicialComplex& complex,
                                        const SimplicialComplex& larger,
                                        const HomologyOptions& options) {
  // K_d''s graph and annotations, and K_d's own graph and reduction (beta1 and components), are
  // independent: with more than one thread they are built side by side.
  std::unique_ptr<Graph> gl;
  Annotation big;
  const auto larger_reduction = [&] {
    gl = std::make_unique<Graph>(larger);
    big = annotate(larger, *gl, true, std::numeric_limits<int>::max());
  };
  std::unique_ptr<Graph> own_graph;
  Annotation own;
  const auto own_reduction = [&] {
    own_graph = std::make_unique<Graph>(complex);
    own = annotate(complex, *own_graph, false, options.max_beta1);
  };
  parallel_invoke(own_reduction, larger_reduction, options.threads);
  const Graph& g = *own_graph;
  HomologyBasis out;
  out.beta1 = own.beta1;
  if (own.beta1 == 0 || big.beta1 == 0) return out;
  // Each edge of K_d carries its annotation in K_d': a cycle's class there is their XOR.
  const int W = big.words;
  std::vector<Word> ann(complex.edges.size() * W, 0);
  for (size_t e = 0; e < complex.edges.size(); ++e) {
    const int u = complex.edges[e][0], w = complex.edges[e][1];
    const int in_larger = gl->edge_between(u, w);
    if (in_larger < 0)
      throw std::invalid_argument("persistent_homology_basis: the edge " + std::to_string(u) + "-" +
                                  std::to_string(w) + " is not in the larger complex");
    std::copy_n(big.edge_ann.data() + size_t(in_larger) * W, W, ann.data() + e * W);
  }
  regauge(g, W, own.component, options.threads, ann);
  shortest_cycles(complex, g, ann.data(), W, own.component, -1, options, out);
  return out;
}

}  // namespace claspplan::perception
