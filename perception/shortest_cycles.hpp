// Steps 2-3 of the shortest homology basis (perception/homology.cpp): candidate cycles from
// bounded Dijkstra trees, and the greedy choice of the shortest independent ones. Internal to
// perception; not installed.
#pragma once

#include <vector>

#include "perception/homology.hpp"
#include "perception/homology_graph.hpp"

namespace claspplan::perception::homology_detail {

/// Is the class (W words) zero?
inline bool is_zero(const Word* v, int W) {
  for (int w = 0; w < W; ++w)
    if (v[w]) return false;
  return true;
}

/// For any annotation `ann` (W words per edge) of the complex's edges: the shortest cycles whose
/// classes are independent and non-zero, `rank` of them (-1: as many as the candidates of one full
/// tree per component span), into out.cycles (shortest first); out.roots and out.support_edges.
void shortest_cycles(const SimplicialComplex& complex, const Graph& g, const Word* ann, int W,
                     const std::vector<int>& component, int rank, const HomologyOptions& options,
                     HomologyBasis& out);

}  // namespace claspplan::perception::homology_detail
