#include "examples/command.hpp"

#include <exception>
#include <iostream>

#include "perception/input_error.hpp"

namespace claspplan::cli {

void print_json(const nlohmann::json& object) {
  std::cout << object.dump(2) << std::endl;
}

void progress(const std::string& message) {
  std::cerr << message << std::endl;
}

// One line on stderr and, with --json, one object on stdout, so scripts always get JSON.
int report_failure(int code, const std::string& reason, bool json) {
  const std::string line = one_line(reason);
  std::cerr << "claspplan: error: " << line << "\n";
  if (json) print_json({{"error", line}, {"exit_code", code}});
  return code;
}

int run_action(const Action& action, bool json) {
  try {
    return action ? action() : kOk;
  } catch (const InputError& e) {
    return report_failure(kBadInput, e.what(), json);
  } catch (const std::exception& e) {
    // Not the user's fault: a broken internal precondition (std::invalid_argument too) or a bug.
    return report_failure(kInternalError, std::string("internal error: ") + e.what(), json);
  } catch (...) {
    return report_failure(kInternalError, "internal error: an unknown exception", json);
  }
}

}  // namespace claspplan::cli
