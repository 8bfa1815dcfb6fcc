// The secure-clasp check (paper Sec. V-A): random motions of the object relative to the closed
// hand. Faster than a plain loop over sequences in three ways that keep its verdicts:
// - only the object's triangles near the closed hand are tested, plus the loop's tube whole (less
//   geometry only makes escaping easier, so a secure verdict stays trustworthy);
// - sequences advance in rounds of motions and the check stops after the first round in which
//   one escapes (an insecure clasp is shown by its first escape);
// - all cores by default; each sequence has its own random stream and rounds end together, so the
//   report does not depend on the number of threads.
#include "tsrrt/secure_clasp.hpp"

#include <algorithm>
#include <atomic>
#include <chrono>
#include <cmath>
#include <iterator>
#include <limits>
#include <unordered_map>

#include "core/parallel.hpp"
#include "core/random_draws.hpp"
#include "robots/kinematics.hpp"
#include "servo/linking.hpp"
#include "tsrrt/clasp_scene.hpp"
#include "tsrrt/secure_clasp_detail.hpp"

namespace claspplan::tsrrt {
namespace detail {
namespace {

double point_segment_distance(const Eigen::Vector3d& p, const Eigen::Vector3d& a,
                              const Eigen::Vector3d& b) {
  const Eigen::Vector3d ab = b - a;
  const double t = std::clamp((p - a).dot(ab) / std::max(ab.squaredNorm(), 1e-300), 0.0, 1.0);
  return (a + t * ab - p).norm();
}

}  // namespace

Eigen::Vector3d random_unit(std::mt19937_64& rng) {
  for (;;) {
    const Eigen::Vector3d v(2.0 * uniform01(rng()) - 1.0, 2.0 * uniform01(rng()) - 1.0,
                            2.0 * uniform01(rng()) - 1.0);
    const double n = v.norm();
    if (n > 1e-3 && n <= 1.0) return v / n;
  }
}

double loop_hand_distance(const servo::Points& loop, const Curves& curves) {
  double best = std::numeric_limits<double>::infinity();
  for (const auto& curve : curves)
    for (std::size_t i = 0; i + 1 < curve.size(); ++i)
      for (const auto& p : loop)
        best = std::min(best, point_segment_distance(p, curve[i], curve[i + 1]));
  return best;
}

ClaspCheckContext clasp_check_context(const robots::RobotModel& model, const Eigen::VectorXd& q,
                                      const servo::Points& loop, SecureClaspReport& report) {
  ClaspCheckContext c;
  robots::RobotData data(model);
  robots::FingerCurvesData curves;
  robots::finger_curves(model, q, data, curves, false);
  c.curves = curves.points;
  c.loop = loop;

  // Paper Fig. 6: the Gauss integral of each open finger curve with the loop, and VLk.
  report.open_linking = open_finger_linking(model, q, loop);
  for (const auto& curve : c.curves) {
    report.virtual_linking.push_back(std::abs(servo::virtual_linking(loop, curve).value));
  }
  const auto [min_open, max_open] =
      std::minmax_element(report.open_linking.begin(), report.open_linking.end());
  const auto [min_v, max_v] =
      std::minmax_element(report.virtual_linking.begin(), report.virtual_linking.end());
  report.min_open_linking = *min_open;
  report.max_open_linking = *max_open;
  report.min_virtual_linking = *min_v;
  report.max_virtual_linking = *max_v;

  c.pivot = loop.front();
  double nearest = std::numeric_limits<double>::infinity();
  for (const auto& p : loop) {
    const double d = loop_hand_distance({p}, c.curves);
    if (d < nearest) nearest = d, c.pivot = p;
  }
  return c;
}

std::uint64_t sequence_seed(std::uint64_t seed, int s) {
  return seed * 1000003ULL + static_cast<std::uint64_t>(s);
}

bool object_free(const ClaspCheckContext& c, const Eigen::Isometry3d& T, double free_distance) {
  servo::Points moved(c.loop.size());
  for (std::size_t i = 0; i < c.loop.size(); ++i) moved[i] = T * c.loop[i];
  for (const auto& curve : c.curves) {
    if (servo::virtual_linking(moved, curve).closed_linking != 0) return false;
  }
  return loop_hand_distance(moved, c.curves) > free_distance;
}

bool random_motion(const ClaspCheckContext& c, const SecureClaspOptions& o, std::mt19937_64& rng,
                   Eigen::Isometry3d& T,
                   const std::function<bool(const Eigen::Isometry3d&)>& collides) {
  // A random screw: a translation and a rotation about the (moving) pivot, in small steps.
  const Eigen::Vector3d direction = random_unit(rng);
  const Eigen::Vector3d axis = random_unit(rng);
  const double mix = uniform01(rng());
  for (int k = 0; k < o.steps_per_motion; ++k) {
    const Eigen::Vector3d centre = T * c.pivot;
    Eigen::Isometry3d step = Eigen::Isometry3d::Identity();
    step.translate(centre + direction * (mix * o.translation_step));
    step.rotate(Eigen::AngleAxisd((1.0 - mix) * o.rotation_step, axis));
    step.translate(-centre);
    const Eigen::Isometry3d trial = step * T;
    if (collides(trial)) break;  // pursued until collision
    T = trial;
  }
  return object_free(c, T, o.free_distance);
}

}  // namespace detail

namespace {

// Where the closed hand is: the box around its links' shapes (their bounding spheres), world frame.
Eigen::AlignedBox3d hand_box(const robots::RobotModel& model, const Eigen::VectorXd& q) {
  robots::RobotData data(model);
  robots::forward_kinematics(model, q, data);
  Eigen::AlignedBox3d box;
  for (const robots::CollisionShape& s : model.shapes) {
    if (!model.links[s.link].hand) continue;
    const double r = robots::shape_reach(s);
    const Eigen::Vector3d c = data.link_poses[s.link] * s.origin.translation();
    box.extend(c - Eigen::Vector3d::Constant(r));
    box.extend(c + Eigen::Vector3d::Constant(r));
  }
  return box;
}

// Vertices within the loop's tube radius of a loop point (the tube's rings), by a hash grid.
std::vector<char> on_loop_tube(const std::vector<Eigen::Vector3d>& vertices,
                               const servo::Points& loop) {
  const double r = kLoopTubeRadius * (1.0 + 1e-6) + 1e-9;
  const auto cell = [r](const Eigen::Vector3d& p) {
    return Eigen::Vector3i((p / r).array().floor().cast<int>());
  };
  const auto key = [](const Eigen::Vector3i& c) {
    return (static_cast<std::int64_t>(c[0]) * 73856093) ^
           (static_cast<std::int64_t>(c[1]) * 19349663) ^
           (static_cast<std::int64_t>(c[2]) * 83492791);
  };
  std::unordered_multimap<std::int64_t, int> grid;
  for (int i = 0; i < static_cast<int>(loop.size()); ++i) grid.emplace(key(cell(loop[i])), i);
  std::vector<char> near(vertices.size(), 0);
  for (std::size_t v = 0; v < vertices.size(); ++v) {
    const Eigen::Vector3i c = cell(vertices[v]);
    for (int dx = -1; dx <= 1 && !near[v]; ++dx)
      for (int dy = -1; dy <= 1 && !near[v]; ++dy)
        for (int dz = -1; dz <= 1 && !near[v]; ++dz) {
          const auto [lo, hi] = grid.equal_range(key(c + Eigen::Vector3i(dx, dy, dz)));
          for (auto it = lo; it != hi && !near[v]; ++it)
            near[v] = (vertices[v] - loop[it->second]).norm() <= r;
        }
  }
  return near;
}

}  // namespace

void crop_near_hand(const robots::RobotModel& model, const Eigen::VectorXd& q,
                    const servo::Points& loop, double margin,
                    const std::vector<Eigen::Vector3d>& vertices,
                    const std::vector<Eigen::Vector3i>& triangles,
                    std::vector<Eigen::Vector3d>& kept_vertices,
                    std::vector<Eigen::Vector3i>& kept_triangles) {
  kept_vertices.clear();
  kept_triangles.clear();
  Eigen::AlignedBox3d region = hand_box(model, q);
  if (margin <= 0.0 || region.isEmpty()) {
    kept_vertices = vertices;
    kept_triangles = triangles;
    return;
  }
  region.min().array() -= margin;
  region.max().array() += margin;
  const std::vector<char> tube = on_loop_tube(vertices, loop);
  std::vector<int> index(vertices.size(), -1);
  const auto valid = [&](int v) { return v >= 0 && v < static_cast<int>(vertices.size()); };
  for (const Eigen::Vector3i& t : triangles) {
    if (!valid(t[0]) || !valid(t[1]) || !valid(t[2])) {
      kept_triangles.push_back(t);  // left for set_object() to refuse
      continue;
    }
    Eigen::AlignedBox3d box(vertices[t[0]]);
    box.extend(vertices[t[1]]).extend(vertices[t[2]]);
    const bool on_tube = tube[t[0]] && tube[t[1]] && tube[t[2]];
    if (!on_tube && !box.intersects(region)) continue;
    Eigen::Vector3i kept;
    for (int k = 0; k < 3; ++k) {
      int& i = index[t[k]];
      if (i < 0) {
        i = static_cast<int>(kept_vertices.size());
        kept_vertices.push_back(vertices[t[k]]);
      }
      kept[k] = i;
    }
    kept_triangles.push_back(kept);
  }
  if (kept_vertices.empty()) kept_vertices = vertices;  // nothing near: set_object() decides
}

namespace {

// The motions of one sequence so far.
struct Sequence {
  std::mt19937_64 rng;
  Eigen::Isometry3d T = Eigen::Isometry3d::Identity();  // the object's motion from its start
  int motions = 0;
  int escape_motion = -1;
  bool timed_out = false;
};

// Sequence s up to `end` motions (or its escape, or the deadline), in `world`.
void advance(Sequence& s, int end, robots::CollisionWorld& world, const robots::RobotData& data,
             const detail::ClaspCheckContext& c, const SecureClaspOptions& o) {
  const auto collides = [&](const Eigen::Isometry3d& T) {
    world.set_object_pose(T);
    return world.object_in_collision(data);
  };
  for (; s.motions < end && s.escape_motion < 0; ++s.motions) {
    if (o.deadline && std::chrono::steady_clock::now() >= *o.deadline) {
      s.timed_out = true;
      return;
    }
    if (detail::random_motion(c, o, s.rng, s.T, collides)) s.escape_motion = s.motions;
  }
}

// Round boundaries (motions done by every sequence): 25, 100, 400, ... then all.
int round_end(int round, int motions) {
  long end = 25;
  for (int r = 0; r < round && end < motions; ++r) end *= 4;
  return static_cast<int>(std::min<long>(end, motions));
}

// The object as the check at q tests it (see SecureClaspOptions::near_hand).
std::shared_ptr<const robots::ObjectGeometry> object_near_hand(
    const robots::RobotModel& model, const std::vector<Eigen::Vector3d>& object_vertices,
    const std::vector<Eigen::Vector3i>& object_triangles, const Eigen::VectorXd& q,
    const servo::Points& loop, const SecureClaspOptions& o) {
  std::vector<Eigen::Vector3d> vertices;
  std::vector<Eigen::Vector3i> triangles;
  crop_near_hand(model, q, loop, o.near_hand, object_vertices, object_triangles, vertices,
                 triangles);
  return robots::make_object_geometry(vertices, triangles, o.exact_round_shapes);
}

// The escape stages after the random motions passed, one per world at a time (the robot at q
// placed in `data`). The report holds the stages up to the first that frees the object or times
// out; a later stage still running is cancelled, and every later one is reported as not run, so
// the report does not depend on which finished first.
void run_escape_stages(const robots::RobotModel& model, std::vector<robots::CollisionWorld>& worlds,
                       const robots::RobotData& data, const Eigen::VectorXd& q,
                       const servo::Points& loop, const std::vector<Eigen::Vector3d>& vertices,
                       const SecureClaspOptions& o, SecureClaspReport& report) {
  constexpr EscapeStage kStages[] = {EscapeStage::kEscapeSearch, EscapeStage::kGravity,
                                     EscapeStage::kApproach};
  constexpr int kCount = static_cast<int>(std::size(kStages));
  const auto not_run = [](EscapeStage stage) {
    VerificationStage v;
    v.name = stage_name(stage);
    return v;
  };
  // The caller's stop is polled on its own thread only (Python's Ctrl-C check needs that).
  if (o.stop && o.stop()) {
    report.secure = false;
    report.timed_out = true;
    for (const EscapeStage stage : kStages) report.stages.push_back(not_run(stage));
    return;
  }
  // One problem per world the stages can use at once, each colliding in its own world.
  const EscapeProblem problem = escape_problem(model, q, loop, vertices, nullptr);
  std::vector<EscapeProblem> problems(std::min<std::size_t>(worlds.size(), kCount), problem);
  for (std::size_t w = 0; w < problems.size(); ++w)
    problems[w].collides = [world = &worlds[w], &data](const Eigen::Isometry3d& T) {
      world->set_object_pose(T);
      return world->object_in_collision(data);
    };
  EscapeSearchOptions options = o.escape;
  options.seed = o.seed;
  options.deadline = o.deadline;
  options.translation_step = o.translation_step;
  options.rotation_step = o.rotation_step;
  std::atomic<int> first_failed{kCount};
  std::vector<VerificationStage> runs(kCount);
  parallel_for(kCount, static_cast<int>(problems.size()), [&](std::size_t k, int worker) {
    const int stage = static_cast<int>(k);
    if (first_failed.load() < stage) return;
    EscapeSearchOptions eo = options;
    eo.cancelled = [&] { return first_failed.load() < stage; };
    runs[k] = run_escape_stage(kStages[k], problems[worker], eo);
    if (runs[k].passed) return;
    int failed = first_failed.load();
    while (stage < failed && !first_failed.compare_exchange_weak(failed, stage)) {
    }
  });
  for (robots::CollisionWorld& world : worlds) world.set_object_pose(Eigen::Isometry3d::Identity());
  const int failed = first_failed.load();
  for (int k = 0; k < kCount; ++k) {
    if (k > failed) {
      report.stages.push_back(not_run(kStages[k]));
      continue;
    }
    report.stages.push_back(std::move(runs[k]));
    const VerificationStage& v = report.stages.back();
    if (v.passed) continue;
    report.secure = false;
    report.timed_out |= v.timed_out;
    if (v.escape) {
      report.escape = v.escape;
      report.escape_stage = v.name;
    }
  }
}

// Runs the check; `rounds_done` (optional) tells how many rounds ran. `vertices`: the whole
// object's, for the escape stages' centroid.
SecureClaspReport run_check(const robots::RobotModel& model,
                            const std::shared_ptr<const robots::ObjectGeometry>& object,
                            const std::vector<Eigen::Vector3d>& vertices, const Eigen::VectorXd& q,
                            const servo::Points& loop, const SecureClaspOptions& o,
                            int* rounds_done) {
  const auto t0 = std::chrono::steady_clock::now();
  SecureClaspReport report;
  const detail::ClaspCheckContext c = detail::clasp_check_context(model, q, loop, report);
  robots::RobotData data(model);
  robots::forward_kinematics(model, q, data);

  const int threads = thread_count(o.threads, static_cast<std::size_t>(std::max(0, o.sequences)));
  // The robot and the object only, as in the paper's test; the arm does not move.
  std::vector<robots::CollisionWorld> worlds;
  for (int t = 0; t < threads; ++t) {
    worlds.emplace_back(model);
    worlds.back().set_self_collision(false);
    worlds.back().set_exact_round_shapes(o.exact_round_shapes);
    worlds.back().set_object(object);
  }
  if (worlds.front().in_collision(data)) {
    report.start_in_collision = true;
    return report;
  }

  report.sequences = o.sequences;
  std::vector<Sequence> sequences(o.sequences);
  for (int s = 0; s < o.sequences; ++s) sequences[s].rng.seed(detail::sequence_seed(o.seed, s));
  bool stop = false;
  for (int round = 0; !stop; ++round) {
    const int end = round_end(round, o.motions);
    // Threads take sequences in any order; each sequence's result is its own.
    parallel_for(sequences.size(), threads, [&](std::size_t s, int worker) {
      advance(sequences[s], end, worlds[worker], data, c, o);
    });
    if (rounds_done) *rounds_done = round + 1;
    for (const Sequence& s : sequences) {
      report.timed_out |= s.timed_out;
      if (s.escape_motion < 0) continue;
      ++report.escaped_sequences;
      if (report.escape_motion < 0) report.escape_motion = s.escape_motion;
      if (!report.escape) report.escape = s.T;
    }
    if (o.stop && o.stop()) report.timed_out = true;
    stop = end >= o.motions || report.escaped_sequences > 0 || report.timed_out;
  }
  report.secure = report.escaped_sequences == 0 && !report.timed_out;
  VerificationStage random{"random_motions", true, report.secure, report.timed_out, 0, 0.0,
                           report.escape};
  for (const Sequence& s : sequences) random.iterations += s.motions;
  random.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  report.stages.push_back(std::move(random));
  if (report.escape) report.escape_stage = "random_motions";
  if (report.secure && o.escape_stages)
    run_escape_stages(model, worlds, data, q, loop, vertices, o, report);
  return report;
}

}  // namespace

SecureClaspReport check_secure_clasp(const robots::RobotModel& model,
                                     const std::vector<Eigen::Vector3d>& object_vertices,
                                     const std::vector<Eigen::Vector3i>& object_triangles,
                                     const Eigen::VectorXd& q, const servo::Points& loop,
                                     const SecureClaspOptions& options) {
  return run_check(model,
                   object_near_hand(model, object_vertices, object_triangles, q, loop, options),
                   object_vertices, q, loop, options, nullptr);
}

SecureClaspChecker::SecureClaspChecker(const robots::RobotModel& model,
                                       std::vector<Eigen::Vector3d> object_vertices,
                                       std::vector<Eigen::Vector3i> object_triangles,
                                       const SecureClaspOptions& options)
    : model_(model),
      vertices_(std::move(object_vertices)),
      triangles_(std::move(object_triangles)),
      options_(options) {}

SecureClaspReport SecureClaspChecker::check(const Eigen::VectorXd& q, const servo::Points& loop,
                                            bool* screened_out) {
  std::shared_ptr<const robots::ObjectGeometry> object = whole_;
  if (options_.near_hand > 0.0) {
    object = object_near_hand(model_, vertices_, triangles_, q, loop, options_);
  } else if (!object) {
    object = whole_ =
        robots::make_object_geometry(vertices_, triangles_, options_.exact_round_shapes);
  }
  int rounds = 0;
  SecureClaspReport report = run_check(model_, object, vertices_, q, loop, options_, &rounds);
  // The screening is the random motions' first rounds (the first stage).
  if (screened_out)
    *screened_out = (report.stages.empty() || !report.stages.front().passed) && rounds <= 2;
  return report;
}

std::vector<double> open_finger_linking(const robots::RobotModel& model, const Eigen::VectorXd& q,
                                        const servo::Points& loop) {
  robots::RobotData data(model);
  robots::FingerCurvesData curves;
  robots::finger_curves(model, q, data, curves, false);
  std::vector<double> values;
  for (const auto& curve : curves.points) {
    values.push_back(std::abs(servo::gauss_linking(loop, true, curve, false)));
  }
  return values;
}

}  // namespace claspplan::tsrrt
