// The one exception type that means "the user's input is bad" (exit 2 in the command line).
//
// Readers of files, parsers of scenarios, robots and cameras, and option checks throw InputError.
// Any other exception, std::invalid_argument from an internal precondition included, is an
// internal failure (exit 3): a run must never blame the user for its own bugs. InputError derives
// from std::invalid_argument, so callers that catch that keep working.
#pragma once

#include <stdexcept>
#include <string>
#include <utility>

namespace claspplan {

class InputError : public std::invalid_argument {
 public:
  using std::invalid_argument::invalid_argument;
};

/// Runs `f`, turning any std::invalid_argument it throws into an InputError with the same message:
/// for checks shared by user input and internal data (a mesh, a curve, a joint vector) called on
/// what the user gave.
template <typename F>
decltype(auto) as_input_error(F&& f) {
  try {
    return std::forward<F>(f)();
  } catch (const InputError&) {
    throw;
  } catch (const std::invalid_argument& e) {
    throw InputError(e.what());
  }
}

/// The text on one line (newlines as spaces, no trailing spaces): messages are one line.
inline std::string one_line(std::string s) {
  for (char& c : s)
    if (c == '\n' || c == '\r') c = ' ';
  while (!s.empty() && s.back() == ' ') s.pop_back();
  return s;
}

}  // namespace claspplan
