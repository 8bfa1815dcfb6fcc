#include <cstdint>
#include <cstring>
#include <functional>
#include <string>
#include <vector>

#include "core/file_io.hpp"
#include "core/file_io_detail.hpp"

namespace claspplan {

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

// The header of a PCD file, as declared.
struct PcdHeader {
  std::vector<std::string> fields, types;
  std::vector<long long> sizes, counts;
  long long width = -1, height = 1, points = -1;
  std::vector<std::string> viewpoint;  // the VIEWPOINT values, unchecked
  bool has_viewpoint = false;
  std::string data_kind;
  size_t body = 0;  // where the data starts
};

PcdHeader read_pcd_header(const std::string& path, const std::string& data) {
  PcdHeader h;
  Lines lines(data);
  std::string line;
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
      h.fields.assign(tok.begin() + 1, tok.end());
      saw_header_key = true;
    } else if (key == "SIZE") {
      ints(h.sizes);
    } else if (key == "TYPE") {
      h.types.assign(tok.begin() + 1, tok.end());
    } else if (key == "COUNT") {
      ints(h.counts);
    } else if (key == "WIDTH") {
      h.width = one_int();
    } else if (key == "HEIGHT") {
      h.height = one_int();
    } else if (key == "POINTS") {
      h.points = one_int();
    } else if (key == "VIEWPOINT") {
      h.viewpoint.assign(tok.begin() + 1, tok.end());
      h.has_viewpoint = true;
    } else if (key == "DATA") {
      if (tok.size() != 2) fail(path, "malformed DATA line");
      h.data_kind = lower(tok[1]);
      break;
    } else {
      fail(path, saw_header_key ? "unknown PCD header key '" + key + "'"
                                : "not a PCD file (unexpected '" + key.substr(0, 20) + "')");
    }
  }
  h.body = lines.position();
  return h;
}

// Checks the declared counts and sizes (completing the defaults).
void check_pcd_header(const std::string& path, PcdHeader& h) {
  if (h.data_kind.empty()) fail(path, "not a PCD file or truncated header (no DATA line)");
  if (h.fields.empty()) fail(path, "PCD header has no FIELDS");
  if (h.counts.empty()) h.counts.assign(h.fields.size(), 1);
  if (h.sizes.size() != h.fields.size() || h.types.size() != h.fields.size() ||
      h.counts.size() != h.fields.size())
    fail(path, "PCD header: FIELDS, SIZE, TYPE and COUNT have different lengths");
  if (h.width < 0 && h.points < 0) fail(path, "PCD header has neither WIDTH nor POINTS");
  const auto absurd = [&] {
    fail(path, "PCD header declares an absurd size (WIDTH " + std::to_string(h.width) +
                   ", HEIGHT " + std::to_string(h.height) + ", POINTS " + std::to_string(h.points) +
                   ")");
  };
  // The sizes are bounded before they are multiplied.
  if (h.width > kMaxCount || h.height < 1 || h.height > kMaxCount || h.points > kMaxCount) absurd();
  if (h.width < 0) h.width = h.points;
  if (h.points < 0) h.points = h.width * h.height;
  if (h.width < 0 || h.points < 0 || h.points > kMaxCount) absurd();
  if (h.width * h.height != h.points)
    fail(path, "PCD header: WIDTH x HEIGHT = " + std::to_string(h.width * h.height) +
                   " but POINTS = " + std::to_string(h.points));
}

// Where x, y and z are in a point.
struct PcdLayout {
  long long point_size = 0, columns = 0;
  int xyz_col[3] = {-1, -1, -1}, xyz_size[3] = {0, 0, 0};
  long long xyz_offset[3] = {0, 0, 0}, xyz_field_offset[3] = {0, 0, 0};
};

