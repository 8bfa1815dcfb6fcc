// One libFuzzer target: CLASPPLAN_FUZZ_TARGET names the reader it feeds (fuzz_inputs.hpp).
#include <cstddef>
#include <cstdint>
#include <stdexcept>
#include <string>

#include "test/fuzz/fuzz_inputs.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  try {
    claspplan::fuzz::parse_input(CLASPPLAN_FUZZ_TARGET,
                                 std::string(reinterpret_cast<const char*>(data), size));
  } catch (const std::invalid_argument&) {
    // A clean input error (exit 2). Any other exception escapes: libFuzzer reports it as a crash.
  }
  return 0;
}
