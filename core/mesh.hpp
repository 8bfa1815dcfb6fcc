// Point clouds and triangle meshes, and sampling points on a mesh's surface (uniformly by area, on
// the whole surface or only where cameras see it).
#pragma once

#include <array>
#include <cstdint>
#include <string>
#include <vector>

#include <Eigen/Core>
#include <Eigen/Geometry>

namespace claspplan {

/// A point cloud in metres (world frame unless said otherwise).
using PointCloud = std::vector<Eigen::Vector3d>;

/// An indexed triangle mesh (counter-clockwise seen from outside for closed meshes).
/// The one mesh type: object surfaces, collision models and drawn shapes alike.
struct TriangleMesh {
  std::vector<Eigen::Vector3d> vertices;
  std::vector<Eigen::Vector3i> triangles;  ///< vertex indices
};

/// Throws std::invalid_argument("<what>: ...") for an empty mesh, out-of-range indices or
/// non-finite vertices. `what` names the source (a file name) in the message.
void validate_mesh(const TriangleMesh& mesh, const std::string& what);

/// Throws std::invalid_argument for an empty cloud or NaN/Inf coordinates.
void validate_cloud(const PointCloud& cloud, const std::string& what);

/// Total area; zero-area triangles contribute nothing.
double surface_area(const TriangleMesh& mesh);

/// Number of triangles with area below 1e-18 m² (skipped by sampling and rendering).
int degenerate_triangle_count(const TriangleMesh& mesh);

/// Appends `b` to `a` (indices shifted).
void append_mesh(TriangleMesh& a, const TriangleMesh& b);

/// A box of edge lengths `size` centred at the origin, its edges along the axes: 12 triangles,
/// facing outwards.
TriangleMesh box_mesh(const Eigen::Vector3d& size);

/// Applies a rigid transform to every vertex.
TriangleMesh transformed(const TriangleMesh& mesh, const Eigen::Isometry3d& T);

/// Axis-aligned bounds of the vertices (empty box for an empty mesh).
Eigen::AlignedBox3d bounds(const TriangleMesh& mesh);
Eigen::AlignedBox3d bounds(const PointCloud& cloud);

/// `count` points uniformly distributed by area over the whole surface (seeded, deterministic).
/// Throws std::invalid_argument when the mesh has no triangle of positive area.
PointCloud sample_surface(const TriangleMesh& mesh, int count, std::uint64_t seed);

/// Per-triangle unit normals (zero for degenerate triangles).
std::vector<Eigen::Vector3d> triangle_normals(const TriangleMesh& mesh);

/// Edge-manifold and closed: every undirected edge is shared by exactly two triangles.
bool is_watertight(const TriangleMesh& mesh);

/// V - E + F of the mesh (2 - 2g for a closed orientable surface of genus g).
int euler_characteristic(const TriangleMesh& mesh);

}  // namespace claspplan
