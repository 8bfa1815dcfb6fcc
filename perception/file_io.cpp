#include "perception/file_io.hpp"

#include <algorithm>
#include <cctype>
#include <cmath>
#include <cstdint>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <iomanip>
#include <map>
#include <sstream>
#include <stdexcept>

namespace claspplan::perception {

namespace {

constexpr long long kMaxCount = 50'000'000;

[[noreturn]] void fail(const std::string& path, const std::string& message) {
  throw std::invalid_argument(path + ": " + message);
}

std::string read_all(const std::string& path) {
  std::error_code ec;
  if (!std::filesystem::exists(path, ec)) fail(path, "file not found");
  if (!std::filesystem::is_regular_file(path, ec)) fail(path, "not a regular file");
  std::ifstream in(path, std::ios::binary);
  if (!in) fail(path, "cannot open the file");
  std::string data((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  if (data.empty()) fail(path, "empty file");
  return data;
}

std::string lower(std::string s) {
  for (char& c : s) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
  return s;
}

std::string extension(const std::string& path) {
  return lower(std::filesystem::path(path).extension().string());
}

bool is_space(char c) {
  return c == ' ' || c == '\t' || c == '\r' || c == '\n' || c == '\f' || c == '\v';
}

// Splits a line into whitespace- (and optionally comma-) separated tokens.
std::vector<std::string> split(const std::string& line, bool commas = false) {
  std::vector<std::string> out;
  std::string cur;
  for (char c : line) {
    if (is_space(c) || (commas && c == ',')) {
      if (!cur.empty()) out.push_back(cur), cur.clear();
    } else {
      cur += c;
    }
  }
  if (!cur.empty()) out.push_back(cur);
  return out;
}

bool parse_double(const std::string& token, double& value) {
  if (token.empty()) return false;
  char* end = nullptr;
  value = std::strtod(token.c_str(), &end);
  return end == token.c_str() + token.size();
}

bool parse_integer(const std::string& token, long long& value) {
  if (token.empty()) return false;
  char* end = nullptr;
  errno = 0;
  value = std::strtoll(token.c_str(), &end, 10);
  return errno == 0 && end == token.c_str() + token.size();
}

// Line reader over a whole file held in memory.
class Lines {
 public:
  explicit Lines(const std::string& data, size_t start = 0) : data_(data), pos_(start) {}
  bool next(std::string& line) {
    if (pos_ >= data_.size()) return false;
    size_t end = data_.find('\n', pos_);
    if (end == std::string::npos) end = data_.size();
    line.assign(data_, pos_, end - pos_);
    if (!line.empty() && line.back() == '\r') line.pop_back();
    pos_ = end + 1;
    ++number_;
    return true;
  }
  size_t position() const { return std::min(pos_, data_.size()); }
  int number() const { return number_; }

 private:
  const std::string& data_;
  size_t pos_;
  int number_ = 0;
};

// Whitespace tokens over a buffer, from a start offset, without copying the buffer.
class Tokens {
 public:
  Tokens(const std::string& data, size_t start) : data_(data), pos_(start) {}
  bool next(std::string& token) {
    while (pos_ < data_.size() && is_space(data_[pos_])) ++pos_;
    if (pos_ >= data_.size()) return false;
    const size_t b = pos_;
    while (pos_ < data_.size() && !is_space(data_[pos_])) ++pos_;
    token.assign(data_, b, pos_ - b);
    return true;
  }

 private:
  const std::string& data_;
  size_t pos_;
};

void check_point(const std::string& path, const Eigen::Vector3d& p, long long index) {
  if (!p.allFinite())
    fail(path, "point " + std::to_string(index) + " has a NaN or infinite coordinate");
}

// ---------------------------------------------------------------------------------------------
// PCD

// LZF decompression (the format PCL's binary_compressed uses). Returns false on malformed input.
bool lzf_decompress(const unsigned char* in, size_t in_len, unsigned char* out, size_t out_len) {
  size_t ip = 0, op = 0;
  while (ip < in_len) {
    const unsigned ctrl = in[ip++];
    if (ctrl < 32) {
      const size_t len = ctrl + 1;
      if (ip + len > in_len || op + len > out_len) return false;
      std::memcpy(out + op, in + ip, len);
      ip += len;
      op += len;
    } else {
      size_t len = ctrl >> 5;
      if (len == 7) {
        if (ip >= in_len) return false;
        len += in[ip++];
      }
      if (ip >= in_len) return false;
      const size_t back = ((ctrl & 0x1f) << 8) + in[ip++] + 1;
      len += 2;
      if (back > op || op + len > out_len) return false;
      for (size_t k = 0; k < len; ++k, ++op) out[op] = out[op - back];
    }
  }
  return op == out_len;
}

double read_float(const unsigned char* p, int size) {
  if (size == 4) {
    float f;
    std::memcpy(&f, p, 4);
    return f;
  }
  double d;
  std::memcpy(&d, p, 8);
  return d;
}

}  // namespace

PointCloud read_pcd(const std::string& path) {
  const std::string data = read_all(path);
  Lines lines(data);
  std::string line;
  std::vector<std::string> fields, types;
  std::vector<long long> sizes, counts;
  long long width = -1, height = 1, points = -1;
  std::string data_kind;
  bool saw_header_key = false;
  while (lines.next(line)) {
    if (lines.position() > (1 << 20) && !saw_header_key) fail(path, "not a PCD file (no header)");
    const auto tok = split(line);
    if (tok.empty() || tok[0][0] == '#') continue;
    const std::string key = tok[0];
    auto ints = [&](std::vector<long long>& out) {
      for (size_t i = 1; i < tok.size(); ++i) {
        long long v;
        if (!parse_integer(tok[i], v)) fail(path, "header line '" + line + "' has a non-integer");
        out.push_back(v);
      }
    };
    auto one_int = [&]() {
      long long v;
      if (tok.size() != 2 || !parse_integer(tok[1], v))
        fail(path, "header line '" + line + "' must have one integer");
      return v;
    };
    if (key == "VERSION") {
      saw_header_key = true;
    } else if (key == "FIELDS") {
      fields.assign(tok.begin() + 1, tok.end());
      saw_header_key = true;
    } else if (key == "SIZE") {
      ints(sizes);
    } else if (key == "TYPE") {
      types.assign(tok.begin() + 1, tok.end());
    } else if (key == "COUNT") {
      ints(counts);
    } else if (key == "WIDTH") {
      width = one_int();
    } else if (key == "HEIGHT") {
      height = one_int();
    } else if (key == "POINTS") {
      points = one_int();
    } else if (key == "VIEWPOINT") {
    } else if (key == "DATA") {
      if (tok.size() != 2) fail(path, "malformed DATA line");
      data_kind = lower(tok[1]);
      break;
    } else {
      fail(path, saw_header_key ? "unknown PCD header key '" + key + "'"
                                : "not a PCD file (unexpected '" + key.substr(0, 20) + "')");
    }
  }
  if (data_kind.empty()) fail(path, "not a PCD file or truncated header (no DATA line)");
  if (fields.empty()) fail(path, "PCD header has no FIELDS");
  if (counts.empty()) counts.assign(fields.size(), 1);
  if (sizes.size() != fields.size() || types.size() != fields.size() ||
      counts.size() != fields.size())
    fail(path, "PCD header: FIELDS, SIZE, TYPE and COUNT have different lengths");
  if (width < 0 && points < 0) fail(path, "PCD header has neither WIDTH nor POINTS");
  if (width < 0) width = points;
  if (points < 0) points = width * height;
  if (width < 0 || height < 1 || points < 0 || points > kMaxCount || width > kMaxCount ||
      height > kMaxCount)
    fail(path, "PCD header declares an absurd size (WIDTH " + std::to_string(width) + ", HEIGHT " +
                   std::to_string(height) + ", POINTS " + std::to_string(points) + ")");
  if (width * height != points)
    fail(path, "PCD header: WIDTH x HEIGHT = " + std::to_string(width * height) +
                   " but POINTS = " + std::to_string(points));
  long long point_size = 0, columns = 0;
  int xyz_col[3] = {-1, -1, -1}, xyz_size[3] = {0, 0, 0};
  long long xyz_offset[3] = {0, 0, 0}, xyz_field_offset[3] = {0, 0, 0};
  for (size_t f = 0; f < fields.size(); ++f) {
    if (sizes[f] != 1 && sizes[f] != 2 && sizes[f] != 4 && sizes[f] != 8)
      fail(path, "PCD field '" + fields[f] + "' has size " + std::to_string(sizes[f]));
    if (counts[f] < 1 || counts[f] > 10000)
      fail(path, "PCD field '" + fields[f] + "' has count " + std::to_string(counts[f]));
    if (types[f] != "F" && types[f] != "I" && types[f] != "U")
      fail(path, "PCD field '" + fields[f] + "' has type '" + types[f] + "'");
    for (int a = 0; a < 3; ++a) {
      if (fields[f] == std::string(1, "xyz"[a])) {
        if (types[f] != "F" || (sizes[f] != 4 && sizes[f] != 8) || counts[f] != 1)
          fail(path, "PCD field '" + fields[f] + "' must be one float (F 4 or F 8)");
        xyz_col[a] = static_cast<int>(columns);
        xyz_size[a] = static_cast<int>(sizes[f]);
        xyz_offset[a] = point_size;
        xyz_field_offset[a] = point_size * points;  // binary_compressed: field-major
      }
    }
    point_size += sizes[f] * counts[f];
    columns += counts[f];
  }
  for (int a = 0; a < 3; ++a)
    if (xyz_col[a] < 0) fail(path, "PCD file has no field '" + std::string(1, "xyz"[a]) + "'");
  const bool organized = height > 1;
  PointCloud cloud;
  cloud.reserve(points);
  auto add = [&](const Eigen::Vector3d& p, long long i) {
    if (organized && p.hasNaN()) return;  // PCL's "no reading" in organized clouds
    check_point(path, p, i);
    cloud.push_back(p);
  };
  const size_t body = lines.position();
  if (data_kind == "ascii") {
    Lines rows(data, body);
    std::string row;
    long long i = 0;
    while (i < points && rows.next(row)) {
      const auto tok = split(row);
      if (tok.empty()) continue;
      if (static_cast<long long>(tok.size()) != columns)
        fail(path, "PCD point " + std::to_string(i) + " has " + std::to_string(tok.size()) +
                       " values, expected " + std::to_string(columns));
      Eigen::Vector3d p;
      for (int a = 0; a < 3; ++a)
        if (!parse_double(tok[xyz_col[a]], p[a]))
          fail(path,
               "PCD point " + std::to_string(i) + ": '" + tok[xyz_col[a]] + "' is not a number");
      add(p, i++);
    }
    if (i < points)
      fail(path, "truncated: header declares " + std::to_string(points) + " points, found " +
                     std::to_string(i));
  } else if (data_kind == "binary") {
    const long long need = points * point_size;
    if (static_cast<long long>(data.size() - body) < need)
      fail(path, "truncated: " + std::to_string(points) + " points need " + std::to_string(need) +
                     " bytes of data, the file has " + std::to_string(data.size() - body));
    const auto* base = reinterpret_cast<const unsigned char*>(data.data() + body);
    for (long long i = 0; i < points; ++i) {
      Eigen::Vector3d p;
      for (int a = 0; a < 3; ++a)
        p[a] = read_float(base + i * point_size + xyz_offset[a], xyz_size[a]);
      add(p, i);
    }
  } else if (data_kind == "binary_compressed") {
    if (data.size() - body < 8) fail(path, "truncated binary_compressed data");
    std::uint32_t csize, usize;
    std::memcpy(&csize, data.data() + body, 4);
    std::memcpy(&usize, data.data() + body + 4, 4);
    if (static_cast<long long>(usize) != points * point_size)
      fail(path, "binary_compressed: uncompressed size " + std::to_string(usize) +
                     " != " + std::to_string(points * point_size));
    if (csize > data.size() - body - 8)
      fail(path, "truncated: compressed block of " + std::to_string(csize) +
                     " bytes, the file has " + std::to_string(data.size() - body - 8));
    std::vector<unsigned char> raw(usize);
    if (usize > 0 && !lzf_decompress(reinterpret_cast<const unsigned char*>(data.data() + body + 8),
                                     csize, raw.data(), usize))
      fail(path, "binary_compressed data is corrupt");
    for (long long i = 0; i < points; ++i) {
      Eigen::Vector3d p;
      for (int a = 0; a < 3; ++a)
        p[a] = read_float(raw.data() + xyz_field_offset[a] + i * xyz_size[a], xyz_size[a]);
      add(p, i);
    }
  } else {
    fail(path, "unknown PCD DATA kind '" + data_kind + "'");
  }
  if (cloud.empty()) fail(path, "no points");
  return cloud;
}

// ---------------------------------------------------------------------------------------------
// XYZ

PointCloud read_xyz(const std::string& path) {
  const std::string data = read_all(path);
  Lines lines(data);
  std::string line;
  PointCloud cloud;
  while (lines.next(line)) {
    const size_t hash = line.find('#');
    if (hash != std::string::npos) line.resize(hash);
    const auto tok = split(line, true);
    if (tok.empty()) continue;
    if (tok.size() < 3)
      fail(path,
           "line " + std::to_string(lines.number()) + ": expected 'x y z', got '" + line + "'");
    Eigen::Vector3d p;
    for (int a = 0; a < 3; ++a)
      if (!parse_double(tok[a], p[a]))
        fail(path, "line " + std::to_string(lines.number()) + ": '" + tok[a] + "' is not a number");
    if (!p.allFinite())
      fail(path, "line " + std::to_string(lines.number()) + ": NaN or infinite coordinate");
    cloud.push_back(p);
    if (static_cast<long long>(cloud.size()) > kMaxCount) fail(path, "more than 50 million points");
  }
  if (cloud.empty()) fail(path, "no points (expected lines 'x y z')");
  return cloud;
}

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

double decode(const unsigned char* p, int size, char kind, bool big_endian) {
  unsigned char b[8];
  for (int i = 0; i < size; ++i) b[i] = big_endian ? p[size - 1 - i] : p[i];
  switch (kind) {
    case 'f':
      if (size == 4) {
        float f;
        std::memcpy(&f, b, 4);
        return f;
      } else {
        double d;
        std::memcpy(&d, b, 8);
        return d;
      }
    case 'i':
      if (size == 1) return static_cast<std::int8_t>(b[0]);
      if (size == 2) {
        std::int16_t v;
        std::memcpy(&v, b, 2);
        return v;
      } else {
        std::int32_t v;
        std::memcpy(&v, b, 4);
        return v;
      }
    default:
      if (size == 1) return b[0];
      if (size == 2) {
        std::uint16_t v;
        std::memcpy(&v, b, 2);
        return v;
      } else {
        std::uint32_t v;
        std::memcpy(&v, b, 4);
        return v;
      }
  }
}

void fan(std::vector<std::array<int, 3>>& tris, const std::vector<long long>& face, long long nv,
         const std::string& path, long long index) {
  if (face.size() < 3) fail(path, "face " + std::to_string(index) + " has fewer than 3 vertices");
  for (long long v : face)
    if (v < 0 || v >= nv)
      fail(path, "face " + std::to_string(index) + " uses vertex " + std::to_string(v) + " of " +
                     std::to_string(nv));
  for (size_t k = 1; k + 1 < face.size(); ++k)
    tris.push_back(
        {static_cast<int>(face[0]), static_cast<int>(face[k]), static_cast<int>(face[k + 1])});
}

}  // namespace

GeometryFile read_ply(const std::string& path) {
  const std::string data = read_all(path);
  Lines lines(data);
  std::string line;
  if (!lines.next(line) || split(line) != std::vector<std::string>{"ply"})
    fail(path, "not a PLY file (the first line must be 'ply')");
  std::string format;
  std::vector<PlyElement> elements;
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
      format = tok[1];
      if (format != "ascii" && format != "binary_little_endian" && format != "binary_big_endian")
        fail(path, "unknown PLY format '" + format + "'");
    } else if (tok[0] == "element") {
      long long n;
      if (tok.size() != 3 || !parse_integer(tok[2], n)) fail(path, "malformed element line");
      if (n < 0 || n > kMaxCount)
        fail(path, "element '" + tok[1] + "' declares an absurd count " + tok[2]);
      elements.push_back({tok[1], n, {}});
    } else if (tok[0] == "property") {
      if (elements.empty()) fail(path, "property before any element");
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
      elements.back().props.push_back(p);
    } else {
      fail(path, "unexpected PLY header line '" + line.substr(0, 40) + "'");
    }
  }
  if (!ended) fail(path, "truncated PLY header (no end_header)");
  if (format.empty()) fail(path, "PLY header has no format line");
  const PlyElement* vertex = nullptr;
  const PlyElement* face = nullptr;
  for (const auto& e : elements) {
    if (e.name == "vertex") vertex = &e;
    if (e.name == "face") face = &e;
  }
  if (!vertex) fail(path, "PLY file has no vertex element");
  int ix[3] = {-1, -1, -1};
  for (size_t i = 0; i < vertex->props.size(); ++i)
    for (int a = 0; a < 3; ++a)
      if (vertex->props[i].name == std::string(1, "xyz"[a]) && !vertex->props[i].list)
        ix[a] = static_cast<int>(i);
  for (int a = 0; a < 3; ++a)
    if (ix[a] < 0)
      fail(path, "PLY vertex element has no property '" + std::string(1, "xyz"[a]) + "'");
  int face_prop = -1;
  if (face) {
    for (size_t i = 0; i < face->props.size(); ++i)
      if (face->props[i].list &&
          (face->props[i].name == "vertex_indices" || face->props[i].name == "vertex_index"))
        face_prop = static_cast<int>(i);
    if (face_prop < 0 && face->count > 0) fail(path, "PLY face element has no vertex_indices list");
  }
  const size_t body = lines.position();
  const bool binary = format != "ascii";
  // Declared counts against the bytes (binary) or tokens (ascii) actually there.
  if (binary) {
    long long min_bytes = 0;
    for (const auto& e : elements) {
      long long item = 0;
      for (const auto& p : e.props) item += p.list ? p.count_size : p.type;
      min_bytes += e.count * item;
    }
    if (min_bytes > static_cast<long long>(data.size() - body))
      fail(path, "truncated or absurd counts: the header needs at least " +
                     std::to_string(min_bytes) + " bytes of data, the file has " +
                     std::to_string(data.size() - body));
  } else {
    long long min_tokens = 0;
    for (const auto& e : elements) min_tokens += e.count * static_cast<long long>(e.props.size());
    if (min_tokens > static_cast<long long>(data.size() - body))
      fail(path,
           "truncated or absurd counts: the header declares more values than the file has "
           "characters");
  }
  GeometryFile out;
  PointCloud& pts = out.cloud;
  pts.reserve(vertex->count);
  std::vector<std::array<int, 3>> tris;
  std::vector<long long> poly;
  std::vector<double> values;
  if (binary) {
    const bool be = format == "binary_big_endian";
    const auto* p = reinterpret_cast<const unsigned char*>(data.data() + body);
    const auto* end = reinterpret_cast<const unsigned char*>(data.data() + data.size());
    for (const auto& e : elements) {
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
          if (&e == face && static_cast<int>(k) == face_prop) {
            poly.clear();
            for (long long j = 0; j < static_cast<long long>(n); ++j)
              poly.push_back(
                  static_cast<long long>(decode(p + j * prop.type, prop.type, prop.kind, be)));
            fan(tris, poly, vertex->count, path, i);
          }
          p += static_cast<long long>(n) * prop.type;
          values.push_back(0.0);
        }
        if (&e == vertex) {
          const Eigen::Vector3d v(values[ix[0]], values[ix[1]], values[ix[2]]);
          check_point(path, v, i);
          pts.push_back(v);
        }
      }
    }
  } else {
    Tokens tokens(data, body);
    std::string tok;
    auto number = [&](const std::string& element) {
      double v;
      if (!tokens.next(tok))
        fail(path, "truncated: the data ends inside element '" + element + "'");
      if (!parse_double(tok, v)) fail(path, "'" + tok.substr(0, 20) + "' is not a number");
      return v;
    };
    for (const auto& e : elements) {
      for (long long i = 0; i < e.count; ++i) {
        values.clear();
        for (size_t k = 0; k < e.props.size(); ++k) {
          const auto& prop = e.props[k];
          if (!prop.list) {
            values.push_back(number(e.name));
            continue;
          }
          const double n = number(e.name);
          if (n < 0 || n > 1e6 || n != std::floor(n))
            fail(path, "bad list size in '" + e.name + "'");
          poly.clear();
          for (long long j = 0; j < static_cast<long long>(n); ++j)
            poly.push_back(static_cast<long long>(number(e.name)));
          if (&e == face && static_cast<int>(k) == face_prop)
            fan(tris, poly, vertex->count, path, i);
          values.push_back(0.0);
        }
        if (&e == vertex) {
          const Eigen::Vector3d v(values[ix[0]], values[ix[1]], values[ix[2]]);
          check_point(path, v, i);
          pts.push_back(v);
        }
      }
    }
  }
  if (pts.empty()) fail(path, "no vertices");
  if (!tris.empty()) {
    out.is_mesh = true;
    out.mesh.vertices = std::move(pts);
    out.mesh.triangles = std::move(tris);
    out.cloud.clear();
  }
  return out;
}

