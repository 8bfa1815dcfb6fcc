// The secure-clasp check (paper Sec. V-A, 10 sequences x 500 motions) on the purse clasped by the
// SDH (planned once, seed 1): the reference check of the tests (the whole object mesh, every
// sequence to its end) against tsrrt::check_secure_clasp, on one core and on all cores, and
// against a SecureClaspChecker that keeps the object's geometry between checks; these run the
// random motions alone (escape_stages off). BM_EscapeSearch: the escape stages alone (no random
// motions).
#include <memory>

#include <benchmark/benchmark.h>

#include "test/support/purse_request.hpp"
#include "test/support/reference_secure_clasp.hpp"

namespace claspplan::test {
namespace {

struct Clasped {
  tsrrt::ClaspRequest request = floor_request(purse(), "kr5_sdh", 1);
  tsrrt::ClaspResult result = tsrrt::plan_clasp(request);
};

const Clasped& clasped_purse() {
  static const auto clasped = std::make_unique<Clasped>();
  return *clasped;
}

// Runs `check(robot, vertices, triangles, q, loop, options)` on the purse's clasp, as often as
// the benchmark asks.
template <typename Check>
void run(benchmark::State& state, Check check, bool escape_stages = false) {
  const tsrrt::ClaspResult& r = clasped_purse().result;
  if (!r.verified) {
    state.SkipWithError("the purse was not clasped");
    return;
  }
  tsrrt::SecureClaspOptions o;
  o.threads = static_cast<int>(state.range(0));
  o.escape_stages = escape_stages;
  if (escape_stages) o.sequences = 0;
  const auto& m = r.collision_mesh;
  bool secure = false;
  for (auto _ : state) {
    secure = check(*clasped_purse().request.robot, m.vertices, m.triangles, r.motion.final_q,
                   r.chosen_loop()->points, o)
                 .secure;
  }
  if (!secure) state.SkipWithError("the clasp is not secure");
}

void BM_SecureClaspReference(benchmark::State& state) {
  run(state, reference_secure_clasp);
}
BENCHMARK(BM_SecureClaspReference)->Arg(1)->Iterations(2)->Unit(benchmark::kMillisecond);

void BM_SecureClasp(benchmark::State& state) {
  run(state, tsrrt::check_secure_clasp);
}
// Threads: 1, and 0 = all cores.
BENCHMARK(BM_SecureClasp)->Arg(1)->Arg(0)->Iterations(5)->Unit(benchmark::kMillisecond);

// What a search pays per clasp candidate: the object's geometry built once (SecureClaspChecker).
void BM_SecureClaspChecker(benchmark::State& state) {
  std::unique_ptr<tsrrt::SecureClaspChecker> checker;
  run(state,
      [&](const robots::RobotModel& robot, const auto& vertices, const auto& triangles,
          const Eigen::VectorXd& q, const servo::Points& loop, const tsrrt::SecureClaspOptions& o) {
        if (!checker) {
          checker = std::make_unique<tsrrt::SecureClaspChecker>(robot, vertices, triangles, o);
          checker->check(q, loop);  // builds the geometry
        }
        return checker->check(q, loop);
      });
}
BENCHMARK(BM_SecureClaspChecker)->Arg(1)->Arg(0)->Iterations(5)->Unit(benchmark::kMillisecond);

// The escape stages (escape search, gravity, approach) on the secure clasp: each runs its whole
// budget. Single-threaded whatever the argument.
void BM_EscapeSearch(benchmark::State& state) {
  run(state, tsrrt::check_secure_clasp, true);
}
BENCHMARK(BM_EscapeSearch)->Arg(1)->Iterations(5)->Unit(benchmark::kMillisecond);

}  // namespace
}  // namespace claspplan::test
