#include "examples/command.hpp"

#include <iostream>

namespace claspplan::cli {

void print_json(const nlohmann::json& object) {
  std::cout << object.dump(2) << std::endl;
}

void progress(const std::string& message) {
  std::cerr << message << std::endl;
}

}  // namespace claspplan::cli
