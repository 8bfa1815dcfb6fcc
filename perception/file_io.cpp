// read_geometry(): dispatch by extension. The readers and writers of each format family are in
// cloud_files.cpp (PCD, XYZ), ply_files.cpp (PLY clouds and meshes) and mesh_files.cpp (OBJ, OFF,
// STL); their shared helpers in file_io_detail.hpp.
#include "perception/file_io.hpp"

#include <utility>

#include "perception/file_io_detail.hpp"

namespace claspplan::perception {

using namespace file_io_detail;

GeometryFile read_geometry(const std::string& path) {
  const std::string ext = extension(path);
  GeometryFile g;
  if (ext == ".pcd") {
    g.cloud = read_pcd(path);
  } else if (ext == ".xyz") {
    g.cloud = read_xyz(path);
  } else if (ext == ".ply") {
    g = read_ply(path);
  } else if (ext == ".obj" || ext == ".stl" || ext == ".off") {
    g.mesh = ext == ".obj" ? read_obj(path) : ext == ".stl" ? read_stl(path) : read_off(path);
    g.is_mesh = !g.mesh.triangles.empty();
    if (!g.is_mesh) std::swap(g.cloud, g.mesh.vertices);  // an OBJ of vertices only: a cloud
  } else {
    fail(path, "unknown file type '" + ext +
                   "' (expected .png with --camera, .pcd, .ply, .xyz, .obj, .stl or .off)");
  }
  if (g.is_mesh)
    validate_mesh(g.mesh, path);
  else
    validate_cloud(g.cloud, path);
  return g;
}

}  // namespace claspplan::perception
