#include "robots/mesh_resources.hpp"

#include <algorithm>
#include <cctype>
#include <cstdlib>
#include <filesystem>
#include <optional>
#include <vector>

#include <assimp/Importer.hpp>
#include <assimp/config.h>
#include <assimp/postprocess.h>
#include <assimp/scene.h>

#include "core/file_io.hpp"
#include "core/input_error.hpp"

namespace claspplan::robots {
namespace {

namespace fs = std::filesystem;

bool is_file(const fs::path& p) {
  std::error_code ec;
  return fs::is_regular_file(p, ec);
}

bool is_dir(const fs::path& p) {
  std::error_code ec;
  return fs::is_directory(p, ec);
}

std::vector<fs::path> env_folders(const char* variable) {
  std::vector<fs::path> out;
  const char* value = std::getenv(variable);
  if (!value) return out;
  std::string text = value;
  std::size_t start = 0;
  while (start <= text.size()) {
    const std::size_t end = std::min(text.find(':', start), text.size());
    if (end > start) out.emplace_back(text.substr(start, end - start));
    start = end + 1;
  }
  return out;
}

// A folder named `name` up to `depth` levels below `root`, the first by path (deterministic).
std::optional<fs::path> find_below(const fs::path& root, const std::string& name, int depth) {
  if (depth == 0 || !is_dir(root)) return std::nullopt;
  std::vector<fs::path> children;
  std::error_code ec;
  for (fs::directory_iterator it(root, ec), end; !ec && it != end; it.increment(ec))
    if (it->is_directory(ec)) children.push_back(it->path());
  std::sort(children.begin(), children.end());
  for (const auto& c : children)
    if (c.filename() == name) return c;
  for (const auto& c : children)
    if (auto found = find_below(c, name, depth - 1)) return found;
  return std::nullopt;
}

std::optional<fs::path> in_package_folder(const fs::path& dir, const std::string& package,
                                          const std::string& rest) {
  if (dir.filename() == package && is_file(dir / rest)) return dir / rest;
  if (is_file(dir / package / rest)) return dir / package / rest;
  return std::nullopt;
}

std::string package_path(const std::string& uri, const std::string& urdf_file) {
  // Some public URDFs write package:///PACKAGE/PATH (Talos' in example-robot-data); the extra
  // slash names no package, so it is skipped.
  std::string body = uri.substr(std::string("package://").size());
  body.erase(0, std::min(body.find_first_not_of('/'), body.size()));
  const std::size_t slash = body.find('/');
  if (slash == std::string::npos || slash == 0 || slash + 1 == body.size())
    throw InputError("mesh '" + uri + "': expected package://PACKAGE/PATH");
  const std::string package = body.substr(0, slash), rest = body.substr(slash + 1);
  for (const char* variable : {"CLASPPLAN_PACKAGE_PATH", "ROS_PACKAGE_PATH"}) {
    for (const fs::path& root : env_folders(variable)) {
      if (auto p = in_package_folder(root, package, rest)) return p->string();
      if (auto dir = find_below(root, package, 3))
        if (is_file(*dir / rest)) return (*dir / rest).string();
    }
  }
  fs::path dir = fs::absolute(fs::path(urdf_file).parent_path());
  for (;;) {
    if (auto p = in_package_folder(dir, package, rest)) return p->string();
    if (!dir.has_parent_path() || dir.parent_path() == dir) break;
    dir = dir.parent_path();
  }
  throw InputError("mesh '" + uri + "' not found: no folder '" + package + "' holding '" + rest +
                   "' in CLASPPLAN_PACKAGE_PATH, ROS_PACKAGE_PATH, or the URDF's folder and those "
                   "above it");
}

std::string lower_extension(const std::string& path) {
  std::string e = fs::path(path).extension().string();
  std::transform(e.begin(), e.end(), e.begin(), [](unsigned char c) { return std::tolower(c); });
  return e;
}

// Every mesh of the node's subtree, with the node transforms applied.
void collect(const aiScene& scene, const aiNode& node, const aiMatrix4x4& parent,
             TriangleMesh& out) {
  const aiMatrix4x4 tf = parent * node.mTransformation;
  for (unsigned m = 0; m < node.mNumMeshes; ++m) {
    const aiMesh& mesh = *scene.mMeshes[node.mMeshes[m]];
    const int base = static_cast<int>(out.vertices.size());
    for (unsigned v = 0; v < mesh.mNumVertices; ++v) {
      const aiVector3D p = tf * mesh.mVertices[v];
      out.vertices.emplace_back(p.x, p.y, p.z);
    }
    for (unsigned f = 0; f < mesh.mNumFaces; ++f) {
      const aiFace& face = mesh.mFaces[f];
      if (face.mNumIndices != 3) continue;  // points and lines left by triangulation
      out.triangles.emplace_back(base + static_cast<int>(face.mIndices[0]),
                                 base + static_cast<int>(face.mIndices[1]),
                                 base + static_cast<int>(face.mIndices[2]));
    }
  }
  for (unsigned c = 0; c < node.mNumChildren; ++c) collect(scene, *node.mChildren[c], tf, out);
}

TriangleMesh read_with_assimp(const std::string& path) {
  // Checked like our own readers' inputs: a file that claims no size or a huge one (/proc's) is
  // not read.
  constexpr std::uintmax_t kMaxBytes = std::uintmax_t(1) << 30;
  std::error_code ec;
  const std::uintmax_t bytes = fs::file_size(path, ec);
  if (ec || bytes == 0 || bytes > kMaxBytes)
    throw InputError(path + ": not a mesh file of 1 byte to 1 GiB");
  Assimp::Importer importer;
  // ROS reads COLLADA meshes in the link's frame: Assimp would turn a Z_UP file to Y up.
  importer.SetPropertyBool(AI_CONFIG_IMPORT_COLLADA_IGNORE_UP_DIRECTION, true);
  const aiScene* scene = importer.ReadFile(
      path, aiProcess_Triangulate | aiProcess_JoinIdenticalVertices | aiProcess_SortByPType);
  if (!scene || !scene->mRootNode)
    throw InputError(path + ": not a readable mesh: " + one_line(importer.GetErrorString()));
  TriangleMesh mesh;
  collect(*scene, *scene->mRootNode, aiMatrix4x4(), mesh);
  if (mesh.triangles.empty()) throw InputError(path + ": the mesh has no triangles");
  as_input_error([&] { validate_mesh(mesh, path); });
  return mesh;
}

}  // namespace

std::string resolve_mesh_uri(const std::string& uri, const std::string& urdf_file) {
  if (uri.empty()) throw InputError("mesh filename is empty");
  if (uri.rfind("package://", 0) == 0) return package_path(uri, urdf_file);
  std::string path = uri;
  if (uri.rfind("file://", 0) == 0) {
    path = uri.substr(std::string("file://").size());
  } else if (uri.find("://") != std::string::npos) {
    throw InputError("mesh '" + uri + "': only package://, file:// and file paths are read");
  }
  fs::path p(path);
  if (p.is_relative()) p = fs::path(urdf_file).parent_path() / p;
  if (!is_file(p)) throw InputError("mesh '" + uri + "' not found (looked for " + p.string() + ")");
  return p.string();
}

TriangleMesh read_mesh_resource(const std::string& path) {
  const std::string ext = lower_extension(path);
  if (ext == ".stl" || ext == ".obj" || ext == ".ply" || ext == ".off") {
    GeometryFile g = read_geometry(path);
    if (!g.is_mesh) throw InputError(path + ": a point cloud, not a mesh");
    return std::move(g.mesh);
  }
  return read_with_assimp(path);
}

}  // namespace claspplan::robots
