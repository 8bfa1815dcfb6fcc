// Kernels of the robots library (issue 4 budgets in the comments).
#include <algorithm>
#include <chrono>
#include <random>
#include <vector>

#include <benchmark/benchmark.h>

#include "robots/collision_world.hpp"
#include "robots/kinematics.hpp"
#include "test/robots/test_meshes.hpp"

namespace claspplan::robots {
namespace {

const RobotModel& icub() {
  static const RobotModel model = load_robot("kr5_icub");
  return model;
}

std::vector<Eigen::VectorXd> random_configurations(const RobotModel& m, int n, uint64_t seed) {
  std::mt19937_64 rng(seed);
  std::vector<Eigen::VectorXd> qs;
  for (int k = 0; k < n; ++k) {
    Eigen::VectorXd q(m.dof());
    for (int i = 0; i < m.dof(); ++i)
      q[i] = std::uniform_real_distribution<double>(m.joints[i].lower, m.joints[i].upper)(rng);
    qs.push_back(q);
  }
  return qs;
}

// FK plus every finger-curve point and its 3 × 21 Jacobian for kr5_icub (4 curves × 11 points):
// at most 20 µs.
void BM_IcubFkAndFingerCurveJacobians(benchmark::State& state) {
  const RobotModel& m = icub();
  RobotData data(m);
  FingerCurvesData curves;
  const auto qs = random_configurations(m, 64, 7);
  size_t k = 0;
  for (auto _ : state) {
    finger_curves(m, qs[k++ % qs.size()], data, curves, true);
    benchmark::DoNotOptimize(curves.jacobians[0][0].data());
  }
}
BENCHMARK(BM_IcubFkAndFingerCurveJacobians);

void BM_IcubForwardKinematics(benchmark::State& state) {
  const RobotModel& m = icub();
  RobotData data(m);
  const auto qs = random_configurations(m, 64, 7);
  size_t k = 0;
  for (auto _ : state) {
    forward_kinematics(m, qs[k++ % qs.size()], data);
    benchmark::DoNotOptimize(data.link_poses.back().data());
  }
}
BENCHMARK(BM_IcubForwardKinematics);

// A 30,000-triangle ring (torus, 150 × 100 quads; major radius 0.10 m, tube 0.015 m) whose lowest
// strand runs along y 1.5-2 cm above the iCub's open fingers at HOME: the moment before closing.
CollisionWorld clasp_scene() {
  CollisionWorld world(icub());
  const test::TriMesh ring = test::torus_mesh(0.10, 0.015, 150, 100);
  world.set_object(ring.vertices, ring.triangles);
  Eigen::Isometry3d pose = Eigen::Isometry3d::Identity();
  pose.linear() = Eigen::AngleAxisd(M_PI / 2, Eigen::Vector3d::UnitY()).toRotationMatrix();
  pose.translation() = Eigen::Vector3d(0.68, 0.0, 0.83 + 0.10);
  world.set_object_pose(pose);
  world.add_box(Eigen::Isometry3d(Eigen::Translation3d(0.6, 0.0, 0.2)), {0.6, 1.0, 0.4});  // table
  return world;
}

// Configurations around the pre-clasp pose: arm jittered by ±0.03 rad, fingers closed by 0–0.35
// rad; a mix of free and colliding ones, like a planner's samples near the goal.
std::vector<Eigen::VectorXd> near_object_configurations(int n) {
  const RobotModel& m = icub();
  std::mt19937_64 rng(11);
  std::uniform_real_distribution<double> jitter(-0.03, 0.03), close(0.0, 0.35);
  std::vector<Eigen::VectorXd> qs;
  for (int k = 0; k < n; ++k) {
    Eigen::VectorXd q = m.home;
    for (int i = 0; i < m.arm_dof; ++i) q[i] += jitter(rng);
    for (int i = m.arm_dof; i < m.dof(); ++i) q[i] += close(rng);
    qs.push_back(m.clamp(q));
  }
  return qs;
}

// One configuration's full check (FK, object, environment, self-collision): median at most
// 100 µs against the 30,000-triangle object.
void BM_IcubCollisionCheck30kNearObject(benchmark::State& state) {
  CollisionWorld world = clasp_scene();
  const auto qs = near_object_configurations(256);
  size_t k = 0, hits = 0, checks = 0;
  for (auto _ : state) {
    hits += world.in_collision(qs[k++ % qs.size()]);
    ++checks;
  }
  state.counters["colliding"] = static_cast<double>(hits) / static_cast<double>(checks);
}
BENCHMARK(BM_IcubCollisionCheck30kNearObject)->Repetitions(9)->ReportAggregatesOnly(true);

// The same configurations timed one by one (100 checks each): the median, 90th percentile and
// maximum over configurations of one check's time, in µs, as counters.
void BM_IcubCollisionCheck30kPerConfiguration(benchmark::State& state) {
  CollisionWorld world = clasp_scene();
  const auto qs = near_object_configurations(256);
  std::vector<double> micros;
  for (auto _ : state) {
    micros.clear();
    for (const auto& q : qs) {
      const auto start = std::chrono::steady_clock::now();
      for (int r = 0; r < 100; ++r) benchmark::DoNotOptimize(world.in_collision(q));
      const std::chrono::duration<double, std::micro> took =
          std::chrono::steady_clock::now() - start;
      micros.push_back(took.count() / 100.0);
    }
  }
  std::sort(micros.begin(), micros.end());
  state.counters["median_us"] = micros[micros.size() / 2];
  state.counters["p90_us"] = micros[micros.size() * 9 / 10];
  state.counters["max_us"] = micros.back();
}
BENCHMARK(BM_IcubCollisionCheck30kPerConfiguration)->Iterations(1)->Unit(benchmark::kMillisecond);

// The pre-clasp pose itself (free, the fingers 1.5-2 cm below the ring): nothing exits early.
void BM_IcubCollisionCheck30kFreeAtLoop(benchmark::State& state) {
  CollisionWorld world = clasp_scene();
  const Eigen::VectorXd q = icub().home;
  if (world.in_collision(q)) state.SkipWithError("the pre-clasp pose should be free");
  for (auto _ : state) benchmark::DoNotOptimize(world.in_collision(q));
}
BENCHMARK(BM_IcubCollisionCheck30kFreeAtLoop)->Repetitions(9)->ReportAggregatesOnly(true);

// Random configurations over the whole joint space (mostly far from the ring).
void BM_IcubCollisionCheck30kRandom(benchmark::State& state) {
  CollisionWorld world = clasp_scene();
  const auto qs = random_configurations(icub(), 256, 3);
  size_t k = 0;
  for (auto _ : state) benchmark::DoNotOptimize(world.in_collision(qs[k++ % qs.size()]));
}
BENCHMARK(BM_IcubCollisionCheck30kRandom)->Repetitions(9)->ReportAggregatesOnly(true);

// Clearance of the index finger's middle link to the ring (16 mm), capped at 2 cm (closing fingers
// until contact).
void BM_IcubLinkObjectDistance(benchmark::State& state) {
  CollisionWorld world = clasp_scene();
  const RobotModel& m = icub();
  RobotData data(m);
  forward_kinematics(m, m.home, data);
  const int link = m.link_index("index_mid_link");
  for (auto _ : state) benchmark::DoNotOptimize(world.link_object_distance(data, link, 0.02));
  state.counters["distance_mm"] = 1000.0 * world.link_object_distance(data, link, 0.02);
}
BENCHMARK(BM_IcubLinkObjectDistance);

// Is the index finger's middle link (16 mm below the ring) within the clearance (argument: mm) of
// the ring? Cost grows with the number of triangles within reach.
void BM_IcubLinkNearObject(benchmark::State& state) {
  CollisionWorld world = clasp_scene();
  const RobotModel& m = icub();
  RobotData data(m);
  forward_kinematics(m, m.home, data);
  const int link = m.link_index("index_mid_link");
  const double clearance = 0.001 * static_cast<double>(state.range(0));
  for (auto _ : state) benchmark::DoNotOptimize(world.link_near_object(data, link, clearance));
  state.counters["near"] = world.link_near_object(data, link, clearance);
}
BENCHMARK(BM_IcubLinkNearObject)->Arg(2)->Arg(5)->Arg(10)->Arg(20);

// Does that link touch the ring or the table (the step test for closing a finger)?
void BM_IcubLinkInCollision(benchmark::State& state) {
  CollisionWorld world = clasp_scene();
  const RobotModel& m = icub();
  RobotData data(m);
  forward_kinematics(m, m.home, data);
  const int link = m.link_index("index_mid_link");
  for (auto _ : state) benchmark::DoNotOptimize(world.link_in_collision(data, link));
}
BENCHMARK(BM_IcubLinkInCollision);

}  // namespace
}  // namespace claspplan::robots
