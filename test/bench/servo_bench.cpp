// Kernels of the linking core (issue 2 budgets in the comments).
#include <memory>

#include <benchmark/benchmark.h>

#include "robots/robot_model.hpp"
#include "servo/clasp_controller.hpp"
#include "servo/linking.hpp"
#include "test/support/curves.hpp"

namespace claspplan::test {
namespace {

// Gauss sum throughput: at least 10 million segment pairs per second on one core.
void BM_GaussSum(benchmark::State& state) {
  const int n = static_cast<int>(state.range(0));
  const Curve a = torus_link_component(3, 0, n);
  const Curve b = torus_link_component(3, 1, n);
  for (auto _ : state) benchmark::DoNotOptimize(servo::gauss_linking(a, true, b, true));
  state.SetItemsProcessed(state.iterations() * n * n);  // segment pairs
}
BENCHMARK(BM_GaussSum)->Arg(10)->Arg(100)->Arg(1000);

// A 100-segment loop and a 9-segment finger loop: the crossing count within 5 µs.
Curve hundred_segment_loop() {
  return circle({0, 0, 0}, 0.1, Eigen::Vector3d::UnitX(), Eigen::Vector3d::UnitY(), 100);
}
Curve finger_curve(double span, double shift = 0.0) {
  Curve c;
  for (int i = 0; i < 9; ++i) {
    const double t = kPi - span / 2.0 + span * i / 8.0;
    c.emplace_back(0.1 + 0.04 * std::cos(t), shift, 0.04 * std::sin(t));
  }
  return c;
}

void BM_LinkingNumberCrossings(benchmark::State& state) {
  const Curve loop = hundred_segment_loop();
  const Curve finger = finger_curve(5.0);  // 9 points: closed by the cord, a 9-segment loop
  for (auto _ : state) benchmark::DoNotOptimize(servo::linking_number(loop, finger));
}
BENCHMARK(BM_LinkingNumberCrossings);

void BM_LinkingNumberGaussSum(benchmark::State& state) {
  const Curve loop = hundred_segment_loop();
  const Curve finger = finger_curve(5.0);
  for (auto _ : state) benchmark::DoNotOptimize(servo::gauss_linking(loop, true, finger, true));
}
BENCHMARK(BM_LinkingNumberGaussSum);

// VLk of four 8-segment finger curves with a 100-segment loop; with the gradient within 3×.
std::vector<Curve> four_fingers() {
  return {finger_curve(5.0, -0.01), finger_curve(4.5, 0.0), finger_curve(4.0, 0.01),
          finger_curve(3.0, 0.02)};
}

void BM_VirtualLinking4Fingers(benchmark::State& state) {
  const Curve loop = hundred_segment_loop();
  const auto fingers = four_fingers();
  for (auto _ : state) {
    double sum = 0.0;
    for (const auto& f : fingers) sum += servo::virtual_linking(loop, f).value;
    benchmark::DoNotOptimize(sum);
  }
}
BENCHMARK(BM_VirtualLinking4Fingers);

void BM_VirtualLinkingWithGradient4Fingers(benchmark::State& state) {
  const Curve loop = hundred_segment_loop();
  const auto fingers = four_fingers();
  std::vector<Eigen::Vector3d> grad;
  for (auto _ : state) {
    double sum = 0.0;
    for (const auto& f : fingers) {
      const servo::VirtualLinking v = servo::virtual_linking(loop, f);
      servo::virtual_linking_gradient(v, f, grad);
      sum += v.value + grad[0].x();
    }
    benchmark::DoNotOptimize(sum);
  }
}
BENCHMARK(BM_VirtualLinkingWithGradient4Fingers);

// The open-curve Gauss integral with its gradient (paper Fig. 6), for comparison.
void BM_OpenGaussWithGradient4Fingers(benchmark::State& state) {
  const Curve loop = hundred_segment_loop();
  const auto fingers = four_fingers();
  std::vector<Eigen::Vector3d> grad;
  for (auto _ : state) {
    double sum = 0.0;
    for (const auto& f : fingers) sum += servo::gauss_linking_gradient(loop, true, f, false, grad);
    benchmark::DoNotOptimize(sum);
  }
}
BENCHMARK(BM_OpenGaussWithGradient4Fingers);

}  // namespace
}  // namespace claspplan::test

namespace claspplan::test {
namespace {

// One TS-CONTROL step (Alg. 4) for kr5_icub, 21 joints: FK and finger-curve Jacobians, the three
// features with their Jacobians, and the hierarchy. Budget: 50 µs. The ring passes through the
// hand, so the linking task is active.
// kr5_icub at home with a 15 cm ring through its open hand and 12 clasp targets on the ring.
struct IcubRing {
  robots::RobotModel model = robots::load_robot("kr5_icub");
  Eigen::Vector3d centre, forward;
  std::unique_ptr<servo::ClaspController> controller;  // refers to `model`: IcubRing stays put
  IcubRing() {
    servo::ClaspController probe(model, hundred_segment_loop(),
                                 {{Eigen::Vector3d(5, 0, 0), Eigen::Vector3d::UnitY()}});
    centre = probe.project(model.home).position;
    const servo::HandKinematics& hand = probe.hand();
    forward = hand.forward;
    const Curve ring = circle(centre + 0.15 * forward, 0.15, -forward, hand.sideways, 100);
    std::vector<ClaspTarget> targets;
    for (int i = 0; i < 12; ++i) targets.push_back({ring[i * 8], hand.sideways});
    controller = std::make_unique<servo::ClaspController>(model, ring, targets);
  }
};

void BM_ControlStepIcub(benchmark::State& state) {
  IcubRing scene;
  servo::ClaspController& controller = *scene.controller;
  for (auto _ : state) {
    controller.forget_direction();  // else the features at the same q are kept, not recomputed
    benchmark::DoNotOptimize(controller.step(scene.model.home, scene.centre, 1.0));
  }
}
BENCHMARK(BM_ControlStepIcub);

// A connect attempt's inner loop as TS-RRT runs it, kr5_icub: step from the last node, project
// the new one (its task point for the tree), 40 times. Argument 0: the features computed at the
// projection are kept for the next step (one kinematics per step); 1: recomputed there, as before
// (two per step). Time per step = real time / 40.
void BM_SearchStepsIcub(benchmark::State& state) {
  IcubRing scene;
  servo::ClaspController& controller = *scene.controller;
  const bool twice = state.range(0) == 1;
  for (auto _ : state) {
    controller.forget_direction();
    Eigen::VectorXd q = scene.model.home;
    for (int s = 0; s < 40; ++s) {
      q = controller.step(q, scene.centre + 0.15 * scene.forward, 1.0);
      benchmark::DoNotOptimize(controller.project(q).linking);
      if (twice) controller.forget_direction();
    }
  }
}
BENCHMARK(BM_SearchStepsIcub)->Arg(0)->Arg(1);

}  // namespace
}  // namespace claspplan::test
