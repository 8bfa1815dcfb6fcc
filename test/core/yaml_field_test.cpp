// The typed YAML reader behind the scenario, hand-description and camera files: every error is one
// line naming the file, the line and the key path; absent sections read as absent keys.
#include "core/yaml_field.hpp"

#include <functional>
#include <string>

#include <gtest/gtest.h>

namespace claspplan {
namespace {

std::string error_of(const std::function<void()>& f) {
  try {
    f();
  } catch (const InputError& e) {
    return e.what();
  }
  return "";
}

const char* kText =
    "name: arm\n"
    "limits:\n"
    "  speed: 2.5\n"
    "  count: 3\n"
    "  ratio: .nan\n"
    "  word: fast\n"
    "points: [[0, 0, 1], [1, 2]]\n";

TEST(YamlField, ValuesAndTheirErrorsNameFileLineAndKey) {
  const YamlField root = YamlField::parse_map(kText, "f.yaml", "(test)");
  EXPECT_EQ(root.required("name").text(), "arm");
  EXPECT_DOUBLE_EQ(root["limits"]["speed"].number(0.0, 3.0), 2.5);
  EXPECT_EQ(root["limits"]["count"].integer(0, 10), 3);
  EXPECT_EQ(root["points"].items()[0].vector3(), Eigen::Vector3d(0, 0, 1));

  EXPECT_EQ(error_of([&] { root["limits"]["ratio"].number(); }),
            "f.yaml: line 5: limits.ratio: must be finite, got '.nan'");
  EXPECT_EQ(error_of([&] { root["limits"]["word"].number(); }),
            "f.yaml: line 6: limits.word: expected a number, got 'fast'");
  EXPECT_EQ(error_of([&] { root["limits"]["speed"].number(0.0, 1.0); }),
            "f.yaml: line 3: limits.speed: must be in [0, 1], got 2.5");
  EXPECT_EQ(error_of([&] { root["limits"]["speed"].integer(0, 9); }),
            "f.yaml: line 3: limits.speed: expected an integer, got 2.5");
  EXPECT_EQ(error_of([&] { root["points"].items()[1].vector3(); }),
            "f.yaml: line 7: points[1]: expected a list of 3 numbers");
  EXPECT_EQ(error_of([&] {
              root["limits"].only({"speed", "count", "ratio"});
            }),
            "f.yaml: line 6: limits.word: unknown key 'word'");
  EXPECT_EQ(error_of([&] { root["limits"].required("torque"); }),
            "f.yaml: line 3: limits: missing key 'torque'");
}

TEST(YamlField, AbsentSectionsReadAsAbsentKeys) {
  const YamlField root = YamlField::parse_map(kText, "f.yaml", "(test)");
  const YamlField absent = root["controller"]["gains"];
  EXPECT_FALSE(absent.present());
  EXPECT_FALSE(absent.has("p"));
  EXPECT_NO_THROW(absent.only({"p"}));
  EXPECT_EQ(absent.path(), "controller.gains");
  EXPECT_EQ(error_of([&] { root["name"]["first"]; }), "f.yaml: line 1: name: expected a mapping");
}

TEST(YamlField, MalformedTextIsOneLine) {
  const std::string broken = error_of([] { YamlField::parse_map("a: [1,\n", "b.yaml", "(x)"); });
  EXPECT_EQ(broken.rfind("b.yaml: malformed YAML: line ", 0), 0u) << broken;
  EXPECT_EQ(broken.find('\n'), std::string::npos) << broken;
  EXPECT_EQ(error_of([] { YamlField::parse_map("- 1\n- 2\n", "l.yaml", "of fields"); }),
            "l.yaml: expected a YAML mapping of fields");
  EXPECT_EQ(error_of([] { YamlField::parse_map(std::string("a\0b", 3), "n.yaml", "(x)"); }),
            "n.yaml: not a YAML text file (contains NUL bytes)");
}

}  // namespace
}  // namespace claspplan
