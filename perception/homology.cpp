#include "perception/homology.hpp"

#include <algorithm>
#include <cstdint>
#include <limits>
#include <numeric>
#include <queue>
#include <stdexcept>
#include <string>
#include <unordered_map>
#include <utility>

#include "perception/homology_graph.hpp"
#include "perception/input_error.hpp"

namespace claspplan::perception {

namespace {

using homology_detail::Dijkstra;
using homology_detail::Graph;
using homology_detail::kInf;
using homology_detail::Word;

// Step 1: annotations.
struct Annotation {
  int beta1 = 0;
  int words = 0;
  std::vector<Word> edge_ann;  // m x words; zero for tree edges and null fundamental cycles
  std::vector<int> component;  // per vertex
};

std::vector<int> symmetric_difference(const std::vector<int>& a, const std::vector<int>& b) {
  std::vector<int> out;
  out.reserve(a.size() + b.size());
  std::set_symmetric_difference(a.begin(), a.end(), b.begin(), b.end(), std::back_inserter(out));
  return out;
}

Annotation annotate(const SimplicialComplex& k, const Graph& g, bool need_annotations,
                    int max_beta1) {
  const int n = g.n;
  const int m = static_cast<int>(k.edges.size());
  Annotation a;
  a.component.assign(n, -1);
  // A shortest-path spanning forest: fundamental cycles stay tight, so few edges carry a non-zero
  // annotation (the roots of the fast path).
  std::vector<char> tree(m, 0);
  std::vector<double> dist0(n, kInf);
  {
    Dijkstra dj(g, 0);
    int comp = 0;
    for (int r = 0; r < n; ++r) {
      if (a.component[r] >= 0) continue;
      dj.run(r, kInf, nullptr, [](int, int, int, double) {});
      for (int v : dj.order()) {
        a.component[v] = comp;
        dist0[v] = dj.dist(v);
        if (dj.parent_edge(v) >= 0) tree[dj.parent_edge(v)] = 1;
      }
      ++comp;
    }
  }
  // Coordinates: the non-tree edges, ordered by distance from their component's root so that the
  // reduction behaves like a persistence computation along a sweep (short chains, little fill).
  std::vector<int> coords;
  for (int e = 0; e < m; ++e)
    if (!tree[e]) coords.push_back(e);
  auto key = [&](int e) { return std::max(dist0[k.edges[e][0]], dist0[k.edges[e][1]]); };
  std::sort(coords.begin(), coords.end(), [&](int x, int y) {
    const double kx = key(x), ky = key(y);
    return kx != ky ? kx < ky : x < y;
  });
  std::vector<int> coord_of(m, -1);
  for (size_t i = 0; i < coords.size(); ++i) coord_of[coords[i]] = static_cast<int>(i);
  const int kc = static_cast<int>(coords.size());
  // Triangle boundaries in non-tree coordinates, reduced over Z2 (low-pivot reduction).
  std::vector<std::vector<int>> columns(k.triangles.size());
  std::vector<int> order;  // the triangles with a non-zero column, in reduction order
  order.reserve(k.triangles.size());
  for (size_t t = 0; t < k.triangles.size(); ++t) {
    auto& c = columns[t];
    for (int e : k.triangles[t])
      if (coord_of[e] >= 0) c.push_back(coord_of[e]);
    std::sort(c.begin(), c.end());
    if (!c.empty()) order.push_back(static_cast<int>(t));
  }
  std::sort(order.begin(), order.end(), [&](int i, int j) {
    const auto &x = columns[i], &y = columns[j];
    return x.back() != y.back() ? x.back() < y.back() : x < y;
  });
  // A tetrahedron's four faces sum to a zero boundary, so the last of them to be reduced is a sum
  // of columns already seen: it would reduce to zero, and is skipped (the same pivots, far less
  // work where K_d is thick: most of such a column's additions are spent reaching zero).
  std::vector<int> position(k.triangles.size(), -1);
  for (size_t i = 0; i < order.size(); ++i) position[order[i]] = static_cast<int>(i);
  std::vector<char> dependent(order.size(), 0);
  for (const auto& tet : k.tetrahedra) {
    int last = -1;
    for (int t : tet) last = std::max(last, position[t]);
    if (last >= 0) dependent[last] = 1;
  }
  std::vector<int> pivot_of(kc, -1);
  std::vector<std::vector<int>> reduced;
  for (size_t i = 0; i < order.size(); ++i) {
    if (dependent[i]) continue;
    auto& c = columns[order[i]];
    while (!c.empty() && pivot_of[c.back()] >= 0)
      c = symmetric_difference(c, reduced[pivot_of[c.back()]]);
    if (c.empty()) continue;
    pivot_of[c.back()] = static_cast<int>(reduced.size());
    reduced.push_back(std::move(c));
  }
  a.beta1 = kc - static_cast<int>(reduced.size());
  if (a.beta1 > max_beta1)
    throw InputError("K_d has beta1 = " + std::to_string(a.beta1) + " (more than " +
                     std::to_string(max_beta1) + " loops): d = " + std::to_string(k.d) +
                     " m is too small for these points; use a larger d");
  if (!need_annotations || a.beta1 == 0) return a;
  // Annotation of coordinate i: e_i reduced by the pivots, read on the beta1 free coordinates.
  // A pivot column's entries are all below its pivot, so one increasing pass suffices.
  a.words = (a.beta1 + 63) / 64;
  const int W = a.words;
  std::vector<Word> coord_ann(size_t(kc) * W, 0);
  int free_index = 0;
  for (int i = 0; i < kc; ++i) {
    Word* ai = coord_ann.data() + size_t(i) * W;
    if (pivot_of[i] < 0) {
      ai[free_index / 64] |= Word(1) << (free_index % 64);
      ++free_index;
      continue;
    }
    for (int j : reduced[pivot_of[i]]) {
      if (j == i) continue;
      const Word* aj = coord_ann.data() + size_t(j) * W;
      for (int w = 0; w < W; ++w) ai[w] ^= aj[w];
    }
  }
  a.edge_ann.assign(size_t(m) * W, 0);
  for (int e = 0; e < m; ++e)
    if (coord_of[e] >= 0)
      std::copy_n(coord_ann.data() + size_t(coord_of[e]) * W, W, a.edge_ann.data() + size_t(e) * W);
  return a;
}

bool is_zero(const Word* v, int W) {
  for (int w = 0; w < W; ++w)
    if (v[w]) return false;
  return true;
}

struct Candidate {
  double length;
  int root;
  int edge;
};

// Candidate order: by length, ties by root and edge (deterministic).
bool before(const Candidate& a, const Candidate& b) {
  if (a.length != b.length) return a.length < b.length;
  if (a.root != b.root) return a.root < b.root;
  return a.edge < b.edge;
}

// Step 3: greedy over candidates sorted by length; an XOR basis with pivots on the highest bit.
std::vector<int> greedy(const std::vector<Candidate>& cand, const std::vector<Word>& classes, int W,
                        int beta1) {
  std::vector<int> order(cand.size());
  std::iota(order.begin(), order.end(), 0);
  std::sort(order.begin(), order.end(), [&](int x, int y) { return before(cand[x], cand[y]); });
  std::vector<std::vector<Word>> basis_at(size_t(W) * 64);
  std::vector<int> kept;
  std::vector<Word> v(W);
  for (int c : order) {
    std::copy_n(classes.data() + size_t(c) * W, W, v.begin());
    while (true) {
      int h = -1;
      for (int w = W - 1; w >= 0; --w)
        if (v[w]) {
          h = w * 64 + 63 - __builtin_clzll(v[w]);
          break;
        }
      if (h < 0) break;  // dependent
      if (basis_at[h].empty()) {
        basis_at[h] = v;
        kept.push_back(c);
        break;
      }
      for (int w = 0; w < W; ++w) v[w] ^= basis_at[h][w];
    }
    if (static_cast<int>(kept.size()) == beta1) break;
  }
  return kept;
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
      int edge = -1;
      if (u >= 0 && u < g.n) {
        for (int k = g.start[u]; k < g.start[u + 1]; ++k)
          if (g.arcs[k].to == w) edge = g.arcs[k].edge;
      }
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

// A vertex cover of `edges` (greedy: the vertex with the most uncovered edges first, ties to the
// lower index): every cycle through one of the edges passes through a chosen vertex.
std::vector<int> vertex_cover(const SimplicialComplex& complex, const std::vector<int>& edges,
                              int n) {
  std::vector<std::vector<int>> incident(n);
  for (int e : edges) {
    incident[complex.edges[e][0]].push_back(e);
    incident[complex.edges[e][1]].push_back(e);
  }
  std::vector<int> uncovered(n, 0);
  std::vector<char> covered(complex.edges.size(), 0);
  std::priority_queue<std::pair<int, int>> queue;  // (uncovered degree, -vertex)
  for (int v = 0; v < n; ++v) {
    uncovered[v] = static_cast<int>(incident[v].size());
    if (uncovered[v] > 0) queue.emplace(uncovered[v], -v);
  }
  std::vector<int> roots;
  while (!queue.empty()) {
    const auto [deg, negv] = queue.top();
    queue.pop();
    const int v = -negv;
    if (deg != uncovered[v] || deg == 0) continue;  // stale
    roots.push_back(v);
    for (int e : incident[v]) {
      if (covered[e]) continue;
      covered[e] = 1;
      for (int x : complex.edges[e])
        if (--uncovered[x] > 0 && x != v) queue.emplace(uncovered[x], -x);
    }
  }
  return roots;
}

// An XOR basis (pivot = highest set bit) to test membership in a span of classes.
class Span {
 public:
  explicit Span(int words) : W_(words), at_(size_t(words) * 64) {}
  // Reduces v in place; returns true if v was in the span (reduced to zero).
  bool reduce(std::vector<Word>& v) const {
    for (int h = top(v); h >= 0; h = top(v)) {
      if (at_[h].empty()) return false;
      for (int w = 0; w < W_; ++w) v[w] ^= at_[h][w];
    }
    return true;
  }
  bool insert(std::vector<Word> v) {
    if (reduce(v)) return false;
    at_[top(v)] = std::move(v);
    return true;
  }

 private:
  int top(const std::vector<Word>& v) const {
    for (int w = W_ - 1; w >= 0; --w)
      if (v[w]) return w * 64 + 63 - __builtin_clzll(v[w]);
    return -1;
  }
  int W_;
  std::vector<std::vector<Word>> at_;
};

}  // namespace

HomologyBasis shortest_homology_basis(const SimplicialComplex& complex,
                                      const HomologyOptions& options) {
  const Graph g(complex);
  const Annotation a = annotate(complex, g, true, options.max_beta1);
  HomologyBasis out;
  out.beta1 = a.beta1;
  if (a.beta1 == 0) return out;
  const int W = a.words;
  const int m = static_cast<int>(complex.edges.size());
  const Word* ann = a.edge_ann.data();

  std::vector<int> support;
  for (int e = 0; e < m; ++e)
    if (!is_zero(ann + size_t(e) * W, W)) support.push_back(e);
  out.support_edges = static_cast<int>(support.size());

  Dijkstra dj(g, W);
  std::vector<Candidate> cand;
  std::vector<Word> classes;
  std::unordered_map<std::string, int> by_class;
  double bound = kInf;  // candidates longer than the worst loop of a full basis are useless
  std::vector<Word> cls(W);
  std::vector<char> rooted(g.n, 0);
  auto collect = [&](int root, double radius) {
    if (!rooted[root]) ++out.roots, rooted[root] = 1;
    dj.run(root, radius, ann, [&](int u, int w, int e, double length) {
      const Word* pu = dj.pa(u);
      const Word* pw = dj.pa(w);
      const Word* ae = ann + size_t(e) * W;
      bool zero = true;
      for (int k = 0; k < W; ++k) {
        cls[k] = pu[k] ^ pw[k] ^ ae[k];
        zero = zero && !cls[k];
      }
      if (zero) return;
      // The cycle proper: the two tree paths meet at their lowest common vertex, above which they
      // cancel. Its length is the candidate's (the same class, and never longer than the Horton
      // candidate): short loops far from the root get short lengths, hence tight bounds.
      length -= 2.0 * dj.dist(dj.common_ancestor(u, w));
      if (length > bound) return;
      // Only the shortest candidate of each class can enter the basis: keep one per class.
      const std::string key(reinterpret_cast<const char*>(cls.data()), W * sizeof(Word));
      const Candidate fresh{length, root, e};
      const auto [it, added] = by_class.emplace(key, static_cast<int>(cand.size()));
      if (added) {
        cand.push_back(fresh);
        classes.insert(classes.end(), cls.begin(), cls.end());
      } else if (before(fresh, cand[it->second])) {
        cand[it->second] = fresh;
      }
    });
  };
  // The greedy basis of the candidates so far, as candidate indices sorted by length; tightens
  // the bound and drops candidates above it once the basis is full.
  auto basis = [&]() {
    std::vector<int> kept = greedy(cand, classes, W, a.beta1);
    std::sort(kept.begin(), kept.end(), [&](int x, int y) { return before(cand[x], cand[y]); });
    if (static_cast<int>(kept.size()) == a.beta1 && cand[kept.back()].length < bound) {
      bound = cand[kept.back()].length;
      std::vector<int> remap(cand.size(), -1);
      size_t n_kept = 0;
      for (size_t c = 0; c < cand.size(); ++c) {
        if (cand[c].length > bound) continue;
        cand[n_kept] = cand[c];
        std::copy_n(classes.begin() + c * W, W, classes.begin() + n_kept * W);
        remap[c] = static_cast<int>(n_kept++);
      }
      cand.resize(n_kept);
      classes.resize(n_kept * W);
      by_class.clear();
      for (size_t c = 0; c < cand.size(); ++c)
        by_class.emplace(
            std::string(reinterpret_cast<const char*>(classes.data() + c * W), W * sizeof(Word)),
            static_cast<int>(c));
      for (int& k : kept) k = remap[k];
    }
    return kept;
  };

  if (!options.fast) {
    for (int v = 0; v < g.n; ++v) collect(v, kInf);
  } else {
    // One root per component with loops, unbounded: its candidates span that component's H1, so
    // the greedy then has a full basis and the bound.
    const std::vector<int> cover = vertex_cover(complex, support, g.n);
    std::vector<char> has_support(g.n, 0), seen(g.n, 0);
    std::vector<double> radius_done(g.n, -1.0);
    for (int e : support) has_support[a.component[complex.edges[e][0]]] = 1;
    for (int r : cover) {
      const int c = a.component[r];
      if (has_support[c] && !seen[c]) {
        seen[c] = 1;
        collect(r, kInf);
        radius_done[r] = kInf;
      }
    }
    // Levels. After all roots on the edges whose annotation is outside V (the span of the loops
    // certified so far) have run with radius rho, every basis loop of length <= 2 rho is found:
    // such a loop's class is outside V, so one of its edges is, and a root on it sees the whole
    // loop within half its length. The greedy's loops up to 2 rho are then certified.
    Span certified(W);
    int n_certified = 0;
    while (true) {
      const std::vector<int> kept = basis();
      if (static_cast<int>(kept.size()) != a.beta1)
        throw std::logic_error("shortest basis: the candidates do not span H1");
      if (n_certified == a.beta1) break;
      // This level: the next uncertified loops whose lengths are within 5% of the first.
      const double first = cand[kept[n_certified]].length;
      double level = first;
      for (int k = n_certified; k < a.beta1 && cand[kept[k]].length <= 1.05 * first; ++k)
        level = cand[kept[k]].length;
      std::vector<int> outside;
      std::vector<Word> v(W);
      for (int e : support) {
        std::copy_n(ann + size_t(e) * W, W, v.begin());
        if (!certified.reduce(v)) outside.push_back(e);
      }
      for (int r : vertex_cover(complex, outside, g.n)) {
        if (radius_done[r] >= level / 2) continue;
        collect(r, level / 2);
        radius_done[r] = level / 2;
      }
      const std::vector<int> now = basis();
      for (int k = n_certified; k < a.beta1; ++k) {
        if (cand[now[k]].length > level) break;
        certified.insert(std::vector<Word>(classes.begin() + size_t(now[k]) * W,
                                           classes.begin() + size_t(now[k] + 1) * W));
        ++n_certified;
      }
    }
  }
  const std::vector<int> kept = greedy(cand, classes, W, a.beta1);
  if (static_cast<int>(kept.size()) != a.beta1)
    throw std::logic_error("shortest basis: the candidates do not span H1");

  // Rebuild each loop: the two tree paths from the root, joined at their last common vertex.
  std::vector<int> mark(g.n, -1);
  for (size_t idx = 0; idx < kept.size(); ++idx) {
    const Candidate& c = cand[kept[idx]];
    const int u = complex.edges[c.edge][0], w = complex.edges[c.edge][1];
    dj.run(
        c.root, kInf, nullptr, [](int, int, int, double) {}, u, w);
    std::vector<int> up_u, up_w;
    for (int v = u; v >= 0; v = dj.parent_vertex(v)) {
      up_u.push_back(v);
      mark[v] = static_cast<int>(idx);
    }
    int lca = w;
    while (mark[lca] != static_cast<int>(idx)) {
      up_w.push_back(lca);
      lca = dj.parent_vertex(lca);
    }
    BasisCycle cyc;
    for (int v : up_u) {
      cyc.vertices.push_back(v);
      cyc.edges.push_back(dj.parent_edge(v));
      if (v == lca) break;
    }
    cyc.edges.pop_back();  // the LCA's own parent edge is not on the loop
    for (auto it = up_w.rbegin(); it != up_w.rend(); ++it) {
      cyc.edges.push_back(dj.parent_edge(*it));
      cyc.vertices.push_back(*it);
    }
    cyc.edges.push_back(c.edge);  // w -> u closes it
    for (int e : cyc.edges) cyc.length += complex.edge_length[e];
    out.cycles.push_back(std::move(cyc));
  }
  std::stable_sort(out.cycles.begin(), out.cycles.end(),
                   [](const BasisCycle& x, const BasisCycle& y) { return x.length < y.length; });
  return out;
}

}  // namespace claspplan::perception
