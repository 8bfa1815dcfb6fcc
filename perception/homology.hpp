// The exact shortest basis of H1(K_d) over Z2 (what the paper's ShortLoop tool approximates).
//
// 1. Annotations: a shortest-path spanning forest T of the 1-skeleton; the non-tree edges are
//    coordinates; triangle boundaries are reduced over Z2 (low-pivot reduction); beta1 = #non-tree
//    edges - rank. Each edge gets an annotation (a beta1-bit vector) such that the homology class
//    of any cycle is the XOR of its edges' annotations.
// 2. Candidates: for a root v, a Dijkstra tree; each non-tree edge uw closes the candidate cycle
//    path(v,u) + uw + path(w,v) of length d(u) + |uw| + d(w), with class pa[u] ^ pa[w] ^ ann(uw).
//    The union over all roots contains a shortest basis (Horton; Dey, Sun, Wang 2010).
// 3. Greedy: candidates by length, kept when independent of those kept, until beta1 loops.
// Fast path (default):
//  - each candidate is measured as the cycle it really is (the two tree paths cancel above their
//    lowest common vertex), and only the shortest candidate of each class is kept;
//  - roots: every non-null cycle contains an edge with a non-zero annotation, and a shortest basis
//    cycle is a candidate of the tree rooted at any of its vertices, so the roots are a vertex
//    cover of those support edges;
//  - the first root of each component runs in full and gives a basis (an upper bound per loop);
//  - levels: with V the span of the loops certified so far, only edges whose annotation lies
//    outside V need roots; each of them runs a Dijkstra bounded by half the level's loop length (a
//    basis cycle of length L has both ends of its closing edge within L/2 of a root on it); the
//    greedy's loops up to that length are then certified, V grows, and fewer roots are needed.
// The result has the same lengths as the all-roots greedy (tested on many random complexes).
#pragma once

#include <vector>

#include "perception/complex.hpp"

namespace claspplan::perception {

struct HomologyOptions {
  bool fast = true;      ///< limited roots + bounded Dijkstra (false: every vertex is a root)
  int max_beta1 = 1000;  ///< above this, throw std::invalid_argument (d too small for the points)
  int threads = 0;       ///< Dijkstra roots run on this many threads (0: all cores); same result
};

/// One basis cycle: a closed path of vertices (first vertex not repeated at the end).
struct BasisCycle {
  std::vector<int> vertices;
  std::vector<int> edges;  ///< edges[i] joins vertices[i] and vertices[i+1] (cyclically)
  double length = 0.0;
};

struct HomologyBasis {
  int beta1 = 0;
  std::vector<BasisCycle> cycles;  ///< shortest first
  int roots = 0;                   ///< Dijkstra roots used
  int support_edges = 0;           ///< edges with a non-zero annotation
};

/// beta1 only (step 1), cheap.
int betti_1(const SimplicialComplex& complex);

/// For each cycle (a closed vertex path, first vertex not repeated; consecutive vertices must be
/// joined by edges of `larger`), whether it bounds in `larger`: its class there is zero. With
/// `larger` = K_d' for d' > d this tells which loops of K_d persist (a hole narrower than about
/// d' fills in). Throws std::invalid_argument when a cycle uses an edge `larger` lacks.
std::vector<bool> bounds_in(const SimplicialComplex& larger,
                            const std::vector<std::vector<int>>& cycles);

/// The shortest H1 basis (steps 1-3).
HomologyBasis shortest_homology_basis(const SimplicialComplex& complex,
                                      const HomologyOptions& options = {});

/// The loops of `complex` (K_d) that persist into `larger` (K_d', d' > d, with every edge of K_d):
/// the shortest cycles of K_d whose classes in K_d' are independent and non-zero, a shortest basis
/// of the image of H1(K_d) in H1(K_d'). beta1 is K_d's; cycles.size() is the image's rank, and
/// beta1 minus it the loops that fill in. Steps 2-3 run with K_d' annotations, whose support is
/// only the edges across persistent holes, so far fewer roots than for all of K_d's loops.
HomologyBasis persistent_homology_basis(const SimplicialComplex& complex,
                                        const SimplicialComplex& larger,
                                        const HomologyOptions& options = {});

}  // namespace claspplan::perception
