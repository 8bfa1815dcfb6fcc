// Readers and writers for point clouds and meshes. All parsers are our own (PCL 1.13's readers
// crash or hang on bad files): headers, declared counts and sizes are checked against the file
// before anything is allocated, and every problem is a one-line InputError naming the
// file.
//
//   .pcd  clouds: DATA ascii, binary, binary_compressed; fields x y z of type F (4 or 8 bytes),
//   other
//         fields skipped. NaN points are rejected, except in organized clouds (HEIGHT > 1), where
//         PCL marks missing readings with NaN: those points are skipped.
//   .ply  format ascii 1.0, binary_little_endian 1.0 or binary_big_endian 1.0; element vertex with
//         x y z (any scalar type), optional element face (list of vertex indices): a mesh if it has
//         faces, else a cloud. Other elements and properties are skipped.
//   .xyz  one point per line, the first three numbers `x y z` (further columns ignored), `#`
//   comments. .obj  `v x y z` and `f i j k ...` (i, i/t, i/t/n, i//n, negative indices), polygons
//   fanned. .stl  binary (84 + 50 n bytes) or ascii (`solid ... facet ... vertex x y z`); equal
//   vertices
//         merged.
//   .off  `OFF`, `nv nf ne`, vertices, faces `n i1 ... in`, `#` comments.
// Limits: at most 50 million points or faces per file.
#pragma once

#include <string>

#include "core/input_error.hpp"
#include "core/mesh.hpp"

namespace claspplan {

/// What a geometry file holds: a cloud, or a mesh (the cloud is empty then).
struct GeometryFile {
  PointCloud cloud;
  TriangleMesh mesh;
  bool is_mesh = false;
};

/// Reads any supported file by its extension (case-insensitive). Throws InputError for
/// unknown extensions, unreadable, empty, truncated or malformed files and NaN/Inf coordinates.
GeometryFile read_geometry(const std::string& path);

PointCloud read_pcd(const std::string& path);
PointCloud read_xyz(const std::string& path);
GeometryFile read_ply(const std::string& path);
TriangleMesh read_obj(const std::string& path);
TriangleMesh read_stl(const std::string& path);
TriangleMesh read_off(const std::string& path);

/// The same readers on a file's contents held in memory: `name` stands for the path in messages
/// (and gives parse_geometry the format by its extension). Same checks, same errors.
GeometryFile parse_geometry(const std::string& data, const std::string& name);
PointCloud parse_pcd(const std::string& data, const std::string& name);
PointCloud parse_xyz(const std::string& data, const std::string& name);
GeometryFile parse_ply(const std::string& data, const std::string& name);
TriangleMesh parse_obj(const std::string& data, const std::string& name);
TriangleMesh parse_stl(const std::string& data, const std::string& name);
TriangleMesh parse_off(const std::string& data, const std::string& name);

/// Writers (full double precision in text formats; binary ones store float32 for .pcd/.stl and
/// float64 for .ply). Throw std::runtime_error when the file cannot be written.
void write_pcd(const PointCloud& cloud, const std::string& path, bool binary = true);
void write_xyz(const PointCloud& cloud, const std::string& path);
void write_ply(const PointCloud& cloud, const std::string& path, bool binary = true);
void write_ply(const TriangleMesh& mesh, const std::string& path, bool binary = true);
void write_obj(const TriangleMesh& mesh, const std::string& path);
void write_stl(const TriangleMesh& mesh, const std::string& path, bool binary = true);
void write_off(const TriangleMesh& mesh, const std::string& path);

}  // namespace claspplan
