#include "perception/shortest_cycles.hpp"

#include <algorithm>
#include <limits>
#include <memory>
#include <numeric>
#include <queue>
#include <stdexcept>
#include <string>
#include <unordered_map>
#include <utility>

#include "core/parallel.hpp"

namespace claspplan::perception::homology_detail {

namespace {

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

// The candidate cycles found so far, one per class (the shortest), and the bound on their
// length; the search's Dijkstra workers, one per thread.
class CandidateSearch {
 public:
  CandidateSearch(const Graph& g, const Word* ann, int W, const HomologyOptions& options,
                  HomologyBasis& out)
      : g_(g), ann_(ann), W_(W), out_(out), rooted_(g.n, 0) {
    threads_ = std::min(thread_count(options.threads, 64), 64);
    for (int t = 0; t < threads_; ++t) workers_.push_back(std::make_unique<Dijkstra>(g, W));
  }

  const std::vector<Candidate>& candidates() const { return cand_; }
  const Word* class_of(int c) const { return classes_.data() + size_t(c) * W_; }
  Dijkstra& dijkstra() { return *workers_[0]; }

  // Roots run on all cores (a Dijkstra each, within `radius`), then merge in root order: only the
  // shortest candidate of each class can enter the basis, so one per class is kept. The result
  // does not depend on the number of threads.
  void collect(const std::vector<int>& roots, double radius) {
    std::vector<Found> found(roots.size());
    parallel_for(roots.size(), threads_, [&](std::size_t i, int worker) {
      run_root(*workers_[worker], roots[i], radius, found[i]);
    });
    for (size_t i = 0; i < roots.size(); ++i) {
      if (!rooted_[roots[i]]) ++out_.roots, rooted_[roots[i]] = 1;
      const Found& f = found[i];
      for (size_t c = 0; c < f.cand.size(); ++c) {
        const Word* cls = f.classes.data() + c * W_;
        const auto [it, added] = by_class_.emplace(key(cls), static_cast<int>(cand_.size()));
        if (added) {
          cand_.push_back(f.cand[c]);
          classes_.insert(classes_.end(), cls, cls + W_);
        } else if (before(f.cand[c], cand_[it->second])) {
          cand_[it->second] = f.cand[c];
        }
      }
    }
  }

  // The greedy basis of the candidates so far, as candidate indices sorted by length; tightens
  // the bound and drops candidates above it once the basis is full.
  std::vector<int> basis(int rank) {
    std::vector<int> kept = greedy(cand_, classes_, W_, rank);
    std::sort(kept.begin(), kept.end(), [&](int x, int y) { return before(cand_[x], cand_[y]); });
    if (static_cast<int>(kept.size()) == rank && cand_[kept.back()].length < bound_) {
      bound_ = cand_[kept.back()].length;
      std::vector<int> remap(cand_.size(), -1);
      size_t n_kept = 0;
      for (size_t c = 0; c < cand_.size(); ++c) {
        if (cand_[c].length > bound_) continue;
        cand_[n_kept] = cand_[c];
        std::copy_n(classes_.begin() + c * W_, W_, classes_.begin() + n_kept * W_);
        remap[c] = static_cast<int>(n_kept++);
      }
      cand_.resize(n_kept);
      classes_.resize(n_kept * W_);
      by_class_.clear();
      for (size_t c = 0; c < cand_.size(); ++c)
        by_class_.emplace(key(classes_.data() + c * W_), static_cast<int>(c));
      for (int& k : kept) k = remap[k];
    }
    return kept;
  }

  // The greedy basis without a rank: its size is the rank the candidates span.
  std::vector<int> greedy_basis(int rank) const { return greedy(cand_, classes_, W_, rank); }

 private:
  // One root's tree: per non-zero class it closes, its shortest cycle within the bound.
  struct Found {
    std::vector<Candidate> cand;
    std::vector<Word> classes;
  };

  std::string key(const Word* cls) const {
    return std::string(reinterpret_cast<const char*>(cls), W_ * sizeof(Word));
  }

  void run_root(Dijkstra& dj, int root, double radius, Found& f) const {
    std::unordered_map<std::string, int> index;
    std::vector<Word> cls(W_);
    dj.run(root, radius, ann_, [&](int u, int w, int e, double length) {
      const Word* pu = dj.pa(u);
      const Word* pw = dj.pa(w);
      const Word* ae = ann_ + size_t(e) * W_;
      bool zero = true;
      for (int k = 0; k < W_; ++k) {
        cls[k] = pu[k] ^ pw[k] ^ ae[k];
        zero = zero && !cls[k];
      }
      if (zero) return;
      // The cycle proper: the two tree paths meet at their lowest common vertex, above which they
      // cancel. Its length is the candidate's (the same class, and never longer than the Horton
      // candidate): short loops far from the root get short lengths, hence tight bounds.
      length -= 2.0 * dj.dist(dj.common_ancestor(u, w));
      if (length > bound_) return;
      const Candidate fresh{length, root, e};
      const auto [it, added] = index.emplace(key(cls.data()), static_cast<int>(f.cand.size()));
      if (added) {
        f.cand.push_back(fresh);
        f.classes.insert(f.classes.end(), cls.begin(), cls.end());
      } else if (before(fresh, f.cand[it->second])) {
        f.cand[it->second] = fresh;
      }
    });
  }

