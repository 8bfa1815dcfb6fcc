// Typed reading of YAML files (scenario, hand description, camera), for the readers only (not
// installed). Every failure is a one-line InputError "<file>: line N: <key path>: <what>", so a
// user can find the offending key; values are checked to be finite and within their range.
// Header-only: robots/ uses it without linking the perception library.
#pragma once

#include <cmath>
#include <cstddef>
#include <initializer_list>
#include <set>
#include <string>
#include <utility>
#include <vector>

#include <Eigen/Core>
#include <yaml-cpp/yaml.h>

#include "core/input_error.hpp"

namespace claspplan {

/// A node of a YAML file with where it sits (file and key path), for messages.
class YamlField {
 public:
  // yaml-cpp's node for a missing key is "invalid" and throws on most queries; keep a plain
  // undefined node instead, so that absent keys can be asked about safely.
  YamlField(const YAML::Node& node, std::string file, std::string path)
      : node_(node.IsDefined() ? node : YAML::Node(YAML::NodeType::Undefined)),
        file_(std::move(file)),
        path_(std::move(path)) {}

  /// Parses `text`, whose root must be a mapping (`expected` says of what, for the message).
  static YamlField parse_map(const std::string& text, const std::string& file,
                             const std::string& expected) {
    if (text.find('\0') != std::string::npos)
      throw InputError(file + ": not a YAML text file (contains NUL bytes)");
    YAML::Node root;
    try {
      root = YAML::Load(text);
    } catch (const YAML::Exception& e) {
      throw InputError(file + ": malformed YAML: " + line_of(e.mark) + one_line(e.msg));
    }
    if (!root.IsMap()) throw InputError(file + ": expected a YAML mapping " + expected);
    return YamlField(root, file, "");
  }

  [[noreturn]] void fail(const std::string& what) const {
    const std::string line = node_.IsDefined() ? line_of(node_.Mark()) : std::string();
    throw InputError(file_ + ": " + line + (path_.empty() ? "" : path_ + ": ") + what);
  }

  const YAML::Node& node() const { return node_; }
  const std::string& path() const { return path_; }
  bool is_map() const { return node_.IsMap(); }
  bool is_list() const { return node_.IsSequence(); }
  /// Present and not `~`.
  bool present() const { return node_.IsDefined() && !node_.IsNull(); }
  bool has(const std::string& key) const { return node_.IsMap() && (*this)[key].present(); }

  /// The value under `key`, absent when this node is (check present() or use required()).
  YamlField operator[](const std::string& key) const {
    const std::string path = path_.empty() ? key : path_ + "." + key;
    if (!present()) return YamlField(YAML::Node(YAML::NodeType::Undefined), file_, path);
    if (!node_.IsMap()) fail("expected a mapping");
    return YamlField(node_[key], file_, path);
  }
  YamlField required(const std::string& key) const {
    const YamlField f = (*this)[key];
    if (!f.present()) fail("missing key '" + key + "'");
    return f;
  }

  /// The (key, value) pairs of a mapping; both carry the key in their path.
  std::vector<std::pair<YamlField, YamlField>> entries() const {
    if (!node_.IsMap()) fail("expected a mapping");
    std::vector<std::pair<YamlField, YamlField>> out;
    for (const auto& kv : node_) {
      if (!kv.first.IsScalar()) fail("a key must be a name, not a list or map");
      const std::string path = path_.empty() ? kv.first.Scalar() : path_ + "." + kv.first.Scalar();
      out.emplace_back(YamlField(kv.first, file_, path), YamlField(kv.second, file_, path));
    }
    return out;
  }

  /// Rejects keys outside `keys`: a typo must not fall back silently to a default.
  void only(std::initializer_list<const char*> keys) const {
    if (!present()) return;
    const std::set<std::string> ok(keys.begin(), keys.end());
    for (const auto& [key, value] : entries())
      if (!ok.count(key.node().Scalar())) key.fail("unknown key '" + key.node().Scalar() + "'");
  }

  /// The entries of a list; `what` names one entry for the message when this is not a list.
  std::vector<YamlField> items(const std::string& what = "entries") const {
    if (!node_.IsSequence()) fail("expected a list of " + what);
    std::vector<YamlField> out;
    for (std::size_t i = 0; i < node_.size(); ++i)
      out.emplace_back(node_[i], file_, path_ + "[" + std::to_string(i) + "]");
    return out;
  }

  double number(double lo = -INFINITY, double hi = INFINITY) const {
    if (!node_.IsScalar()) fail("expected a number");
    double v = 0.0;
    try {
      v = node_.as<double>();
    } catch (const YAML::Exception&) {
      fail("expected a number, got '" + node_.Scalar() + "'");
    }
    if (!std::isfinite(v)) fail("must be finite, got '" + node_.Scalar() + "'");
    if (v < lo || v > hi)
      fail("must be in [" + text_of(lo) + ", " + text_of(hi) + "], got " + node_.Scalar());
    return v;
  }

  long long integer(long long lo, long long hi) const {
    const double v = number();
    if (v != std::floor(v)) fail("expected an integer, got " + node_.Scalar());
    if (v < static_cast<double>(lo) || v > static_cast<double>(hi))
      fail("must be in [" + std::to_string(lo) + ", " + std::to_string(hi) + "], got " +
           node_.Scalar());
    return static_cast<long long>(v);
  }

  bool boolean() const {
    if (!node_.IsScalar()) fail("expected true or false");
    try {
      return node_.as<bool>();
    } catch (const YAML::Exception&) {
      fail("expected true or false, got '" + node_.Scalar() + "'");
    }
  }

  /// A scalar; with `non_empty` the empty string is refused.
  std::string text(bool non_empty = true) const {
    if (!node_.IsScalar() || (non_empty && node_.Scalar().empty()))
      fail(non_empty ? "expected a non-empty name" : "expected a string");
    return node_.Scalar();
  }

  /// A list of finite numbers; with `size` > 0 exactly that many.
  std::vector<double> numbers(std::size_t size = 0) const {
    std::vector<double> out;
    for (const YamlField& f : items("numbers")) out.push_back(f.number());
    if (size && out.size() != size)
      fail("expected " + std::to_string(size) + " numbers, got " + std::to_string(out.size()));
    return out;
  }

  Eigen::Vector3d vector3() const {
    if (!node_.IsSequence() || node_.size() != 3) fail("expected a list of 3 numbers");
    const std::vector<double> v = numbers(3);
    return {v[0], v[1], v[2]};
  }

  /// yaml-cpp's own position text ("line N: "), empty when unknown.
  static std::string line_of(const YAML::Mark& mark) {
    return mark.is_null() || mark.line < 0 ? "" : "line " + std::to_string(mark.line + 1) + ": ";
  }

 private:
  static std::string text_of(double v) {
    if (std::isinf(v)) return v < 0 ? "-inf" : "inf";
    std::string s = std::to_string(v);
    while (s.size() > 1 && s.back() == '0') s.pop_back();
    if (!s.empty() && s.back() == '.') s.pop_back();
    return s;
  }

  YAML::Node node_;
  std::string file_;
  std::string path_;
};

}  // namespace claspplan
