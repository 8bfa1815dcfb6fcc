#include "perception/camera.hpp"

#include <cmath>
#include <cstdint>
#include <cstring>
#include <fstream>
#include <iomanip>
#include <sstream>
#include <stdexcept>

#include <Eigen/SVD>
#include <opencv2/core.hpp>

#include "core/file_io_detail.hpp"
#include "core/input_error.hpp"
#include "core/png_files.hpp"
#include "core/yaml_field.hpp"

namespace claspplan::perception {

Eigen::Vector3d CameraModel::project(const Eigen::Vector3d& p_world) const {
  const Eigen::Vector3d p = T_world_camera.inverse() * p_world;
  if (p.z() <= 0.0) return {0.0, 0.0, p.z()};
  return {fx * p.x() / p.z() + cx, fy * p.y() / p.z() + cy, p.z()};
}

Eigen::Vector3d CameraModel::back_project(double u, double v, double z) const {
  return T_world_camera * Eigen::Vector3d((u - cx) * z / fx, (v - cy) * z / fy, z);
}

namespace {

std::string num(double v) {
  std::ostringstream s;
  s << std::setprecision(10) << v;
  return s.str();
}

void require(bool ok, const std::string& what, const std::string& message) {
  if (!ok) throw InputError(what + ": " + message);
}

}  // namespace

void validate_camera(const CameraModel& c, const std::string& what) {
  require(c.width > 0 && c.width <= 100000, what,
          "width must be in 1..100000, got " + num(c.width));
  require(c.height > 0 && c.height <= 100000, what,
          "height must be in 1..100000, got " + num(c.height));
  require(std::isfinite(c.fx) && c.fx > 0, what, "fx must be > 0, got " + num(c.fx));
  require(std::isfinite(c.fy) && c.fy > 0, what, "fy must be > 0, got " + num(c.fy));
  require(std::isfinite(c.cx), what, "cx must be finite, got " + num(c.cx));
  require(std::isfinite(c.cy), what, "cy must be finite, got " + num(c.cy));
  require(std::isfinite(c.depth_scale) && c.depth_scale > 0, what,
          "depth_scale must be > 0 (metres per PNG unit), got " + num(c.depth_scale));
  const Eigen::Matrix4d& M = c.T_world_camera.matrix();
  require(M.allFinite(), what, "T_world_camera has a NaN or infinite entry");
  require((M.row(3) - Eigen::RowVector4d(0, 0, 0, 1)).cwiseAbs().maxCoeff() < 1e-6, what,
          "T_world_camera's last row must be 0 0 0 1");
  const Eigen::Matrix3d R = M.topLeftCorner<3, 3>();
  const double err = (R.transpose() * R - Eigen::Matrix3d::Identity()).cwiseAbs().maxCoeff();
  require(err < 1e-4, what,
          "T_world_camera's rotation is not orthonormal (|R^T R - I| = " + num(err) + ")");
  require(R.determinant() > 0, what, "T_world_camera's rotation is a reflection (det < 0)");
}

CameraModel read_camera_yaml(const std::string& path) {
  return parse_camera_yaml(file_io_detail::read_all(path), path);
}

CameraModel parse_camera_yaml(const std::string& text, const std::string& path) {
  const YamlField root = YamlField::parse_map(text, path, "of camera fields");
  root.only(
      {"width", "height", "fx", "fy", "cx", "cy", "depth_scale", "T_world_camera", "no_reading"});
  CameraModel c;
  if (root.has("no_reading")) {
    const std::string v = root["no_reading"].text(true);
    if (v != "free" && v != "unknown") root["no_reading"].fail("must be free or unknown");
    c.no_reading_is_free = v == "free";
  }
  const auto integer = [&](const char* key) {
    return static_cast<int>(root.required(key).integer(-1000000000, 1000000000));
  };
  c.width = integer("width");
  c.height = integer("height");
  c.fx = root.required("fx").number();
  c.fy = root.required("fy").number();
  c.cx = root.required("cx").number();
  c.cy = root.required("cy").number();
  c.depth_scale = root.required("depth_scale").number();
  // 16 numbers (4x4 row-major), flat or as 4 rows of 4.
  const YamlField t = root.required("T_world_camera");
  std::vector<double> values;
  for (const YamlField& row : t.items("16 numbers (4x4 row-major) or 4 rows of 4")) {
    if (!row.is_list()) {
      values.push_back(row.number());
      continue;
    }
    const std::vector<double> r = row.numbers(4);
    values.insert(values.end(), r.begin(), r.end());
  }
  if (values.size() != 16)
    t.fail("must have 16 numbers (4x4 row-major), got " + std::to_string(values.size()));
  Eigen::Matrix4d M;
  for (int i = 0; i < 16; ++i) M(i / 4, i % 4) = values[i];
  c.T_world_camera.matrix() = M;
  validate_camera(c, path);
  // Remove rounding in the file's rotation (validated to 1e-4 above).
  Eigen::JacobiSVD<Eigen::Matrix3d> svd(M.topLeftCorner<3, 3>(),
                                        Eigen::ComputeFullU | Eigen::ComputeFullV);
  c.T_world_camera.linear() = svd.matrixU() * svd.matrixV().transpose();
  return c;
}

void write_camera_yaml(const CameraModel& c, const std::string& path) {
  validate_camera(c, "camera");
  std::ofstream out(path);
  if (!out) throw std::runtime_error(path + ": cannot write the camera file");
  out << std::setprecision(17);
  out << "# Pinhole depth camera: pixels, metres; optical frame z forward, x right, y down.\n";
  out << "width: " << c.width << "\nheight: " << c.height << "\n";
  out << "fx: " << c.fx << "\nfy: " << c.fy << "\ncx: " << c.cx << "\ncy: " << c.cy << "\n";
  out << "depth_scale: " << c.depth_scale << "  # metres per PNG unit (z-depth)\n";
  out << "T_world_camera:  # 4x4 row-major\n";
  const Eigen::Matrix4d M = c.T_world_camera.matrix();
  for (int i = 0; i < 4; ++i) {
    out << "  - [" << M(i, 0) << ", " << M(i, 1) << ", " << M(i, 2) << ", " << M(i, 3) << "]\n";
  }
  if (c.no_reading_is_free)
    out << "no_reading: free  # a rendered complete scene: a pixel without a reading saw nothing\n";
  if (!out) throw std::runtime_error(path + ": write failed");
}

CameraModel look_at_camera(const Eigen::Vector3d& position, const Eigen::Vector3d& target,
                           double radius, int width, int height) {
  Eigen::Vector3d z = target - position;
  const double dist = z.norm();
  if (!(dist > 1e-9) || !position.allFinite() || !target.allFinite())
    throw InputError("view position must differ from the target and be finite");
  z /= dist;
  Eigen::Vector3d up = Eigen::Vector3d::UnitZ();
  if (std::abs(z.dot(up)) > 0.99) up = Eigen::Vector3d::UnitX();
  const Eigen::Vector3d y = (-up + up.dot(z) * z).normalized();  // image down
  const Eigen::Vector3d x = y.cross(z);                          // image right
  CameraModel c;
  c.width = width;
  c.height = height;
  c.cx = (width - 1) / 2.0;
  c.cy = (height - 1) / 2.0;
  const double half = std::asin(std::min(0.99, std::max(radius, 1e-6) / dist));
  c.fx = c.fy = 0.45 * std::min(width, height) / std::tan(half);
  c.T_world_camera.linear().col(0) = x;
  c.T_world_camera.linear().col(1) = y;
  c.T_world_camera.linear().col(2) = z;
  c.T_world_camera.translation() = position;
  return c;
}

int DepthImage::valid_count() const {
  int n = 0;
  for (float z : depth) n += z > 0.0f;
  return n;
}

namespace {

std::uint32_t crc32(const unsigned char* p, size_t n, std::uint32_t crc = 0xffffffffu) {
  static std::uint32_t table[256];
  static const bool ready = [] {
    for (std::uint32_t i = 0; i < 256; ++i) {
      std::uint32_t c = i;
      for (int k = 0; k < 8; ++k) c = (c & 1) ? 0xedb88320u ^ (c >> 1) : c >> 1;
      table[i] = c;
    }
    return true;
  }();
  (void)ready;
  for (size_t i = 0; i < n; ++i) crc = table[(crc ^ p[i]) & 0xff] ^ (crc >> 8);
  return crc;
}

// Walks the PNG's chunks (lengths, CRCs, IHDR first, IEND last) before libpng sees the file, so
// that truncated or corrupt files and non-16-bit-grey images get a clear one-line reason (libpng
// would print its own messages on stderr).
void check_png_chunks(const std::string& data, const std::string& path, const CameraModel& camera) {
  const auto* b = reinterpret_cast<const unsigned char*>(data.data());
  auto be32 = [&](size_t at) {
    return std::uint32_t(b[at]) << 24 | std::uint32_t(b[at + 1]) << 16 |
           std::uint32_t(b[at + 2]) << 8 | std::uint32_t(b[at + 3]);
  };
  size_t at = 8;
  bool first = true;
  while (true) {
    if (at + 12 > data.size())
      throw InputError(path + ": cannot decode the PNG (truncated: no IEND chunk)");
    const std::uint32_t len = be32(at);
    if (len > data.size() - at - 12)
      throw InputError(path + ": cannot decode the PNG (truncated chunk)");
    const std::string type = data.substr(at + 4, 4);
    if (crc32(b + at + 4, len + 4) ^ 0xffffffffu ^ be32(at + 8 + len))
      throw InputError(path + ": cannot decode the PNG (corrupt " + type + " chunk)");
    if (first) {
      if (type != "IHDR" || len != 13)
        throw InputError(path + ": cannot decode the PNG (no IHDR chunk)");
      const int bit_depth = b[at + 8 + 8], colour = b[at + 8 + 9];
      if (bit_depth != 16 || colour != 0)
        throw InputError(path + ": depth must be a 16-bit single-channel PNG, got " +
                         std::to_string(bit_depth) + "-bit " + (colour == 0 ? "grey" : "colour") +
                         " (PNG colour type " + std::to_string(colour) + ")");
      // Before decoding, so that a forged size never allocates the image.
      const std::uint32_t width = be32(at + 8), height = be32(at + 12);
      if (width != static_cast<std::uint32_t>(camera.width) ||
          height != static_cast<std::uint32_t>(camera.height))
        throw InputError(path + ": image is " + std::to_string(width) + "x" +
                         std::to_string(height) + " but the camera is " +
                         std::to_string(camera.width) + "x" + std::to_string(camera.height));
      first = false;
    }
    at += 12 + len;
    if (type == "IEND") return;
  }
}

}  // namespace

DepthImage read_depth_png(const std::string& path, const CameraModel& camera) {
  return decode_depth_png(file_io_detail::read_all(path), camera, path);
}

DepthImage decode_depth_png(const std::string& data, const CameraModel& camera,
                            const std::string& path) {
  static const unsigned char kPng[8] = {0x89, 'P', 'N', 'G', '\r', '\n', 0x1a, '\n'};
  if (data.size() < 8 || std::memcmp(data.data(), kPng, 8) != 0)
    throw InputError(path + ": not a PNG file");
  if (data.size() > (1u << 30)) throw InputError(path + ": larger than 1 GB");
  check_png_chunks(data, path, camera);
  const Gray16Image img = decode_png_gray16(data, path);
  if (img.width != camera.width || img.height != camera.height)
    throw InputError(path + ": image is " + std::to_string(img.width) + "x" +
                     std::to_string(img.height) + " but the camera is " +
                     std::to_string(camera.width) + "x" + std::to_string(camera.height));
  DepthImage out(img.width, img.height);
  for (std::size_t i = 0; i < img.pixels.size(); ++i)
    out.depth[i] = static_cast<float>(img.pixels[i] * camera.depth_scale);
  return out;
}

void write_depth_png(const DepthImage& image, const CameraModel& camera, const std::string& path) {
  if (image.width <= 0 || image.height <= 0 ||
      image.depth.size() != static_cast<size_t>(image.width) * image.height)
    throw std::invalid_argument("write_depth_png: malformed depth image");
  Gray16Image img;
  img.width = image.width;
  img.height = image.height;
  img.pixels.resize(image.depth.size());
  for (std::size_t i = 0; i < image.depth.size(); ++i) {
    const double z = image.depth[i];
    const double units = std::isfinite(z) && z > 0 ? std::round(z / camera.depth_scale) : 0.0;
    img.pixels[i] = units >= 1.0 && units <= 65535.0 ? static_cast<std::uint16_t>(units) : 0;
  }
  write_png_gray16(path, img);
}

std::vector<Eigen::Vector3d> depth_to_points(const DepthView& view) {
  std::vector<Eigen::Vector3d> pts;
  pts.reserve(view.image.valid_count());
  append_depth_points(view, pts);
  return pts;
}

DepthPixels back_project(const DepthView& view, const Eigen::AlignedBox3d& keep,
                         Eigen::Vector3d* out) {
  const CameraModel& c = view.camera;
  const Eigen::Matrix3d R = c.T_world_camera.linear();
  const Eigen::Vector3d t = c.T_world_camera.translation();
  const bool crop = !keep.isEmpty();
  DepthPixels n;
  for (int v = 0; v < view.image.height; ++v) {
    for (int u = 0; u < view.image.width; ++u) {
      const double z = view.image.at(u, v);
      if (!(z > 0.0) || !std::isfinite(z)) continue;
      ++n.valid;
      const Eigen::Vector3d p =
          R * Eigen::Vector3d((u - c.cx) * z / c.fx, (v - c.cy) * z / c.fy, z) + t;
      if (!crop || keep.contains(p)) out[n.kept++] = p;
    }
  }
  return n;
}

int append_depth_points(const DepthView& view, std::vector<Eigen::Vector3d>& out,
                        const Eigen::AlignedBox3d& keep) {
  const std::size_t old = out.size();
  out.resize(old + view.image.valid_count());
  const DepthPixels n = back_project(view, keep, out.data() + old);
  out.resize(old + n.kept);
  return n.valid;
}

}  // namespace claspplan::perception