  const Graph& g_;
  const Word* ann_;
  int W_;
  HomologyBasis& out_;
  int threads_ = 1;
  std::vector<std::unique_ptr<Dijkstra>> workers_;
  std::vector<char> rooted_;
  std::vector<Candidate> cand_;
  std::vector<Word> classes_;
  std::unordered_map<std::string, int> by_class_;
  double bound_ = kInf;  // candidates longer than the worst loop of a full basis are useless
};

// The fast path: one root per component with loops, unbounded (its candidates span that
// component's H1, so the greedy then has a full basis and the bound), then levels. After all
// roots on the edges whose annotation is outside V (the span of the loops certified so far) have
// run with radius rho, every basis loop of length <= 2 rho is found: such a loop's class is outside
// V, so one of its edges is, and a root on it sees the whole loop within half its length. The
// greedy's loops up to 2 rho are then certified. Returns the rank (0: no loop persists).
int search_by_levels(CandidateSearch& search, const SimplicialComplex& complex, const Graph& g,
                     const Word* ann, int W, const std::vector<int>& component,
                     const std::vector<int>& support, int rank) {
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
  search.collect(first_roots, kInf);
  if (rank < 0)
    rank = static_cast<int>(search.greedy_basis(std::numeric_limits<int>::max()).size());
  if (rank == 0) return 0;
  const std::vector<Candidate>& cand = search.candidates();
  Span certified(W);
  int n_certified = 0;
  while (true) {
    const std::vector<int> kept = search.basis(rank);
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
    search.collect(roots, level / 2);
    const std::vector<int> now = search.basis(rank);
    for (int k = n_certified; k < rank; ++k) {
      if (cand[now[k]].length > level) break;
      certified.insert(std::vector<Word>(search.class_of(now[k]), search.class_of(now[k]) + W));
      ++n_certified;
    }
  }
  return rank;
}

// A candidate's loop: the two tree paths from its root, joined at their last common vertex, and
// closed by its edge. `mark` (per vertex) must hold no `id` yet.
BasisCycle rebuild_cycle(const SimplicialComplex& complex, Dijkstra& dj, const Candidate& c, int id,
                         std::vector<int>& mark) {
  const int u = complex.edges[c.edge][0], w = complex.edges[c.edge][1];
  dj.run(
      c.root, kInf, nullptr, [](int, int, int, double) {}, u, w);
  std::vector<int> up_u, up_w;
  for (int v = u; v >= 0; v = dj.parent_vertex(v)) {
    up_u.push_back(v);
    mark[v] = id;
  }
  int lca = w;
  while (mark[lca] != id) {
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
  return cyc;
}

}  // namespace

void shortest_cycles(const SimplicialComplex& complex, const Graph& g, const Word* ann, int W,
                     const std::vector<int>& component, int rank, const HomologyOptions& options,
                     HomologyBasis& out) {
  const int m = static_cast<int>(complex.edges.size());
  std::vector<int> support;
  for (int e = 0; e < m; ++e)
    if (!is_zero(ann + size_t(e) * W, W)) support.push_back(e);
  out.support_edges = static_cast<int>(support.size());

  CandidateSearch search(g, ann, W, options, out);
  if (!options.fast) {
    std::vector<int> all(g.n);
    std::iota(all.begin(), all.end(), 0);
    search.collect(all, kInf);
    // Without a given rank, the candidates of full trees span the image: their greedy's size.
    if (rank < 0)
      rank = static_cast<int>(search.greedy_basis(std::numeric_limits<int>::max()).size());
  } else {
    rank = search_by_levels(search, complex, g, ann, W, component, support, rank);
  }
  if (rank == 0) return;
  const std::vector<int> kept = search.greedy_basis(rank);
  if (static_cast<int>(kept.size()) != rank)
    throw std::logic_error("shortest basis: the candidates do not span H1");
  std::vector<int> mark(g.n, -1);
  for (size_t idx = 0; idx < kept.size(); ++idx)
    out.cycles.push_back(rebuild_cycle(complex, search.dijkstra(), search.candidates()[kept[idx]],
                                       static_cast<int>(idx), mark));
  std::stable_sort(out.cycles.begin(), out.cycles.end(),
                   [](const BasisCycle& x, const BasisCycle& y) { return x.length < y.length; });
}

}  // namespace claspplan::perception::homology_detail
