// What a long computation throws when its caller asked it to stop: a `stop` predicate (Ctrl-C in
// Python, a user interface's cancel button) returned true between two of its steps.
#pragma once

#include <functional>
#include <stdexcept>

namespace claspplan {

class Stopped : public std::runtime_error {
 public:
  Stopped() : std::runtime_error("stopped by the caller") {}
};

/// Throws Stopped when `stop` is set and returns true.
inline void stop_point(const std::function<bool()>& stop) {
  if (stop && stop()) throw Stopped();
}

}  // namespace claspplan
