#include "examples/curve_file.hpp"

#include "perception/file_io.hpp"
#include "perception/input_error.hpp"

namespace claspplan::cli {

servo::Points read_curve_file(const std::string& path, bool closed) {
  servo::Points points = perception::read_xyz(path);  // x y z per line, '#' comments, validated
  if (closed && points.size() > 1 && points.front() == points.back()) points.pop_back();
  as_input_error([&] { servo::validate_curve(points, closed, path); });
  return points;
}

}  // namespace claspplan::cli
