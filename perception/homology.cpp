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

namespace claspplan::perception {

namespace {

using homology_detail::Dijkstra;
using homology_detail::Graph;
using homology_detail::kInf;
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
  // (Keys sorted beside their edges: the sort then reads memory in order.)
  std::vector<std::pair<double, int>> coords;
  for (int e = 0; e < m; ++e)
    if (!tree[e]) coords.emplace_back(std::max(dist0[k.edges[e][0]], dist0[k.edges[e][1]]), e);
  std::sort(coords.begin(), coords.end());
  std::vector<int> coord_of(m, -1);
  for (size_t i = 0; i < coords.size(); ++i) coord_of[coords[i].second] = static_cast<int>(i);
  const int kc = static_cast<int>(coords.size());
  // Triangle boundaries in non-tree coordinates (at most three, ascending), reduced over Z2
  // (low-pivot reduction).
  struct Boundary {
    int size = 0;
    std::array<int, 3> c{};
    int triangle = -1;
    int low() const { return c[size - 1]; }
  };
  // Reduction order: by low, then lexicographically, then by triangle. The lows are coordinates
  // below kc, so the columns are bucketed by low first (a counting sort) and only each bucket's
  // few columns are compared. The columns are moved into that order, so that the reduction reads
  // them in sequence (reading them through an index was a quarter of this function's time).
  std::vector<Boundary> columns;  // the non-zero ones (all, unless a triangle repeats an edge)
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
  {
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
  }
  // Clearing (the "twist" of Chen and Kerber): a tetrahedron's boundary is a 2-cycle, so once the
  // tetrahedra's boundaries are reduced, the lowest triangle of each non-zero reduced column is a
  // sum of triangles reduced before it: its column would reduce to zero, and is skipped. The same
  // pivots; nearly all the work where K_d is thick went into columns reaching zero (the purse at
  // 40,000 points, K_d': 1.7 M of 1.74 M column additions with only each tetrahedron's last face
  // skipped). Tetrahedra are taken in the order of their last face, so their columns stay short.
  // (A face with a zero column drops out of its tetrahedron's relation.)
  std::vector<int> position(k.triangles.size(), -1);
  for (size_t i = 0; i < columns.size(); ++i) position[columns[i].triangle] = static_cast<int>(i);
  std::vector<char> dependent(columns.size(), 0);
  {
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
  }
  Z2Columns reduced(kc);
  std::vector<int> col;
  for (size_t i = 0; i < columns.size(); ++i) {
    if (dependent[i]) continue;
    const Boundary& b = columns[i];
    col.assign(b.c.begin(), b.c.begin() + b.size);
    reduced.reduce_and_add(col);
  }
  const std::vector<int>& pivot_of = reduced.pivot_of;
  const std::vector<int>& pool = reduced.pool;
  const std::vector<int>& first = reduced.first;
  const int rank = reduced.kept();
  a.beta1 = kc - rank;
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
    const int p = pivot_of[i];
    for (int q = first[p]; q < first[p + 1]; ++q) {
      const int j = pool[q];
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

// Steps 2-3 for any annotation `ann` (W words per edge) of the complex's edges: the shortest cycles
// whose classes are independent and non-zero, `rank` of them (-1: as many as the candidates of one
// full tree per component span), into out.cycles (shortest first).
void shortest_cycles(const SimplicialComplex& complex, const Graph& g, const Word* ann, int W,
                     const std::vector<int>& component, int rank, const HomologyOptions& options,
                     HomologyBasis& out) {
  const int m = static_cast<int>(complex.edges.size());

  std::vector<int> support;
  for (int e = 0; e < m; ++e)
    if (!is_zero(ann + size_t(e) * W, W)) support.push_back(e);
  out.support_edges = static_cast<int>(support.size());

  std::vector<Candidate> cand;
  std::vector<Word> classes;
  std::unordered_map<std::string, int> by_class;
  double bound = kInf;  // candidates longer than the worst loop of a full basis are useless
  auto class_key = [W](const Word* cls) {
    return std::string(reinterpret_cast<const char*>(cls), W * sizeof(Word));
  };
  // One root's tree: per non-zero class it closes, its shortest cycle within the bound.
  struct Found {
    std::vector<Candidate> cand;
    std::vector<Word> classes;
  };
  auto run_root = [&](Dijkstra& dj, int root, double radius, Found& f) {
    std::unordered_map<std::string, int> index;
    std::vector<Word> cls(W);
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
      const Candidate fresh{length, root, e};
      const auto [it, added] =
          index.emplace(class_key(cls.data()), static_cast<int>(f.cand.size()));
      if (added) {
        f.cand.push_back(fresh);
        f.classes.insert(f.classes.end(), cls.begin(), cls.end());
      } else if (before(fresh, f.cand[it->second])) {
        f.cand[it->second] = fresh;
      }
    });
  };
  // Roots run on all cores (a Dijkstra each), then merge in root order: only the shortest
  // candidate of each class can enter the basis, so one per class is kept. The result does not
  // depend on the number of threads.
  const int threads = std::min(thread_count(options.threads, 64), 64);
  std::vector<std::unique_ptr<Dijkstra>> workers;
  for (int t = 0; t < threads; ++t) workers.push_back(std::make_unique<Dijkstra>(g, W));
  std::vector<char> rooted(g.n, 0);
  auto collect = [&](const std::vector<int>& roots, double radius) {
    std::vector<Found> found(roots.size());
    parallel_for(roots.size(), threads, [&](std::size_t i, int worker) {
      run_root(*workers[worker], roots[i], radius, found[i]);
    });
    for (size_t i = 0; i < roots.size(); ++i) {
      if (!rooted[roots[i]]) ++out.roots, rooted[roots[i]] = 1;
      const Found& f = found[i];
      for (size_t c = 0; c < f.cand.size(); ++c) {
        const Word* cls = f.classes.data() + c * W;
        const auto [it, added] = by_class.emplace(class_key(cls), static_cast<int>(cand.size()));
        if (added) {
          cand.push_back(f.cand[c]);
          classes.insert(classes.end(), cls, cls + W);
        } else if (before(f.cand[c], cand[it->second])) {
          cand[it->second] = f.cand[c];
        }
      }
    }
  };
  // The greedy basis of the candidates so far, as candidate indices sorted by length; tightens
  // the bound and drops candidates above it once the basis is full.
  auto basis = [&]() {
    std::vector<int> kept = greedy(cand, classes, W, rank);
    std::sort(kept.begin(), kept.end(), [&](int x, int y) { return before(cand[x], cand[y]); });
    if (static_cast<int>(kept.size()) == rank && cand[kept.back()].length < bound) {
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
        by_class.emplace(class_key(classes.data() + c * W), static_cast<int>(c));
      for (int& k : kept) k = remap[k];
    }
    return kept;
  };

