#include <cstdint>
#include <cstring>

#include "perception/file_io.hpp"
#include "perception/file_io_detail.hpp"

namespace claspplan::perception {

using namespace file_io_detail;

// ---------------------------------------------------------------------------------------------
// PCD

namespace {

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
// Writers

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

}  // namespace claspplan::perception
