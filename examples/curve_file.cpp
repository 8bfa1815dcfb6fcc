#include "examples/curve_file.hpp"

#include "core/file_io.hpp"
#include "core/input_error.hpp"

namespace claspplan::cli {
namespace {

servo::Points checked_curve(servo::Points points, const std::string& path, bool closed) {
  if (closed && points.size() > 1 && points.front() == points.back()) points.pop_back();
  as_input_error([&] { servo::validate_curve(points, closed, path); });
  return points;
}

}  // namespace

servo::Points read_curve_file(const std::string& path, bool closed) {
  // x y z per line, '#' comments, validated
  return checked_curve(read_xyz(path), path, closed);
}

servo::Points parse_curve_text(const std::string& text, const std::string& name, bool closed) {
  return checked_curve(parse_xyz(text, name), name, closed);
}

}  // namespace claspplan::cli
