// The mesh files a URDF's <mesh filename="..."> names: where they are (package://, file:// and
// relative URIs resolved through a search path) and their triangles.
//
// Search path for package://NAME/PATH, in this order (the first existing file wins):
//   1. each folder of the environment variable CLASPPLAN_PACKAGE_PATH, then of ROS_PACKAGE_PATH
//      (colon-separated): DIR/PATH when DIR's own name is NAME, DIR/NAME/PATH, or a folder named
//      NAME up to three levels below DIR (a workspace's src/<group>/NAME), the first by name;
//   2. the URDF's folder and every folder above it: DIR/PATH when DIR is named NAME, DIR/NAME/PATH.
// file://PATH is PATH; any other filename is a path, relative to the URDF's folder.
#pragma once

#include <string>

#include "core/mesh.hpp"

namespace claspplan::robots {

/// The file a URDF mesh filename names (see the search path above). Throws InputError naming
/// the URI and where it looked when no file is found, and for URI schemes other than package://
/// and file:// (http:// meshes are not fetched).
std::string resolve_mesh_uri(const std::string& uri, const std::string& urdf_file);

/// A mesh file's triangles, in the file's units and frame: .stl, .obj, .ply and .off by
/// claspplan's own readers, .dae (COLLADA) and other formats by Assimp (its <unit> applied, its
/// up axis not: URDF meshes are in the link's frame, as ROS tools read them). Throws InputError
/// for unreadable, empty or malformed files.
TriangleMesh read_mesh_resource(const std::string& path);

}  // namespace claspplan::robots
