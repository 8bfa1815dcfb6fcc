// The embedded default scenario of `claspplan demo` (a copy of one of examples/scenarios/ and of
// the depth files it reads, taken at build time, so the demo runs from any directory).
#pragma once

#include <cstddef>
#include <vector>

namespace claspplan::cli {

/// A file embedded in the program: its path relative to examples/, and its bytes.
struct EmbeddedFile {
  const char* path;
  const unsigned char* data;
  std::size_t size;
};

extern const char* const kDemoScenarioName;
extern const char* const kDemoScenarioText;  ///< its paths are relative to examples/scenarios/
extern const std::vector<EmbeddedFile> kDemoFiles;

}  // namespace claspplan::cli
