// Curve files: one `x y z` per line (metres; the .xyz format: `#` comments, blank lines and
// further columns ignored).
// A closed curve's last point joins its first; a repeated first point at the end is dropped.
#pragma once

#include <string>

#include "core/input_error.hpp"
#include "servo/linking.hpp"

namespace claspplan::cli {

/// Reads and validates a curve file (servo::validate_curve). Throws InputError with the
/// file name and line for missing files, malformed lines, NaN/Inf, too few points or zero-length
/// segments.
servo::Points read_curve_file(const std::string& path, bool closed);
/// The same from the file's text; `name` stands for the path in messages.
servo::Points parse_curve_text(const std::string& text, const std::string& name, bool closed);

}  // namespace claspplan::cli
