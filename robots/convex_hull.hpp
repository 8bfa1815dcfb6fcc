// The convex hull of a point set as a triangle mesh (Qhull): a robot's mesh link checked as its
// hull has a few hundred triangles instead of tens of thousands (hand description
// `collision.mesh_hulls`).
#pragma once

#include <string>
#include <vector>

#include <Eigen/Core>

#include "core/mesh.hpp"

namespace claspplan::robots {

/// The hull's triangles, facing out. Throws InputError naming `what` when the points span no
/// volume (fewer than 4 points, or all in a plane).
TriangleMesh convex_hull(const std::vector<Eigen::Vector3d>& points, const std::string& what);

}  // namespace claspplan::robots