PcdLayout pcd_layout(const std::string& path, const PcdHeader& h) {
  PcdLayout l;
  for (size_t f = 0; f < h.fields.size(); ++f) {
    if (h.sizes[f] != 1 && h.sizes[f] != 2 && h.sizes[f] != 4 && h.sizes[f] != 8)
      fail(path, "PCD field '" + h.fields[f] + "' has size " + std::to_string(h.sizes[f]));
    if (h.counts[f] < 1 || h.counts[f] > 10000)
      fail(path, "PCD field '" + h.fields[f] + "' has count " + std::to_string(h.counts[f]));
    if (h.types[f] != "F" && h.types[f] != "I" && h.types[f] != "U")
      fail(path, "PCD field '" + h.fields[f] + "' has type '" + h.types[f] + "'");
    for (int a = 0; a < 3; ++a) {
      if (h.fields[f] == std::string(1, "xyz"[a])) {
        if (h.types[f] != "F" || (h.sizes[f] != 4 && h.sizes[f] != 8) || h.counts[f] != 1)
          fail(path, "PCD field '" + h.fields[f] + "' must be one float (F 4 or F 8)");
        l.xyz_col[a] = static_cast<int>(l.columns);
        l.xyz_size[a] = static_cast<int>(h.sizes[f]);
        l.xyz_offset[a] = l.point_size;
        l.xyz_field_offset[a] = l.point_size * h.points;  // binary_compressed: field-major
      }
    }
    l.point_size += h.sizes[f] * h.counts[f];
    l.columns += h.counts[f];
  }
  for (int a = 0; a < 3; ++a)
    if (l.xyz_col[a] < 0) fail(path, "PCD file has no field '" + std::string(1, "xyz"[a]) + "'");
  return l;
}

using AddPoint = std::function<void(const Eigen::Vector3d&, long long)>;

void read_pcd_ascii(const std::string& path, const std::string& data, const PcdHeader& h,
                    const PcdLayout& l, const AddPoint& add) {
  Lines rows(data, h.body);
  std::string row;
  long long i = 0;
  while (i < h.points && rows.next(row)) {
    const auto tok = split(row);
    if (tok.empty()) continue;
    if (static_cast<long long>(tok.size()) != l.columns)
      fail(path, "PCD point " + std::to_string(i) + " has " + std::to_string(tok.size()) +
                     " values, expected " + std::to_string(l.columns));
    Eigen::Vector3d p;
    for (int a = 0; a < 3; ++a)
      if (!parse_double(tok[l.xyz_col[a]], p[a]))
        fail(path,
             "PCD point " + std::to_string(i) + ": '" + tok[l.xyz_col[a]] + "' is not a number");
    add(p, i++);
  }
  if (i < h.points)
    fail(path, "truncated: header declares " + std::to_string(h.points) + " points, found " +
                   std::to_string(i));
}

void read_pcd_binary(const std::string& path, const std::string& data, const PcdHeader& h,
                     const PcdLayout& l, const AddPoint& add) {
  const long long need = h.points * l.point_size;
  if (static_cast<long long>(data.size() - h.body) < need)
    fail(path, "truncated: " + std::to_string(h.points) + " points need " + std::to_string(need) +
                   " bytes of data, the file has " + std::to_string(data.size() - h.body));
  const auto* base = reinterpret_cast<const unsigned char*>(data.data() + h.body);
  for (long long i = 0; i < h.points; ++i) {
    Eigen::Vector3d p;
    for (int a = 0; a < 3; ++a)
      p[a] = read_float(base + i * l.point_size + l.xyz_offset[a], l.xyz_size[a]);
    add(p, i);
  }
}

void read_pcd_compressed(const std::string& path, const std::string& data, const PcdHeader& h,
                         const PcdLayout& l, const AddPoint& add) {
  const size_t body = h.body;
  if (data.size() - body < 8) fail(path, "truncated binary_compressed data");
  std::uint32_t csize, usize;
  std::memcpy(&csize, data.data() + body, 4);
  std::memcpy(&usize, data.data() + body + 4, 4);
  if (static_cast<long long>(usize) != h.points * l.point_size)
    fail(path, "binary_compressed: uncompressed size " + std::to_string(usize) +
                   " != " + std::to_string(h.points * l.point_size));
  if (csize > data.size() - body - 8)
    fail(path, "truncated: compressed block of " + std::to_string(csize) + " bytes, the file has " +
                   std::to_string(data.size() - body - 8));
  std::vector<unsigned char> raw(usize);
  if (usize > 0 && !lzf_decompress(reinterpret_cast<const unsigned char*>(data.data() + body + 8),
                                   csize, raw.data(), usize))
    fail(path, "binary_compressed data is corrupt");
  for (long long i = 0; i < h.points; ++i) {
    Eigen::Vector3d p;
    for (int a = 0; a < 3; ++a)
      p[a] = read_float(raw.data() + l.xyz_field_offset[a] + i * l.xyz_size[a], l.xyz_size[a]);
    add(p, i);
  }
}

}  // namespace

