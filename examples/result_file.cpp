#include "examples/result_file.hpp"

#include <cmath>
#include <fstream>
#include <stdexcept>

#include <nlohmann/json.hpp>

#include "core/input_error.hpp"

namespace claspplan::cli {
namespace {

// Typed access to result.json, naming the file and key in every error.
class ResultReader {
 public:
  ResultReader(const std::string& text, const std::string& path) : path_(path) {
    try {
      j_ = nlohmann::json::parse(text);
    } catch (const nlohmann::json::exception& e) {
      throw InputError(path + ": not valid JSON (" + std::string(e.what()) + ")");
    }
    if (!j_.is_object()) throw InputError(path + ": expected a JSON object");
  }

  const nlohmann::json& at(const std::string& key) const {
    if (!j_.contains(key)) fail(key, "missing (is this a claspplan result.json?)");
    return j_[key];
  }

  [[noreturn]] void fail(const std::string& key, const std::string& what) const {
    throw InputError(path_ + ": " + key + ": " + what);
  }

  double number(const nlohmann::json& v, const std::string& key) const {
    if (!v.is_number()) fail(key, "expected numbers");
    const double x = v.get<double>();
    if (!std::isfinite(x)) fail(key, "not finite");
    return x;
  }

  Eigen::Vector3d point(const nlohmann::json& p, const std::string& key) const {
    if (!p.is_array() || p.size() != 3) fail(key, "expected [x, y, z] entries");
    return Eigen::Vector3d(number(p[0], key), number(p[1], key), number(p[2], key));
  }

  std::vector<Eigen::Vector3d> points(const nlohmann::json& list, const std::string& key) const {
    if (!list.is_array()) fail(key, "expected a list of [x, y, z]");
    std::vector<Eigen::Vector3d> out;
    for (const auto& p : list) out.push_back(point(p, key));
    return out;
  }

  // A configuration of the model.
  Eigen::VectorXd configuration(const nlohmann::json& v, const robots::RobotModel& model,
                                const std::string& key) const {
    if (!v.is_array() || static_cast<int>(v.size()) != model.dof()) {
      fail(key, "expected " + std::to_string(model.dof()) + " joint values for " + model.name);
    }
    Eigen::VectorXd q(model.dof());
    for (int i = 0; i < model.dof(); ++i) q[i] = number(v[i], key);
    return q;
  }

  const nlohmann::json& json() const { return j_; }

 private:
  std::string path_;
  nlohmann::json j_;
};

void read_object_mesh(const ResultReader& r, ResultFile& out) {
  const nlohmann::json& mesh = r.at("object_mesh");
  if (!mesh.is_object() || !mesh.contains("vertices") || !mesh.contains("triangles")) {
    r.fail("object_mesh", "expected {vertices, triangles}");
  }
  out.object_vertices = r.points(mesh["vertices"], "object_mesh.vertices");
  for (const auto& t : mesh["triangles"]) {
    if (!t.is_array() || t.size() != 3 || !t[0].is_number_integer() || !t[1].is_number_integer() ||
        !t[2].is_number_integer()) {
      r.fail("object_mesh.triangles", "expected [i, j, k] vertex indices");
    }
    const Eigen::Vector3i triangle(t[0].get<int>(), t[1].get<int>(), t[2].get<int>());
    if (triangle.minCoeff() < 0 ||
        triangle.maxCoeff() >= static_cast<int>(out.object_vertices.size()))
      r.fail("object_mesh.triangles", "a vertex index is out of range");
    out.object_triangles.push_back(triangle);
  }
  if (out.object_triangles.empty()) r.fail("object_mesh.triangles", "no triangle");
}

void read_path(const ResultReader& r, ResultFile& out) {
  const nlohmann::json& env = r.at("environment");
  if (!env.is_object() || !env.contains("boxes") || !env["boxes"].is_array())
    r.fail("environment", "expected {boxes: [...]}");
  for (const auto& b : env["boxes"]) {
    if (!b.is_object() || !b.contains("size") || !b.contains("position") || !b.contains("rotation"))
      r.fail("environment.boxes", "expected {size, position, rotation}");
    const auto rows = r.points(b["rotation"], "environment.boxes.rotation");
    if (rows.size() != 3) r.fail("environment.boxes.rotation", "expected 3 rows");
    tsrrt::EnvironmentBox box;
    for (int row = 0; row < 3; ++row) box.pose.linear().row(row) = rows[row].transpose();
    box.pose.translation() = r.point(b["position"], "environment.boxes.position");
    box.size = r.point(b["size"], "environment.boxes.size");
    out.environment.push_back(box);
  }
  const nlohmann::json& waypoints = r.at("waypoints");
  if (!waypoints.is_array()) r.fail("waypoints", "expected a list of configurations");
  for (const auto& q : waypoints)
    out.waypoints.push_back(r.configuration(q, out.model, "waypoints"));
}

}  // namespace

ResultFile read_result_file(const std::string& path, bool with_path) {
  std::ifstream in(path, std::ios::binary);
  if (!in) throw InputError(path + ": cannot open result file");
  const std::string text((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  return parse_result_file(text, path, with_path);
}

ResultFile parse_result_file(const std::string& text, const std::string& path, bool with_path) {
  const ResultReader r(text, path);
  ResultFile out;
  if (!r.at("robot").is_string()) r.fail("robot", "expected a robot name or path");
  out.robot = r.at("robot").get<std::string>();
  out.model = robots::load_robot(out.robot);
  out.final_q = r.configuration(r.at("final_q"), out.model, "final_q");
  out.loop = r.points(r.at("loop"), "loop");
  as_input_error([&] { servo::validate_curve(out.loop, true, path + ": loop"); });
  read_object_mesh(r, out);
  if (r.json().contains("seed") && r.json()["seed"].is_number_unsigned()) {
    out.seed = r.json()["seed"].get<std::uint64_t>();
  }
  if (with_path) read_path(r, out);
  return out;
}

}  // namespace claspplan::cli
