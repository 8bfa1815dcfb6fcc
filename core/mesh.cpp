#include "core/mesh.hpp"

#include <algorithm>
#include <cmath>
#include <map>
#include <random>
#include <stdexcept>

#include "core/input_error.hpp"
#include "core/random_draws.hpp"

namespace claspplan {

namespace {

constexpr double kMinArea = 1e-18;

double triangle_area(const TriangleMesh& m, const Eigen::Vector3i& t) {
  return 0.5 *
         (m.vertices[t[1]] - m.vertices[t[0]]).cross(m.vertices[t[2]] - m.vertices[t[0]]).norm();
}

}  // namespace

void validate_mesh(const TriangleMesh& mesh, const std::string& what) {
  if (mesh.vertices.empty()) throw InputError(what + ": the mesh has no vertices");
  if (mesh.triangles.empty()) throw InputError(what + ": the mesh has no faces");
  for (size_t i = 0; i < mesh.vertices.size(); ++i) {
    if (!mesh.vertices[i].allFinite())
      throw InputError(what + ": vertex " + std::to_string(i) +
                       " has a NaN or infinite coordinate");
  }
  const int n = static_cast<int>(mesh.vertices.size());
  for (size_t i = 0; i < mesh.triangles.size(); ++i) {
    for (int v : mesh.triangles[i]) {
      if (v < 0 || v >= n)
        throw InputError(what + ": face " + std::to_string(i) + " uses vertex " +
                         std::to_string(v) + " of " + std::to_string(n));
    }
  }
}

void validate_cloud(const PointCloud& cloud, const std::string& what) {
  if (cloud.empty()) throw InputError(what + ": no points");
  for (size_t i = 0; i < cloud.size(); ++i) {
    if (!cloud[i].allFinite())
      throw InputError(what + ": point " + std::to_string(i) + " has a NaN or infinite coordinate");
  }
}

double surface_area(const TriangleMesh& mesh) {
  double a = 0.0;
  for (const auto& t : mesh.triangles) a += triangle_area(mesh, t);
  return a;
}

int degenerate_triangle_count(const TriangleMesh& mesh) {
  int n = 0;
  for (const auto& t : mesh.triangles) n += triangle_area(mesh, t) < kMinArea;
  return n;
}

void append_mesh(TriangleMesh& a, const TriangleMesh& b) {
  const int offset = static_cast<int>(a.vertices.size());
  a.vertices.insert(a.vertices.end(), b.vertices.begin(), b.vertices.end());
  for (const auto& t : b.triangles)
    a.triangles.push_back({t[0] + offset, t[1] + offset, t[2] + offset});
}

TriangleMesh box_mesh(const Eigen::Vector3d& size) {
  TriangleMesh m;
  const Eigen::Vector3d h = size / 2.0;
  for (int i = 0; i < 8; ++i) {
    m.vertices.emplace_back((i & 1) ? h.x() : -h.x(), (i & 2) ? h.y() : -h.y(),
                            (i & 4) ? h.z() : -h.z());
  }
  const int faces[6][4] = {{0, 2, 3, 1}, {4, 5, 7, 6}, {0, 1, 5, 4},
                           {2, 6, 7, 3}, {0, 4, 6, 2}, {1, 3, 7, 5}};
  for (const auto& f : faces) {
    m.triangles.emplace_back(f[0], f[1], f[2]);
    m.triangles.emplace_back(f[0], f[2], f[3]);
  }
  return m;
}

TriangleMesh transformed(const TriangleMesh& mesh, const Eigen::Isometry3d& T) {
  TriangleMesh out = mesh;
  for (auto& v : out.vertices) v = T * v;
  return out;
}

Eigen::AlignedBox3d bounds(const TriangleMesh& mesh) {
  return bounds(mesh.vertices);
}

Eigen::AlignedBox3d bounds(const PointCloud& cloud) {
  Eigen::AlignedBox3d box;
  for (const auto& p : cloud) box.extend(p);
  return box;
}

PointCloud sample_surface(const TriangleMesh& mesh, int count, std::uint64_t seed) {
  if (count < 0) throw std::invalid_argument("sample_surface: negative point count");
  std::vector<double> cumulative;
  std::vector<int> index;
  double total = 0.0;
  for (size_t i = 0; i < mesh.triangles.size(); ++i) {
    const double a = triangle_area(mesh, mesh.triangles[i]);
    if (a < kMinArea) continue;  // zero-area triangles are skipped, not fatal
    total += a;
    cumulative.push_back(total);
    index.push_back(static_cast<int>(i));
  }
  if (cumulative.empty()) throw InputError("the mesh has no triangle of positive area to sample");
  std::mt19937_64 rng(seed);
  PointCloud out;
  out.reserve(count);
  for (int k = 0; k < count; ++k) {
    const double r = uniform01(rng()) * total;
    size_t j = std::upper_bound(cumulative.begin(), cumulative.end(), r) - cumulative.begin();
    j = std::min(j, cumulative.size() - 1);
    const auto& t = mesh.triangles[index[j]];
    double s = uniform01(rng());
    double u = uniform01(rng());
    if (s + u > 1.0) {  // fold the square onto the triangle: uniform by area
      s = 1.0 - s;
      u = 1.0 - u;
    }
    const Eigen::Vector3d& a = mesh.vertices[t[0]];
    out.push_back(a + s * (mesh.vertices[t[1]] - a) + u * (mesh.vertices[t[2]] - a));
  }
  return out;
}

std::vector<Eigen::Vector3d> triangle_normals(const TriangleMesh& mesh) {
  std::vector<Eigen::Vector3d> n;
  n.reserve(mesh.triangles.size());
  for (const auto& t : mesh.triangles) {
    const Eigen::Vector3d c = (mesh.vertices[t[1]] - mesh.vertices[t[0]])
                                  .cross(mesh.vertices[t[2]] - mesh.vertices[t[0]]);
    const double len = c.norm();
    n.push_back(len > 1e-300 ? Eigen::Vector3d(c / len) : Eigen::Vector3d::Zero());
  }
  return n;
}

namespace {
std::map<std::pair<int, int>, int> edge_use(const TriangleMesh& mesh) {
  std::map<std::pair<int, int>, int> use;
  for (const auto& t : mesh.triangles) {
    for (int k = 0; k < 3; ++k) {
      int a = t[k], b = t[(k + 1) % 3];
      if (a > b) std::swap(a, b);
      ++use[{a, b}];
    }
  }
  return use;
}
}  // namespace

bool is_watertight(const TriangleMesh& mesh) {
  if (mesh.triangles.empty()) return false;
  for (const auto& [e, n] : edge_use(mesh))
    if (n != 2) return false;
  return true;
}

int euler_characteristic(const TriangleMesh& mesh) {
  std::vector<char> used(mesh.vertices.size(), 0);
  for (const auto& t : mesh.triangles)
    for (int v : t) used[v] = 1;
  const int v = static_cast<int>(std::count(used.begin(), used.end(), 1));
  return v - static_cast<int>(edge_use(mesh).size()) + static_cast<int>(mesh.triangles.size());
}

}  // namespace claspplan
