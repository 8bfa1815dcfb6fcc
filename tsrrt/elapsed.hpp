// Wall-clock seconds, for the phase timings of a clasp run (ClaspTimings) and its time limits.
#pragma once

#include <chrono>

namespace claspplan::tsrrt {

using Clock = std::chrono::steady_clock;

/// Seconds from t until now.
inline double since(Clock::time_point t) {
  return std::chrono::duration<double>(Clock::now() - t).count();
}

}  // namespace claspplan::tsrrt
