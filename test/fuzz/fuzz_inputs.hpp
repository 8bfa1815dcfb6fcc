// The readers the fuzz targets exercise, by name: each call parses one input held in memory the
// way the command line reads that kind of file. Bad input must throw std::invalid_argument (the
// command line's exit 2); a crash, a sanitizer report, a hang or any other exception is a bug.
// The fuzz targets (fuzz_main.cpp) and the regression test of their past crashes
// (test/cli/fuzz_regression_test.cpp) share this table.
#pragma once

#include <string>
#include <vector>

namespace claspplan::fuzz {

/// depth_png, camera_yaml, pcd, ply, xyz, obj, stl, off, urdf, hand_description, scenario, curve,
/// result_json.
std::vector<std::string> target_names();

/// Parses `data` as the target's input; throws std::logic_error for an unknown target.
void parse_input(const std::string& target, const std::string& data);

}  // namespace claspplan::fuzz
