// read_geometry() and parse_geometry(): dispatch by extension. The readers and writers of each
// format family are in cloud_files.cpp (PCD, XYZ), ply_files.cpp (PLY clouds and meshes) and
// mesh_files.cpp (OBJ, OFF, STL); their shared helpers in file_io_detail.hpp.
#include "core/file_io.hpp"

#include <utility>

#include "core/file_io_detail.hpp"

namespace claspplan {

using namespace file_io_detail;

namespace {

// The lower-case extension of a supported geometry file; fails for any other.
std::string known_geometry_type(const std::string& path) {
  const std::string ext = extension(path);
  for (const char* known : {".pcd", ".xyz", ".ply", ".obj", ".stl", ".off"})
    if (ext == known) return ext;
  fail(path, "unknown file type '" + ext +
                 "' (expected .png with --camera, .pcd, .ply, .xyz, .obj, .stl or .off)");
}

}  // namespace

GeometryFile read_geometry(const std::string& path) {
  // The type first, so that an unknown extension is reported before the file is read.
  known_geometry_type(path);
  return parse_geometry(read_all(path), path);
}

GeometryFile parse_geometry(const std::string& data, const std::string& path) {
  const std::string ext = known_geometry_type(path);
  GeometryFile g;
  if (ext == ".pcd") {
    g.cloud = parse_pcd(data, path);
  } else if (ext == ".xyz") {
    g.cloud = parse_xyz(data, path);
  } else if (ext == ".ply") {
    g = parse_ply(data, path);
  } else {
    g.mesh = ext == ".obj"   ? parse_obj(data, path)
             : ext == ".stl" ? parse_stl(data, path)
                             : parse_off(data, path);
    g.is_mesh = !g.mesh.triangles.empty();
    if (!g.is_mesh) std::swap(g.cloud, g.mesh.vertices);  // an OBJ of vertices only: a cloud
  }
  if (g.is_mesh)
    validate_mesh(g.mesh, path);
  else
    validate_cloud(g.cloud, path);
  return g;
}

}  // namespace claspplan