  // Without a given rank, the candidates of full trees span the image: their greedy's size.
  auto spanned_rank = [&]() {
    return static_cast<int>(greedy(cand, classes, W, std::numeric_limits<int>::max()).size());
  };
  if (!options.fast) {
    std::vector<int> all(g.n);
    std::iota(all.begin(), all.end(), 0);
    collect(all, kInf);
    if (rank < 0) rank = spanned_rank();
    if (rank == 0) return;
  } else {
    // One root per component with loops, unbounded: its candidates span that component's H1, so
    // the greedy then has a full basis and the bound.
    const std::vector<int> cover = vertex_cover(complex, support, g.n);
    std::vector<char> has_support(g.n, 0), seen(g.n, 0);
    std::vector<double> radius_done(g.n, -1.0);
    for (int e : support) has_support[component[complex.edges[e][0]]] = 1;
    std::vector<int> first_roots;
    for (int r : cover) {
      const int c = component[r];
      if (has_support[c] && !seen[c]) {
        seen[c] = 1;
        first_roots.push_back(r);
        radius_done[r] = kInf;
      }
    }
    collect(first_roots, kInf);
    if (rank < 0) rank = spanned_rank();
    if (rank == 0) return;  // no loop persists
    // Levels. After all roots on the edges whose annotation is outside V (the span of the loops
    // certified so far) have run with radius rho, every basis loop of length <= 2 rho is found:
    // such a loop's class is outside V, so one of its edges is, and a root on it sees the whole
    // loop within half its length. The greedy's loops up to 2 rho are then certified.
    Span certified(W);
    int n_certified = 0;
    while (true) {
      const std::vector<int> kept = basis();
      if (static_cast<int>(kept.size()) != rank)
        throw std::logic_error("shortest basis: the candidates do not span H1");
      if (n_certified == rank) break;
      // This level: the next uncertified loops whose lengths are within 5% of the first.
      const double first = cand[kept[n_certified]].length;
      double level = first;
      for (int k = n_certified; k < rank && cand[kept[k]].length <= 1.05 * first; ++k)
        level = cand[kept[k]].length;
      std::vector<int> outside;
      std::vector<Word> v(W);
      for (int e : support) {
        std::copy_n(ann + size_t(e) * W, W, v.begin());
        if (!certified.reduce(v)) outside.push_back(e);
      }
      std::vector<int> roots;
      for (int r : vertex_cover(complex, outside, g.n)) {
        if (radius_done[r] >= level / 2) continue;
        roots.push_back(r);
        radius_done[r] = level / 2;
      }
      collect(roots, level / 2);
      const std::vector<int> now = basis();
      for (int k = n_certified; k < rank; ++k) {
        if (cand[now[k]].length > level) break;
        certified.insert(std::vector<Word>(classes.begin() + size_t(now[k]) * W,
                                           classes.begin() + size_t(now[k] + 1) * W));
        ++n_certified;
      }
    }
  }
  const std::vector<int> kept = greedy(cand, classes, W, rank);
  if (static_cast<int>(kept.size()) != rank)
    throw std::logic_error("shortest basis: the candidates do not span H1");

  // Rebuild each loop: the two tree paths from the root, joined at their last common vertex.
  std::vector<int> mark(g.n, -1);
  Dijkstra& dj = *workers[0];
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
}

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
