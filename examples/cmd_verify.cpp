// `claspplan verify RESULT.json [--json]`: the secure-clasp check again, on a saved result alone
// (its robot, final configuration, loop and object collision mesh): the paper's random motions
// (Sec. V-A), then the escape search and the gravity and approach pulls (escape_search.hpp).
#include <cstdio>

#include "examples/command.hpp"
#include "examples/result_file.hpp"
#include "examples/run_scenario.hpp"
#include "robots/robot_model.hpp"
#include "tsrrt/clasp_setup.hpp"
#include "tsrrt/secure_clasp.hpp"

namespace claspplan::cli {
namespace {

struct VerifyOptions {
  std::string result;
  tsrrt::SecureClaspOptions check;
  bool seed_given = false;
  bool json = false;
};

int run_verify(VerifyOptions o) {
  check_verification_budget(o.check, "--sequences", "--motions");
  const ResultFile r = read_result_file(o.result);
  if (!o.seed_given && r.seed) o.check.seed = *r.seed;

  const tsrrt::SecureClaspReport v = tsrrt::check_secure_clasp(
      r.model, r.object_vertices, r.object_triangles, r.final_q, r.loop, o.check);
  if (o.json) {
    nlohmann::json j = verification_json(v);
    j["open_linking"] = v.open_linking;
    j["virtual_linking"] = v.virtual_linking;
    print_json(j);
  } else if (v.start_in_collision) {
    std::printf("not secure: the hand already touches the object in the final pose\n");
  } else {
    std::printf("%s: %s\n", v.secure ? "secure" : "not secure",
                v.secure ? "no stage freed the object" : tsrrt::insecure_reason(v).c_str());
    for (const auto& stage : v.stages)
      std::printf("  %-14s %s (%d %s)\n", stage.name.c_str(),
                  !stage.ran     ? "not run"
                  : stage.passed ? "held"
                                 : "freed the object",
                  stage.iterations,
                  stage.name == "random_motions" ? "random motions" : "search iterations");
    std::printf("|Lk| of the open finger curves with the loop: %.3f to %.3f; VLk %.3f to %.3f\n",
                v.min_open_linking, v.max_open_linking, v.min_virtual_linking,
                v.max_virtual_linking);
  }
  return v.secure ? kOk : kNoAnswer;
}

}  // namespace

void add_verify_command(CLI::App& app, Action& action) {
  auto o = std::make_shared<VerifyOptions>();
  CLI::App* cmd = app.add_subcommand("verify", command_description("verify"));
  cmd->add_option("RESULT", o->result, "a result.json written by claspplan run")->required();
  cmd->add_option("--sequences", o->check.sequences, "sequences of random motions")
      ->check(CLI::Range(1, 1000))
      ->capture_default_str();
  cmd->add_option("--motions", o->check.motions, "random motions per sequence")
      ->check(CLI::Range(1, 100000))
      ->capture_default_str();
  cmd->add_option("--near-hand", o->check.near_hand,
                  "test only the object's triangles within this of the closed hand, and the "
                  "loop's tube (m; 0: the whole object)")
      ->check(CLI::Range(0.0, 10.0))
      ->capture_default_str();
  cmd->add_option("--seed", o->check.seed, "random seed (default: the result's)");
  cmd->add_option("--threads", o->check.threads, "parallel sequences (0: all cores)")
      ->check(CLI::Range(0, 64))
      ->capture_default_str();
  cmd->add_flag("--json", o->json, "print one JSON object instead of the summary");
  cmd->callback([o, cmd, &action] {
    o->seed_given = cmd->count("--seed") > 0;
    action = [o] { return run_verify(*o); };
  });
}

}  // namespace claspplan::cli
