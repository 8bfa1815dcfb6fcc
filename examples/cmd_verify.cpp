// `claspplan verify RESULT.json [--json]`: the secure-clasp check (paper Sec. V-A) again, on a
// saved result alone: its robot, final configuration, loop and object collision mesh.
#include <cmath>
#include <cstdio>
#include <fstream>

#include "examples/command.hpp"
#include "examples/run_scenario.hpp"
#include "robots/robot_model.hpp"
#include "tsrrt/clasp_planning.hpp"

namespace claspplan::cli {
namespace {

struct VerifyOptions {
  std::string result;
  tsrrt::SecureClaspOptions check;
  bool seed_given = false;
  bool json = false;
};

// Typed access to result.json, naming the file and key in every error.
class ResultReader {
 public:
  explicit ResultReader(const std::string& path) : path_(path) {
    std::ifstream in(path);
    if (!in) throw std::invalid_argument(path + ": cannot open result file");
    try {
      j_ = nlohmann::json::parse(in);
    } catch (const nlohmann::json::exception& e) {
      throw std::invalid_argument(path + ": not valid JSON (" + std::string(e.what()) + ")");
    }
    if (!j_.is_object()) throw std::invalid_argument(path + ": expected a JSON object");
  }

  const nlohmann::json& at(const std::string& key) const {
    if (!j_.contains(key)) fail(key, "missing (is this a claspplan result.json?)");
    return j_[key];
  }

  [[noreturn]] void fail(const std::string& key, const std::string& what) const {
    throw std::invalid_argument(path_ + ": " + key + ": " + what);
  }

  double number(const nlohmann::json& v, const std::string& key) const {
    if (!v.is_number()) fail(key, "expected numbers");
    const double x = v.get<double>();
    if (!std::isfinite(x)) fail(key, "not finite");
    return x;
  }

  std::vector<Eigen::Vector3d> points(const nlohmann::json& list, const std::string& key) const {
    if (!list.is_array()) fail(key, "expected a list of [x, y, z]");
    std::vector<Eigen::Vector3d> out;
    for (const auto& p : list) {
      if (!p.is_array() || p.size() != 3) fail(key, "expected [x, y, z] entries");
      out.emplace_back(number(p[0], key), number(p[1], key), number(p[2], key));
    }
    return out;
  }

  const nlohmann::json& json() const { return j_; }

 private:
  std::string path_;
  nlohmann::json j_;
};

int run_verify(VerifyOptions o) {
  const ResultReader r(o.result);
  if (!r.at("robot").is_string()) r.fail("robot", "expected a robot name or path");
  const robots::RobotModel model = robots::load_robot(r.at("robot").get<std::string>());
  const nlohmann::json& final_q = r.at("final_q");
  if (!final_q.is_array() || static_cast<int>(final_q.size()) != model.dof()) {
    r.fail("final_q",
           "expected " + std::to_string(model.dof()) + " joint values for " + model.name);
  }
  Eigen::VectorXd q(model.dof());
  for (int i = 0; i < model.dof(); ++i) q[i] = r.number(final_q[i], "final_q");
  const servo::Points loop = r.points(r.at("loop"), "loop");
  servo::validate_curve(loop, true, o.result + ": loop");
  const nlohmann::json& mesh = r.at("object_mesh");
  if (!mesh.is_object() || !mesh.contains("vertices") || !mesh.contains("triangles")) {
    r.fail("object_mesh", "expected {vertices, triangles}");
  }
  const std::vector<Eigen::Vector3d> vertices = r.points(mesh["vertices"], "object_mesh.vertices");
  std::vector<Eigen::Vector3i> triangles;
  for (const auto& t : mesh["triangles"]) {
    if (!t.is_array() || t.size() != 3 || !t[0].is_number_integer() || !t[1].is_number_integer() ||
        !t[2].is_number_integer()) {
      r.fail("object_mesh.triangles", "expected [i, j, k] vertex indices");
    }
    triangles.emplace_back(t[0].get<int>(), t[1].get<int>(), t[2].get<int>());
  }
  if (!o.seed_given && r.json().contains("seed") && r.json()["seed"].is_number_unsigned()) {
    o.check.seed = r.json()["seed"].get<std::uint64_t>();
  }

  const tsrrt::SecureClaspReport v =
      tsrrt::check_secure_clasp(model, vertices, triangles, q, loop, o.check);
  if (o.json) {
    nlohmann::json j = verification_json(v);
    j["open_linking"] = v.open_linking;
    j["virtual_linking"] = v.virtual_linking;
    print_json(j);
  } else if (v.start_in_collision) {
    std::printf("not secure: the hand already touches the object in the final pose\n");
  } else {
    std::printf("%s: the object got free in %d of %d sequences of %d random motions\n",
                v.secure ? "secure" : "not secure", v.escaped_sequences, v.sequences,
                o.check.motions);
    std::printf("|Lk| of the open finger curves with the loop: %.3f to %.3f; VLk %.3f to %.3f\n",
                v.min_open_linking, v.max_open_linking, v.min_virtual_linking,
                v.max_virtual_linking);
  }
  return v.secure ? kOk : kNoAnswer;
}

}  // namespace

void add_verify_command(CLI::App& app, Action& action) {
  auto o = std::make_shared<VerifyOptions>();
  CLI::App* cmd = app.add_subcommand(
      "verify",
      "The secure-clasp check of a saved result: random translations and rotations of the object "
      "relative to the closed hand, each pursued until collision. Exit 0 secure, 1 not.");
  cmd->add_option("RESULT", o->result, "a result.json written by claspplan run")->required();
  cmd->add_option("--sequences", o->check.sequences, "sequences of random motions")
      ->check(CLI::Range(1, 1000))
      ->capture_default_str();
  cmd->add_option("--motions", o->check.motions, "random motions per sequence")
      ->check(CLI::Range(1, 100000))
      ->capture_default_str();
  cmd->add_option("--seed", o->check.seed, "random seed (default: the result's)");
  cmd->add_option("--threads", o->check.threads, "parallel sequences")
      ->check(CLI::Range(1, 64))
      ->capture_default_str();
  cmd->add_flag("--json", o->json, "print one JSON object instead of the summary");
  cmd->callback([o, cmd, &action] {
    o->seed_given = cmd->count("--seed") > 0;
    action = [o] { return run_verify(*o); };
  });
}

}  // namespace claspplan::cli
