// The built-in robots' URDF and hand-description files, embedded into the library at build time
// (robots/embed_models.cmake generates the table from robots/models/), so that the binaries work
// from any directory. robots/models/ holds the source of truth.
#pragma once

#include <string>
#include <vector>

namespace claspplan::robots {

/// The text of an embedded file by its name in robots/models/ ("kr5_sdh.yaml"), or nullptr.
const char* embedded_model_file(const std::string& name);

/// The names of all embedded files, sorted.
std::vector<std::string> embedded_model_names();

}  // namespace claspplan::robots