PcdPoints file_io_detail::parse_pcd_points(const std::string& data, const std::string& path) {
  require_data(path, data);
  PcdHeader h = read_pcd_header(path, data);
  check_pcd_header(path, h);
  const PcdLayout layout = pcd_layout(path, h);
  PcdPoints out;
  out.width = h.width;
  out.height = h.height;
  out.viewpoint = h.viewpoint;
  out.has_viewpoint = h.has_viewpoint;
  out.points.reserve(h.points);
  const AddPoint add = [&](const Eigen::Vector3d& p, long long i) {
    if (!p.hasNaN()) check_point(path, p, i);  // NaN is PCL's "no reading"; infinity is an error
    out.points.push_back(p);
  };
  if (h.data_kind == "ascii") {
    read_pcd_ascii(path, data, h, layout, add);
  } else if (h.data_kind == "binary") {
    read_pcd_binary(path, data, h, layout, add);
  } else if (h.data_kind == "binary_compressed") {
    read_pcd_compressed(path, data, h, layout, add);
  } else {
    fail(path, "unknown PCD DATA kind '" + h.data_kind + "'");
  }
  return out;
}

PointCloud read_pcd(const std::string& path) {
  return parse_pcd(read_all(path), path);
}

PointCloud parse_pcd(const std::string& data, const std::string& path) {
  PcdPoints pcd = parse_pcd_points(data, path);
  const bool organized = pcd.height > 1;
  PointCloud cloud;
  cloud.reserve(pcd.points.size());
  for (size_t i = 0; i < pcd.points.size(); ++i) {
    const Eigen::Vector3d& p = pcd.points[i];
    if (p.hasNaN()) {
      if (organized) continue;  // PCL's "no reading" in organized clouds
      check_point(path, p, static_cast<long long>(i));
    }
    cloud.push_back(p);
  }
  if (cloud.empty()) fail(path, "no points");
  return cloud;
}

// ---------------------------------------------------------------------------------------------
// XYZ

PointCloud read_xyz(const std::string& path) {
  return parse_xyz(read_all(path), path);
}

PointCloud parse_xyz(const std::string& data, const std::string& path) {
  return parse_xyz_points(data, path, false);
}

PointCloud file_io_detail::parse_xyz_points(const std::string& data, const std::string& path,
                                            bool skip_nan) {
  require_data(path, data);
  Lines lines(data);
  std::string line;
  PointCloud cloud;
  while (lines.next(line)) {
    strip_comment(line);
    const auto tok = split(line, true);
    if (tok.empty()) continue;
    if (tok.size() < 3)
      fail(path,
           "line " + std::to_string(lines.number()) + ": expected 'x y z', got '" + line + "'");
    Eigen::Vector3d p;
    for (int a = 0; a < 3; ++a)
      if (!parse_double(tok[a], p[a]))
        fail(path, "line " + std::to_string(lines.number()) + ": '" + tok[a] + "' is not a number");
    if (skip_nan && p.hasNaN()) continue;
    if (!p.allFinite())
      fail(path, "line " + std::to_string(lines.number()) + ": NaN or infinite coordinate");
    cloud.push_back(p);
    if (static_cast<long long>(cloud.size()) > kMaxCount) fail(path, "more than 50 million points");
  }
  if (cloud.empty() && !skip_nan) fail(path, "no points (expected lines 'x y z')");
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

}  // namespace claspplan
