// Inputs that once crashed a reader under the fuzzers (test/fuzz/regressions/<target>/<file>),
// fed again to the same entry point (test/fuzz/fuzz_inputs.hpp): each must now be a clean input
// error, std::invalid_argument (the command line's exit 2).
#include <filesystem>
#include <fstream>
#include <iterator>
#include <stdexcept>
#include <string>

#include <gtest/gtest.h>

#include "test/fuzz/fuzz_inputs.hpp"

namespace fs = std::filesystem;

TEST(FuzzRegressions, EveryCommittedCrashIsACleanInputError) {
  int inputs = 0;
  for (const auto& target : fs::directory_iterator(CLASPPLAN_FUZZ_REGRESSIONS)) {
    for (const auto& file : fs::directory_iterator(target.path())) {
      std::ifstream in(file.path(), std::ios::binary);
      const std::string data((std::istreambuf_iterator<char>(in)),
                             std::istreambuf_iterator<char>());
      SCOPED_TRACE(file.path().string());
      EXPECT_THROW(claspplan::fuzz::parse_input(target.path().filename().string(), data),
                   std::invalid_argument);
      ++inputs;
    }
  }
  EXPECT_GT(inputs, 0);
}

TEST(FuzzRegressions, EveryTargetHasASeedCorpus) {
  for (const std::string& target : claspplan::fuzz::target_names()) {
    const fs::path dir = fs::path(CLASPPLAN_FUZZ_REGRESSIONS).parent_path() / "corpus" / target;
    EXPECT_TRUE(fs::is_directory(dir) && !fs::is_empty(dir)) << dir;
  }
}
