#include <array>
#include <cctype>
#include <cstdint>
#include <cstring>
#include <map>

#include "core/file_io.hpp"
#include "core/file_io_detail.hpp"

namespace claspplan {

using namespace file_io_detail;

// ---------------------------------------------------------------------------------------------
// OBJ, OFF, STL

TriangleMesh read_obj(const std::string& path) {
  return parse_obj(read_all(path), path);
}

TriangleMesh parse_obj(const std::string& data, const std::string& path) {
  require_data(path, data);
  Lines lines(data);
  std::string line;
  TriangleMesh mesh;
  std::vector<long long> poly;
  long long faces = 0;
  while (lines.next(line)) {
    strip_comment(line);
    const auto tok = split(line);
    if (tok.empty()) continue;
    const std::string where = "line " + std::to_string(lines.number());
    if (tok[0] == "v") {
      Eigen::Vector3d p;
      if (tok.size() < 4) fail(path, where + ": a vertex needs x y z");
      for (int a = 0; a < 3; ++a)
        if (!parse_double(tok[a + 1], p[a]))
          fail(path, where + ": '" + tok[a + 1] + "' is not a number");
      check_point(path, p, static_cast<long long>(mesh.vertices.size()));
      mesh.vertices.push_back(p);
    } else if (tok[0] == "f") {
      poly.clear();
      for (size_t k = 1; k < tok.size(); ++k) {
        long long idx;
        if (!parse_integer(tok[k].substr(0, tok[k].find('/')), idx) || idx == 0)
          fail(path, where + ": bad face index '" + tok[k] + "'");
        poly.push_back(idx > 0 ? idx - 1 : static_cast<long long>(mesh.vertices.size()) + idx);
      }
      fan(mesh.triangles, poly, static_cast<long long>(mesh.vertices.size()), path, faces++);
    } else if (tok[0].size() > 8 || !std::isalpha(static_cast<unsigned char>(tok[0][0]))) {
      fail(path, where + ": not an OBJ statement ('" + tok[0].substr(0, 20) + "')");
    }
    if (static_cast<long long>(mesh.vertices.size() + mesh.triangles.size()) > kMaxCount)
      fail(path, "more than 50 million vertices and faces");
  }
  if (mesh.vertices.empty()) fail(path, "no vertices ('v x y z' lines)");
  return mesh;
}

TriangleMesh read_off(const std::string& path) {
  return parse_off(read_all(path), path);
}

TriangleMesh parse_off(const std::string& data, const std::string& path) {
  require_data(path, data);
  Lines lines(data);
  std::string line;
  std::vector<std::string> header;
  auto next_tokens = [&](std::vector<std::string>& tok) {
    while (lines.next(line)) {
      strip_comment(line);
      tok = split(line);
      if (!tok.empty()) return true;
    }
    return false;
  };
  std::vector<std::string> tok;
  if (!next_tokens(tok) || tok[0] != "OFF")
    fail(path, "not an OFF file (the first word must be 'OFF')");
  tok.erase(tok.begin());
  if (tok.empty() && !next_tokens(tok)) fail(path, "truncated: no counts line");
  long long nv, nf;
  if (tok.size() < 2 || !parse_integer(tok[0], nv) || !parse_integer(tok[1], nf))
    fail(path, "the counts line must be 'vertices faces edges'");
  if (nv <= 0 || nf < 0 || nv > kMaxCount || nf > kMaxCount)
    fail(path,
         "absurd counts: " + std::to_string(nv) + " vertices, " + std::to_string(nf) + " faces");
  if (nv * 6 + nf * 8 > static_cast<long long>(data.size()) * 2 + 64)
    fail(path, "truncated or absurd counts: " + std::to_string(nv) + " vertices and " +
                   std::to_string(nf) + " faces cannot fit in " + std::to_string(data.size()) +
                   " bytes");
  TriangleMesh mesh;
  mesh.vertices.reserve(nv);
  for (long long i = 0; i < nv; ++i) {
    if (!next_tokens(tok))
      fail(path, "truncated: " + std::to_string(i) + " of " + std::to_string(nv) + " vertices");
    Eigen::Vector3d p;
    if (tok.size() < 3) fail(path, "vertex " + std::to_string(i) + " needs x y z");
    for (int a = 0; a < 3; ++a)
      if (!parse_double(tok[a], p[a])) fail(path, "'" + tok[a] + "' is not a number");
    check_point(path, p, i);
    mesh.vertices.push_back(p);
  }
  std::vector<long long> poly;
  for (long long i = 0; i < nf; ++i) {
    if (!next_tokens(tok))
      fail(path, "truncated: " + std::to_string(i) + " of " + std::to_string(nf) + " faces");
    long long n;
    if (!parse_integer(tok[0], n) || n < 3 || n >= static_cast<long long>(tok.size()))
      fail(path, "face " + std::to_string(i) + " is malformed");
    poly.clear();
    for (long long k = 0; k < n; ++k) {
      long long v;
      if (!parse_integer(tok[k + 1], v)) fail(path, "face " + std::to_string(i) + ": bad index");
      poly.push_back(v);
    }
    fan(mesh.triangles, poly, nv, path, i);
  }
  if (mesh.triangles.empty()) fail(path, "no faces");
  return mesh;
}

TriangleMesh read_stl(const std::string& path) {
  return parse_stl(read_all(path), path);
}

TriangleMesh parse_stl(const std::string& data, const std::string& path) {
  require_data(path, data);
  std::vector<Eigen::Vector3d> corners;
  bool binary = false;
  if (data.size() >= 84) {
    std::uint32_t n;
    std::memcpy(&n, data.data() + 80, 4);
    binary = 84 + 50ull * n == data.size();
  }
  size_t start = 0;
  while (start < data.size() && is_space(data[start])) ++start;
  const bool ascii = !binary && data.compare(start, 5, "solid") == 0;
  if (binary) {
    std::uint32_t n;
    std::memcpy(&n, data.data() + 80, 4);
    if (n == 0) fail(path, "binary STL with no triangles");
    if (n > kMaxCount) fail(path, "absurd triangle count " + std::to_string(n));
    corners.reserve(3ull * n);
    for (std::uint32_t t = 0; t < n; ++t) {
      const char* rec = data.data() + 84 + 50ull * t + 12;
      for (int k = 0; k < 3; ++k) {
        float f[3];
        std::memcpy(f, rec + 12 * k, 12);
        const Eigen::Vector3d p(f[0], f[1], f[2]);
        check_point(path, p, 3ll * t + k);
        corners.push_back(p);
      }
    }
  } else if (ascii) {
    Tokens tokens(data, start);
    std::string tok;
    int in_loop = -1;
    bool open_facet = false, ended = false;
    while (tokens.next(tok)) {
      if (tok == "facet") {
        open_facet = true;
      } else if (tok == "loop") {
        // Every loop closed before the next: the corners come in threes.
        if (in_loop >= 0) fail(path, "'outer loop' inside a loop (no 'endloop')");
        in_loop = 0;
      } else if (tok == "vertex") {
        if (in_loop < 0) fail(path, "'vertex' outside an 'outer loop'");
        Eigen::Vector3d p;
        for (int a = 0; a < 3; ++a) {
          if (!tokens.next(tok) || !parse_double(tok, p[a]))
            fail(path, "truncated or malformed 'vertex' line");
        }
        check_point(path, p, static_cast<long long>(corners.size()));
        corners.push_back(p);
        ++in_loop;
      } else if (tok == "endloop") {
        if (in_loop != 3) fail(path, "a facet loop must have exactly 3 vertices");
        in_loop = -1;
      } else if (tok == "endfacet") {
        open_facet = false;
      } else if (tok == "endsolid") {
        ended = true;
        break;
      }
      if (static_cast<long long>(corners.size()) > 3 * kMaxCount) fail(path, "too many facets");
    }
    if (open_facet || in_loop >= 0 || !ended) fail(path, "truncated ASCII STL (no endsolid)");
    if (corners.empty()) fail(path, "ASCII STL with no facets");
  } else {
    if (data.size() >= 84)
      fail(path,
           "not an STL file: binary size does not match its triangle count (truncated?) and "
           "it does not start with 'solid'");
    fail(path, "not an STL file (too short for binary, no 'solid' header)");
  }
  TriangleMesh mesh;
  std::map<std::array<double, 3>, int> index;
  for (size_t i = 0; i < corners.size(); i += 3) {
    Eigen::Vector3i t;
    for (int k = 0; k < 3; ++k) {
      const Eigen::Vector3d& p = corners[i + k];
      const auto [it, added] = index.emplace(std::array<double, 3>{p.x(), p.y(), p.z()},
                                             static_cast<int>(mesh.vertices.size()));
      if (added) mesh.vertices.push_back(p);
      t[k] = it->second;
    }
    mesh.triangles.push_back(t);
  }
  return mesh;
}

// ---------------------------------------------------------------------------------------------
// Writers

void write_obj(const TriangleMesh& mesh, const std::string& path) {
  auto out = open_out(path, false);
  out << "# claspplan mesh\n";
  for (const auto& p : mesh.vertices) out << "v " << p.x() << " " << p.y() << " " << p.z() << "\n";
  for (const auto& t : mesh.triangles)
    out << "f " << t[0] + 1 << " " << t[1] + 1 << " " << t[2] + 1 << "\n";
  finish(out, path);
}

void write_off(const TriangleMesh& mesh, const std::string& path) {
  auto out = open_out(path, false);
  out << "OFF\n" << mesh.vertices.size() << " " << mesh.triangles.size() << " 0\n";
  for (const auto& p : mesh.vertices) out << p.x() << " " << p.y() << " " << p.z() << "\n";
  for (const auto& t : mesh.triangles) out << "3 " << t[0] << " " << t[1] << " " << t[2] << "\n";
  finish(out, path);
}

void write_stl(const TriangleMesh& mesh, const std::string& path, bool binary) {
  const auto normals = triangle_normals(mesh);
  auto out = open_out(path, binary);
  if (binary) {
    std::string header(80, ' ');
    header.replace(0, 19, "claspplan binary STL");
    out.write(header.data(), 80);
    put(out, static_cast<std::uint32_t>(mesh.triangles.size()));
    for (size_t i = 0; i < mesh.triangles.size(); ++i) {
      for (int a = 0; a < 3; ++a) put(out, static_cast<float>(normals[i][a]));
      for (int k = 0; k < 3; ++k)
        for (int a = 0; a < 3; ++a)
          put(out, static_cast<float>(mesh.vertices[mesh.triangles[i][k]][a]));
      put(out, static_cast<std::uint16_t>(0));
    }
  } else {
    out << "solid claspplan\n";
    for (size_t i = 0; i < mesh.triangles.size(); ++i) {
      out << "facet normal " << normals[i].x() << " " << normals[i].y() << " " << normals[i].z()
          << "\n outer loop\n";
      for (int k = 0; k < 3; ++k) {
        const auto& p = mesh.vertices[mesh.triangles[i][k]];
        out << "  vertex " << p.x() << " " << p.y() << " " << p.z() << "\n";
      }
      out << " endloop\nendfacet\n";
    }
    out << "endsolid claspplan\n";
  }
  finish(out, path);
}

}  // namespace claspplan