// ---------------------------------------------------------------------------------------------
// OBJ, OFF, STL

TriangleMesh read_obj(const std::string& path) {
  const std::string data = read_all(path);
  Lines lines(data);
  std::string line;
  TriangleMesh mesh;
  std::vector<long long> poly;
  long long faces = 0;
  while (lines.next(line)) {
    const size_t hash = line.find('#');
    if (hash != std::string::npos) line.resize(hash);
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
  const std::string data = read_all(path);
  Lines lines(data);
  std::string line;
  std::vector<std::string> header;
  auto next_tokens = [&](std::vector<std::string>& tok) {
    while (lines.next(line)) {
      const size_t hash = line.find('#');
      if (hash != std::string::npos) line.resize(hash);
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
    if (!parse_integer(tok[0], n) || n < 3 || n + 1 > static_cast<long long>(tok.size()))
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
  const std::string data = read_all(path);
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
    std::array<int, 3> t;
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

// ---------------------------------------------------------------------------------------------
// Writers

namespace {

std::ofstream open_out(const std::string& path, bool binary) {
  std::ofstream out(path, binary ? std::ios::binary : std::ios::out);
  if (!out) throw std::runtime_error(path + ": cannot write the file");
  out << std::setprecision(17);
  return out;
}

template <class T>
void put(std::ofstream& out, T v) {
  out.write(reinterpret_cast<const char*>(&v), sizeof(T));
}

void finish(std::ofstream& out, const std::string& path) {
  out.flush();
  if (!out) throw std::runtime_error(path + ": write failed");
}

}  // namespace

void write_pcd(const PointCloud& cloud, const std::string& path, bool binary) {
  auto out = open_out(path, true);
  out << "# .PCD v0.7 - Point Cloud Data file format\nVERSION 0.7\nFIELDS x y z\n";
  out << (binary ? "SIZE 4 4 4\n" : "SIZE 8 8 8\n") << "TYPE F F F\nCOUNT 1 1 1\n";
  out << "WIDTH " << cloud.size() << "\nHEIGHT 1\nVIEWPOINT 0 0 0 1 0 0 0\nPOINTS " << cloud.size()
      << "\nDATA " << (binary ? "binary" : "ascii") << "\n";
  for (const auto& p : cloud) {
    if (binary) {
      for (int a = 0; a < 3; ++a) put(out, static_cast<float>(p[a]));
    } else {
      out << p.x() << " " << p.y() << " " << p.z() << "\n";
    }
  }
  finish(out, path);
}

void write_xyz(const PointCloud& cloud, const std::string& path) {
  auto out = open_out(path, false);
  out << "# x y z (metres)\n";
  for (const auto& p : cloud) out << p.x() << " " << p.y() << " " << p.z() << "\n";
  finish(out, path);
}

namespace {
void write_ply_impl(const PointCloud& v, const std::vector<std::array<int, 3>>* tris,
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

}  // namespace claspplan::perception
