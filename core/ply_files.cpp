#include <cmath>
#include <cstdint>
#include <cstring>
#include <map>
#include <utility>

#include "core/file_io.hpp"
#include "core/file_io_detail.hpp"

namespace claspplan {

using namespace file_io_detail;

// ---------------------------------------------------------------------------------------------
// PLY

namespace {

struct PlyProperty {
  std::string name;
  int type = 0;     // byte size of the scalar (or of the list items)
  char kind = 'f';  // 'f' float, 'i' signed, 'u' unsigned
  bool list = false;
  int count_size = 0;  // list count
  char count_kind = 'u';
};

struct PlyElement {
  std::string name;
  long long count = 0;
  std::vector<PlyProperty> props;
};

bool ply_type(const std::string& t, int& size, char& kind) {
  static const std::map<std::string, std::pair<int, char>> kTypes = {
      {"char", {1, 'i'}},  {"int8", {1, 'i'}},    {"uchar", {1, 'u'}},  {"uint8", {1, 'u'}},
      {"short", {2, 'i'}}, {"int16", {2, 'i'}},   {"ushort", {2, 'u'}}, {"uint16", {2, 'u'}},
      {"int", {4, 'i'}},   {"int32", {4, 'i'}},   {"uint", {4, 'u'}},   {"uint32", {4, 'u'}},
      {"float", {4, 'f'}}, {"float32", {4, 'f'}}, {"double", {8, 'f'}}, {"float64", {8, 'f'}}};
  const auto it = kTypes.find(t);
  if (it == kTypes.end()) return false;
  size = it->second.first;
  kind = it->second.second;
  return true;
}

// The value of type T in the first sizeof(T) bytes of b.
template <typename T>
T load(const unsigned char* b) {
  T v;
  std::memcpy(&v, b, sizeof v);
  return v;
}

double decode(const unsigned char* p, int size, char kind, bool big_endian) {
  unsigned char b[8];
  for (int i = 0; i < size; ++i) b[i] = big_endian ? p[size - 1 - i] : p[i];
  switch (kind) {
    case 'f':
      return size == 4 ? load<float>(b) : load<double>(b);
    case 'i':
      return size == 1   ? load<std::int8_t>(b)
             : size == 2 ? load<std::int16_t>(b)
                         : load<std::int32_t>(b);
    default:
      return size == 1   ? load<std::uint8_t>(b)
             : size == 2 ? load<std::uint16_t>(b)
                         : load<std::uint32_t>(b);
  }
}

// A vertex index read from a face list, before fan() checks it against the vertex count: any
// number, so a huge, infinite or NaN value is refused before it is converted.
long long list_index(double v, const std::string& path, const std::string& element) {
  if (!(std::abs(v) < 1e15)) fail(path, "bad vertex index in element '" + element + "'");
  return static_cast<long long>(v);
}

// The header of a PLY file.
struct PlyHeader {
  std::string format;
  std::vector<PlyElement> elements;
  size_t body = 0;  // where the data starts
};

PlyHeader read_ply_header(const std::string& path, const std::string& data) {
  Lines lines(data);
  std::string line;
  if (!lines.next(line) || split(line) != std::vector<std::string>{"ply"})
    fail(path, "not a PLY file (the first line must be 'ply')");
  PlyHeader h;
  bool ended = false;
  while (lines.next(line)) {
    const auto tok = split(line);
    if (tok.empty()) continue;
    if (tok[0] == "comment" || tok[0] == "obj_info") continue;
    if (tok[0] == "end_header") {
      ended = true;
      break;
    }
    if (tok[0] == "format") {
      if (tok.size() != 3) fail(path, "malformed format line");
      h.format = tok[1];
      if (h.format != "ascii" && h.format != "binary_little_endian" &&
          h.format != "binary_big_endian")
        fail(path, "unknown PLY format '" + h.format + "'");
    } else if (tok[0] == "element") {
      long long n;
      if (tok.size() != 3 || !parse_integer(tok[2], n)) fail(path, "malformed element line");
      if (n < 0 || n > kMaxCount)
        fail(path, "element '" + tok[1] + "' declares an absurd count " + tok[2]);
      h.elements.push_back({tok[1], n, {}});
    } else if (tok[0] == "property") {
      if (h.elements.empty()) fail(path, "property before any element");
      PlyProperty p;
      if (tok.size() == 5 && tok[1] == "list") {
        p.list = true;
        if (!ply_type(tok[2], p.count_size, p.count_kind) || p.count_kind == 'f' ||
            !ply_type(tok[3], p.type, p.kind))
          fail(path, "bad list property types in '" + line + "'");
        p.name = tok[4];
      } else if (tok.size() == 3) {
        if (!ply_type(tok[1], p.type, p.kind)) fail(path, "unknown property type '" + tok[1] + "'");
        p.name = tok[2];
      } else {
        fail(path, "malformed property line '" + line + "'");
      }
      h.elements.back().props.push_back(p);
    } else {
      fail(path, "unexpected PLY header line '" + line.substr(0, 40) + "'");
    }
  }
  if (!ended) fail(path, "truncated PLY header (no end_header)");
  if (h.format.empty()) fail(path, "PLY header has no format line");
  h.body = lines.position();
  return h;
}

// The elements and properties that hold the geometry.
struct PlyGeometry {
  const PlyElement* vertex = nullptr;
  const PlyElement* face = nullptr;
  int ix[3] = {-1, -1, -1};  // x, y, z among the vertex properties
  int face_prop = -1;        // the vertex index list among the face properties
};

PlyGeometry find_ply_geometry(const std::string& path, const PlyHeader& h) {
  PlyGeometry g;
  for (const auto& e : h.elements) {
    if (e.name == "vertex") g.vertex = &e;
    if (e.name == "face") g.face = &e;
  }
  if (!g.vertex) fail(path, "PLY file has no vertex element");
  for (size_t i = 0; i < g.vertex->props.size(); ++i)
    for (int a = 0; a < 3; ++a)
      if (g.vertex->props[i].name == std::string(1, "xyz"[a]) && !g.vertex->props[i].list)
        g.ix[a] = static_cast<int>(i);
  for (int a = 0; a < 3; ++a)
    if (g.ix[a] < 0)
      fail(path, "PLY vertex element has no property '" + std::string(1, "xyz"[a]) + "'");
  if (g.face) {
    for (size_t i = 0; i < g.face->props.size(); ++i)
      if (g.face->props[i].list &&
          (g.face->props[i].name == "vertex_indices" || g.face->props[i].name == "vertex_index"))
        g.face_prop = static_cast<int>(i);
    if (g.face_prop < 0 && g.face->count > 0)
      fail(path, "PLY face element has no vertex_indices list");
  }
  return g;
}

// Declared counts against the bytes (binary) or tokens (ascii) actually there.
void check_ply_counts(const std::string& path, const std::string& data, const PlyHeader& h) {
  if (h.format != "ascii") {
    long long min_bytes = 0;
    for (const auto& e : h.elements) {
      long long item = 0;
      for (const auto& p : e.props) item += p.list ? p.count_size : p.type;
      min_bytes += e.count * item;
    }
    if (min_bytes > static_cast<long long>(data.size() - h.body))
      fail(path, "truncated or absurd counts: the header needs at least " +
                     std::to_string(min_bytes) + " bytes of data, the file has " +
                     std::to_string(data.size() - h.body));
  } else {
    long long min_tokens = 0;
    for (const auto& e : h.elements) min_tokens += e.count * static_cast<long long>(e.props.size());
    if (min_tokens > static_cast<long long>(data.size() - h.body))
      fail(path,
           "truncated or absurd counts: the header declares more values than the file has "
           "characters");
  }
}

// What the data holds: the vertices and the faces fanned into triangles.
struct PlyData {
  bool keep_nan = false;
  PointCloud points;
  std::vector<Eigen::Vector3i> triangles;
};

void read_ply_binary(const std::string& path, const std::string& data, const PlyHeader& h,
                     const PlyGeometry& g, PlyData& out) {
  std::vector<long long> poly;
  std::vector<double> values;
  const bool be = h.format == "binary_big_endian";
  const auto* p = reinterpret_cast<const unsigned char*>(data.data() + h.body);
  const auto* end = reinterpret_cast<const unsigned char*>(data.data() + data.size());
  for (const auto& e : h.elements) {
    for (long long i = 0; i < e.count; ++i) {
      values.clear();
      for (size_t k = 0; k < e.props.size(); ++k) {
        const auto& prop = e.props[k];
        if (!prop.list) {
          if (end - p < prop.type) fail(path, "truncated data in element '" + e.name + "'");
          values.push_back(decode(p, prop.type, prop.kind, be));
          p += prop.type;
          continue;
        }
        if (end - p < prop.count_size) fail(path, "truncated data in element '" + e.name + "'");
        const double n = decode(p, prop.count_size, prop.count_kind, be);
        p += prop.count_size;
        if (n < 0 || n * prop.type > end - p)
          fail(path, "truncated data or bad list size in element '" + e.name + "'");
        if (&e == g.face && static_cast<int>(k) == g.face_prop) {
          poly.clear();
          for (long long j = 0; j < static_cast<long long>(n); ++j)
            poly.push_back(
                list_index(decode(p + j * prop.type, prop.type, prop.kind, be), path, e.name));
          fan(out.triangles, poly, g.vertex->count, path, i);
        }
        p += static_cast<long long>(n) * prop.type;
        values.push_back(0.0);
      }
      if (&e == g.vertex) {
        const Eigen::Vector3d v(values[g.ix[0]], values[g.ix[1]], values[g.ix[2]]);
        if (!(out.keep_nan && v.hasNaN())) check_point(path, v, i);
        out.points.push_back(v);
      }
    }
  }
}

void read_ply_ascii(const std::string& path, const std::string& data, const PlyHeader& h,
                    const PlyGeometry& g, PlyData& out) {
  std::vector<long long> poly;
  std::vector<double> values;
  Tokens tokens(data, h.body);
  std::string tok;
  auto number = [&](const std::string& element) {
    double v;
    if (!tokens.next(tok)) fail(path, "truncated: the data ends inside element '" + element + "'");
    if (!parse_double(tok, v)) fail(path, "'" + tok.substr(0, 20) + "' is not a number");
    return v;
  };
  for (const auto& e : h.elements) {
    for (long long i = 0; i < e.count; ++i) {
      values.clear();
      for (size_t k = 0; k < e.props.size(); ++k) {
        const auto& prop = e.props[k];
        if (!prop.list) {
          values.push_back(number(e.name));
          continue;
        }
        const double n = number(e.name);
        if (n < 0 || n > 1e6 || n != std::floor(n)) fail(path, "bad list size in '" + e.name + "'");
        poly.clear();
        for (long long j = 0; j < static_cast<long long>(n); ++j)
          poly.push_back(list_index(number(e.name), path, e.name));
        if (&e == g.face && static_cast<int>(k) == g.face_prop)
          fan(out.triangles, poly, g.vertex->count, path, i);
        values.push_back(0.0);
      }
      if (&e == g.vertex) {
        const Eigen::Vector3d v(values[g.ix[0]], values[g.ix[1]], values[g.ix[2]]);
        if (!(out.keep_nan && v.hasNaN())) check_point(path, v, i);
        out.points.push_back(v);
      }
    }
  }
}

}  // namespace

GeometryFile read_ply(const std::string& path) {
  return parse_ply(read_all(path), path);
}

GeometryFile parse_ply(const std::string& data, const std::string& path) {
  return parse_ply_file(data, path, false);
}

GeometryFile file_io_detail::parse_ply_file(const std::string& data, const std::string& path,
                                            bool keep_nan) {
  require_data(path, data);
  const PlyHeader h = read_ply_header(path, data);
  const PlyGeometry g = find_ply_geometry(path, h);
  check_ply_counts(path, data, h);
  PlyData d;
  d.keep_nan = keep_nan;
  d.points.reserve(g.vertex->count);
  if (h.format != "ascii")
    read_ply_binary(path, data, h, g, d);
  else
    read_ply_ascii(path, data, h, g, d);
  if (d.points.empty()) fail(path, "no vertices");
  GeometryFile out;
  if (d.triangles.empty()) {
    out.cloud = std::move(d.points);
  } else {
    out.is_mesh = true;
    out.mesh.vertices = std::move(d.points);
    out.mesh.triangles = std::move(d.triangles);
  }
  return out;
}

// ---------------------------------------------------------------------------------------------
// Writer

namespace {
void write_ply_impl(const PointCloud& v, const std::vector<Eigen::Vector3i>* tris,
                    const std::string& path, bool binary) {
  auto out = open_out(path, true);
  out << "ply\nformat " << (binary ? "binary_little_endian" : "ascii") << " 1.0\n";
  out << "comment claspplan\nelement vertex " << v.size()
      << "\nproperty double x\nproperty double y\nproperty double z\n";
  if (tris) out << "element face " << tris->size() << "\nproperty list uchar int vertex_indices\n";
  out << "end_header\n";
  for (const auto& p : v) {
    if (binary) {
      for (int a = 0; a < 3; ++a) put(out, p[a]);
    } else {
      out << p.x() << " " << p.y() << " " << p.z() << "\n";
    }
  }
  if (tris) {
    for (const auto& t : *tris) {
      if (binary) {
        put(out, static_cast<std::uint8_t>(3));
        for (int k = 0; k < 3; ++k) put(out, static_cast<std::int32_t>(t[k]));
      } else {
        out << "3 " << t[0] << " " << t[1] << " " << t[2] << "\n";
      }
    }
  }
  finish(out, path);
}
}  // namespace

void write_ply(const PointCloud& cloud, const std::string& path, bool binary) {
  write_ply_impl(cloud, nullptr, path, binary);
}

void write_ply(const TriangleMesh& mesh, const std::string& path, bool binary) {
  write_ply_impl(mesh.vertices, &mesh.triangles, path, binary);
}

}  // namespace claspplan
