// The five objects of the paper's experiments (Sec. V, Fig. 3) as procedural solids at real
// size: Purse (1 loop), Bag (1), Travel Bag (1), Lawn Mower (2), Chair (7). Each stands on z = 0,
// centred in x and y, its front towards -x; straps and handles are 1-3 cm thick.
#pragma once

#include <string>
#include <vector>

#include <Eigen/Core>

#include "examples/objects.hpp"

namespace claspplan::objects {

/// A paper object: its mesh, how many loops the paper counts on it, the loop the paper clasps
/// (a point at its hole's centre) and a loop below the chair's seat (the obstructed one).
struct PaperObject {
  std::string name;  ///< purse, bag, travelbag, lawnmower, chair
  TriangleMesh mesh;
  int loops = 1;           ///< Fig. 3
  int targets = 9;         ///< clasp targets on the clasped loop (Sec. V)
  Eigen::Vector3d clasp;   ///< centre of the clasped loop's hole, object frame
  Eigen::Vector3d hidden;  ///< chair: the front loop under the seat; others: = clasp
};

/// The object names, in the paper's order.
const std::vector<std::string>& paper_object_names();

/// Builds the named object (meshing takes about a second); throws std::invalid_argument for an
/// unknown name.
PaperObject paper_object(const std::string& name);

}  // namespace claspplan::objects
