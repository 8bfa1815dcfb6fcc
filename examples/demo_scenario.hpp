// The embedded default scenario of `claspplan demo` (a copy of one of examples/scenarios/, taken
// at build time, so the demo runs from any directory).
#pragma once

namespace claspplan::cli {

extern const char* const kDemoScenarioName;
extern const char* const kDemoScenarioText;

}  // namespace claspplan::cli
