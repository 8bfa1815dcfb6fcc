#include "examples/curve_file.hpp"

#include <cmath>
#include <cstdlib>
#include <fstream>
#include <sstream>

namespace claspplan::cli {
namespace {

// Parses a whole token as a finite double; strtod alone would accept "nan", "inf" and "1.5abc".
bool parse_finite(const std::string& token, double& value) {
  char* end = nullptr;
  value = std::strtod(token.c_str(), &end);
  return end == token.c_str() + token.size() && !token.empty() && std::isfinite(value);
}

}  // namespace

servo::Points read_curve_file(const std::string& path, bool closed) {
  std::ifstream in(path);
  if (!in) throw std::invalid_argument(path + ": cannot open curve file");
  servo::Points points;
  std::string line;
  for (int number = 1; std::getline(in, line); ++number) {
    line = line.substr(0, line.find('#'));
    std::istringstream fields(line);
    std::string token;
    std::vector<double> values;
    while (fields >> token) {
      double v = 0.0;
      if (!parse_finite(token, v)) {
        throw std::invalid_argument(path + ":" + std::to_string(number) + ": '" + token +
                                    "' is not a finite number");
      }
      values.push_back(v);
    }
    if (values.empty()) continue;
    if (values.size() != 3) {
      throw std::invalid_argument(path + ":" + std::to_string(number) +
                                  ": expected 3 numbers (x y z), got " +
                                  std::to_string(values.size()));
    }
    points.emplace_back(values[0], values[1], values[2]);
  }
  if (in.bad()) throw std::invalid_argument(path + ": read error");
  if (closed && points.size() > 1 && points.front() == points.back()) points.pop_back();
  servo::validate_curve(points, closed, path);
  return points;
}

}  // namespace claspplan::cli
