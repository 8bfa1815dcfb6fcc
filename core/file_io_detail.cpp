#include "core/file_io_detail.hpp"

#include <cctype>
#include <cerrno>
#include <cstdlib>
#include <filesystem>
#include <iomanip>
#include <stdexcept>

#include "core/input_error.hpp"

namespace claspplan::file_io_detail {

[[noreturn]] void fail(const std::string& path, const std::string& message) {
  throw InputError(path + ": " + message);
}

std::string read_all(const std::string& path) {
  std::error_code ec;
  if (!std::filesystem::exists(path, ec)) fail(path, "file not found");
  if (!std::filesystem::is_regular_file(path, ec)) fail(path, "not a regular file");
  std::ifstream in(path, std::ios::binary);
  if (!in) fail(path, "cannot open the file");
  return std::string((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
}

void require_data(const std::string& path, const std::string& data) {
  if (data.empty()) fail(path, "empty file");
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

void strip_comment(std::string& line) {
  const size_t hash = line.find('#');
  if (hash != std::string::npos) line.resize(hash);
}

// Splits a line into whitespace- (and optionally comma-) separated tokens.
std::vector<std::string> split(const std::string& line, bool commas) {
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

void check_point(const std::string& path, const Eigen::Vector3d& p, long long index) {
  if (!p.allFinite())
    fail(path, "point " + std::to_string(index) + " has a NaN or infinite coordinate");
}

void fan(std::vector<Eigen::Vector3i>& tris, const std::vector<long long>& face, long long nv,
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

std::ofstream open_out(const std::string& path, bool binary) {
  std::ofstream out(path, binary ? std::ios::binary : std::ios::out);
  if (!out) throw std::runtime_error(path + ": cannot write the file");
  out << std::setprecision(17);
  return out;
}

void finish(std::ofstream& out, const std::string& path) {
  out.flush();
  if (!out) throw std::runtime_error(path + ": write failed");
}

}  // namespace claspplan::file_io_detail
