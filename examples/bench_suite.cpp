#include "examples/bench_suite.hpp"

#include <algorithm>
#include <filesystem>
#include <regex>
#include <stdexcept>

#include "core/input_error.hpp"

namespace claspplan::cli {
namespace {

namespace fs = std::filesystem;

// Scenario files directly in `dir` whose stem matches `pattern`; names are `prefix` + stem.
std::vector<std::pair<std::string, std::string>> matching(const fs::path& dir,
                                                          const std::regex& pattern,
                                                          const std::string& prefix) {
  std::vector<std::pair<std::string, std::string>> out;
  std::error_code ec;
  if (!fs::is_directory(dir, ec)) return out;
  for (const auto& entry : fs::directory_iterator(dir)) {
    const fs::path& p = entry.path();
    if (p.extension() != ".yaml" || !std::regex_match(p.stem().string(), pattern)) continue;
    out.emplace_back(prefix + p.stem().string(), p.string());
  }
  return out;
}

}  // namespace

std::vector<double> paper_tolerances() {
  return {0.5, 0.65, 0.70, 0.75};
}

std::vector<std::string> bench_baselines() {
  return {"grasp_rrt", "ompl_two_phase"};
}

std::vector<std::string> bench_suites() {
  return {"quick", "real", "paper"};
}

std::vector<BenchCase> suite_cases(const std::string& suite, const std::string& scenarios_dir,
                                   int seeds) {
  if (seeds < 1) throw InputError("--seeds must be >= 1");
  const fs::path dir(scenarios_dir);
  const std::string hand = "(sdh|dlr|icub|armar3)";
  std::vector<std::pair<std::string, std::string>> files;
  if (suite == "quick") {
    files = matching(dir, std::regex("(purse_1|jug)_" + hand), "");
  } else if (suite == "real") {
    files = matching(dir / "real", std::regex(".*"), "real/");
  } else if (suite == "paper") {
    files = matching(dir, std::regex("(purse|bag|travelbag|lawnmower|chair)_[123]_" + hand), "");
    const auto chair = matching(dir, std::regex("chair_obstructed_" + hand), "");
    files.insert(files.end(), chair.begin(), chair.end());
  } else {
    throw InputError("unknown suite '" + suite + "' (quick, real or paper)");
  }
  if (files.empty()) {
    throw InputError("suite " + suite + ": no scenario files in " + scenarios_dir +
                     " (give the folder with --scenarios)");
  }
  std::sort(files.begin(), files.end());
  std::vector<BenchCase> cases;
  for (const auto& [name, path] : files) {
    for (int s = 1; s <= seeds; ++s)
      cases.push_back({name, path, static_cast<std::uint64_t>(s), 0.0, ""});
  }
  if (suite == "paper") {
    for (double t : paper_tolerances()) {
      for (const auto& [name, path] : files) {
        if (name.find("_1_") != std::string::npos)
          cases.push_back({name, path, 1, t, ""});  // pose 1
      }
    }
  }
  for (const auto& method : bench_baselines())
    for (const auto& [name, path] : files) cases.push_back({name, path, 1, 0.0, method});
  return cases;
}

std::vector<BenchCase> file_cases(const std::vector<std::string>& files, int seeds) {
  if (seeds < 1) throw InputError("--seeds must be >= 1");
  std::vector<BenchCase> cases;
  for (const auto& file : files) {
    std::error_code ec;
    if (!fs::is_regular_file(file, ec)) throw InputError(file + ": no such scenario file");
    for (int s = 1; s <= seeds; ++s)
      cases.push_back(
          {fs::path(file).stem().string(), file, static_cast<std::uint64_t>(s), 0.0, ""});
  }
  return cases;
}

std::vector<BenchCase> shard_cases(const std::vector<BenchCase>& cases, const std::string& shard) {
  std::smatch m;
  if (!std::regex_match(shard, m, std::regex("([0-9]{1,6})/([0-9]{1,6})"))) {
    throw InputError("--shard must be K/N, e.g. 2/8 (got '" + shard + "')");
  }
  const int k = std::stoi(m[1]), n = std::stoi(m[2]);
  if (n < 1 || k < 1 || k > n) {
    throw InputError("--shard K/N needs 1 <= K <= N (got '" + shard + "')");
  }
  std::vector<BenchCase> out;
  for (std::size_t i = static_cast<std::size_t>(k - 1); i < cases.size(); i += n) {
    out.push_back(cases[i]);
  }
  return out;
}

}  // namespace claspplan::cli
