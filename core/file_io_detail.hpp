// Internals shared by the readers and writers of file_io.hpp (not installed): the size limit,
// the one-line errors naming the file, tokenizing, number parsing, point and face checks, and the
// plumbing of the writers.
#pragma once

#include <algorithm>
#include <array>
#include <fstream>
#include <string>
#include <vector>

#include "core/file_io.hpp"
#include "core/mesh.hpp"

namespace claspplan::file_io_detail {

constexpr long long kMaxCount = 50'000'000;

/// Throws InputError "<path>: <message>".
[[noreturn]] void fail(const std::string& path, const std::string& message);

/// The whole file; fails when it is missing, not a regular file or unreadable.
std::string read_all(const std::string& path);

/// Fails when a file's contents are empty (every parser starts with it).
void require_data(const std::string& path, const std::string& data);

std::string lower(std::string s);

/// The lower-case extension of a path, with its dot.
std::string extension(const std::string& path);

bool is_space(char c);

// Splits a line into whitespace- (and optionally comma-) separated tokens.
std::vector<std::string> split(const std::string& line, bool commas = false);

// Cuts a '#' comment off a line (OBJ, OFF and XYZ files).
void strip_comment(std::string& line);

bool parse_double(const std::string& token, double& value);
bool parse_integer(const std::string& token, long long& value);

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

/// Fails when a point has a NaN or infinite coordinate.
void check_point(const std::string& path, const Eigen::Vector3d& p, long long index);

/// Appends a polygon as a triangle fan; fails on fewer than 3 vertices or an index outside [0, nv).
void fan(std::vector<Eigen::Vector3i>& tris, const std::vector<long long>& face, long long nv,
         const std::string& path, long long index);

/// A PCD file's points in file order with NaN points kept (PCL's "no reading"; infinite
/// coordinates fail), its grid and its VIEWPOINT values when the header has that line (unchecked).
/// May be empty. The common part of parse_pcd() and parse_sensor_cloud().
struct PcdPoints {
  PointCloud points;
  long long width = 0, height = 1;
  std::vector<std::string> viewpoint;
  bool has_viewpoint = false;
};
PcdPoints parse_pcd_points(const std::string& data, const std::string& path);

/// parse_xyz(), skipping points with a NaN coordinate when `skip_nan` (then the result may be
/// empty).
PointCloud parse_xyz_points(const std::string& data, const std::string& path, bool skip_nan);

/// parse_ply(), keeping vertices with a NaN coordinate when `keep_nan` (infinite ones still fail).
GeometryFile parse_ply_file(const std::string& data, const std::string& path, bool keep_nan);

/// Writers: an output stream at full double precision; throws std::runtime_error if it cannot be
/// opened.
std::ofstream open_out(const std::string& path, bool binary);

template <class T>
void put(std::ofstream& out, T v) {
  out.write(reinterpret_cast<const char*>(&v), sizeof(T));
}

/// Flushes; throws std::runtime_error when writing failed.
void finish(std::ofstream& out, const std::string& path);

}  // namespace claspplan::file_io_detail
