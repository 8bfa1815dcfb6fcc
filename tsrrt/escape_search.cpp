// The escape stages of the secure-clasp check (see escape_search.hpp). Our own small RRT-Connect,
// not OMPL's planners: OMPL draws from a process-global seed, so its plans would not be the same
// byte for byte from one run (or one thread interleaving) to the next, and a verdict must be.
// Random numbers come from std::mt19937_64's raw output (core/random_draws.hpp) only.
#include "tsrrt/escape_search.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <random>

#include "core/random_draws.hpp"
#include "robots/kinematics.hpp"
#include "tsrrt/secure_clasp.hpp"
#include "tsrrt/secure_clasp_detail.hpp"

namespace claspplan::tsrrt {
namespace {

using Clock = std::chrono::steady_clock;

// SplitMix64: independent streams for the stages and attempts of one seed.
std::uint64_t mix(std::uint64_t seed, std::uint64_t tag) {
  std::uint64_t z = seed + 0x9E3779B97F4A7C15ULL * (tag + 1);
  z = (z ^ (z >> 30)) * 0xBF58476D1CE4E5B9ULL;
  z = (z ^ (z >> 27)) * 0x94D049BB133111EBULL;
  return z ^ (z >> 31);
}

using detail::random_unit;

// Uniform rotation (Shoemake, Graphics Gems III).
Eigen::Quaterniond random_rotation(std::mt19937_64& rng) {
  const double u1 = uniform01(rng()), u2 = uniform01(rng()), u3 = uniform01(rng());
  const double a = std::sqrt(1.0 - u1), b = std::sqrt(u1);
  return Eigen::Quaterniond(b * std::cos(2 * M_PI * u3), a * std::sin(2 * M_PI * u2),
                            a * std::cos(2 * M_PI * u2), b * std::sin(2 * M_PI * u3));
}

// acos(x) for x in [0, 1] within 6.7e-5 rad (Abramowitz and Stegun, 4.4.45): the nearest-node
// scans' rotation angle, 2 acos(|q1 · q2|). Eigen's angularDistance (an atan2 after a quaternion
// product) took a fifth of a secure clasp's escape stages there; a node nearer by less than the
// error is as good a choice.
double fast_acos(double x) {
  x = std::min(x, 1.0);
  return std::sqrt(1.0 - x) * (1.5707288 + x * (-0.2121144 + x * (0.0742610 - 0.0187293 * x)));
}

// The object's pose: rotated by q about its pivot, the pivot moved to p.
struct State {
  Eigen::Vector3d p;
  Eigen::Quaterniond q;
};

State interpolate(const State& a, const State& b, double t) {
  return {a.p + t * (b.p - a.p), a.q.slerp(t, b.q)};
}

struct Node {
  State s;
  int parent;  // -1: a root
};

enum class Step { kTrapped, kAdvanced, kReached };

class Search {
 public:
  Search(const EscapeProblem& pr, const EscapeSearchOptions& o,
         const std::optional<Eigen::Vector3d>& pull)
      : pr_(pr), o_(o), pull_(pull), rng_(o.seed) {
    // A radian turns the loop's farthest point by this much: rotation and translation compare.
    for (const auto& p : pr.loop) reach_ = std::max(reach_, (p - pr.pivot).norm());
    moved_.resize(pr.loop.size());
  }

  Eigen::Isometry3d pose(const State& s) const {
    Eigen::Isometry3d T = Eigen::Isometry3d::Identity();
    T.translate(s.p);
    T.rotate(s.q);
    T.translate(-pr_.pivot);
    return T;
  }

  State start() const { return {pr_.pivot, Eigen::Quaterniond::Identity()}; }

  bool deadline_passed() const {
    return (o_.deadline && Clock::now() >= *o_.deadline) || (o_.cancelled && o_.cancelled());
  }

  // Energy first (cheap), then contacts.
  bool valid(const State& s) const {
    const Eigen::Isometry3d T = pose(s);
    if (pull_ && -pull_->dot(T * pr_.centroid - pr_.centroid) > o_.energy_slack) return false;
    return !pr_.collides(T);
  }

  // The goal: every loop point escape_distance from every finger curve.
  bool out(const State& s) {
    const Eigen::Isometry3d T = pose(s);
    for (std::size_t i = 0; i < pr_.loop.size(); ++i) moved_[i] = T * pr_.loop[i];
    return detail::loop_hand_distance(moved_, pr_.curves) >= o_.escape_distance;
  }

  double distance(const State& a, const State& b) const {
    return (a.p - b.p).norm() + reach_ * a.q.angularDistance(b.q);
  }

  EscapeResult rrt_connect() {
    EscapeResult r;
    start_ = {{start(), -1}};
    add_goal_roots(o_.goal_attempts);
    for (int it = 0; it < o_.iterations; ++it) {
      if (deadline_passed()) {
        r.timed_out = true;
        return r;
      }
      r.iterations = it + 1;
      if (goal_.empty()) {  // nowhere to go yet: this iteration draws goals
        add_goal_roots(std::max(1, o_.goal_attempts / 8));
        continue;
      }
      const State sample{pr_.pivot + o_.sample_box * Eigen::Vector3d(2.0 * uniform01(rng_()) - 1.0,
                                                                     2.0 * uniform01(rng_()) - 1.0,
                                                                     2.0 * uniform01(rng_()) - 1.0),
                         random_rotation(rng_)};
      // Alternate the trees (RRT-Connect's swap): extend one, connect the other to it.
      const bool from_start = it % 2 == 0;
      std::vector<Node>& grow = from_start ? start_ : goal_;
      std::vector<Node>& other = from_start ? goal_ : start_;
      int added = -1;
      if (extend(grow, sample, o_.extend_distance, added) == Step::kTrapped) continue;
      if (from_start && out(grow[added].s)) return escaped(r, grow[added].s);
      const State target = grow[added].s;
      Step step = Step::kAdvanced;
      int last = -1;
      while (step == Step::kAdvanced) {
        step = extend(other, target, o_.extend_distance, last);
        if (step != Step::kTrapped && !from_start && out(other[last].s))
          return escaped(r, other[last].s);
      }
      if (step == Step::kReached) {
        // The trees meet: the path ends at the goal root of the goal tree's branch.
        int g = from_start ? last : added;
        while (goal_[g].parent >= 0) g = goal_[g].parent;
        return escaped(r, goal_[g].s);
      }
    }
    return r;
  }

  EscapeResult straight(const Eigen::Vector3d& d) {
    EscapeResult r;
    // Far enough for the loop's far side to clear the hand too.
    const int steps =
        static_cast<int>(std::ceil((o_.escape_distance + 2.0 * reach_) / o_.translation_step));
    for (int a = 0; a < o_.pull_attempts; ++a) {
      std::mt19937_64 rng(mix(o_.seed, 1000 + a));
      State s = start();
      for (int k = 0; k < steps; ++k) {
        if (deadline_passed()) {
          r.timed_out = true;
          return r;
        }
        bool moved = false;
        // Attempt 0 slides straight; the others wiggle (sideways by up to half a step, turned by
        // up to half a rotation step about the pivot) and retry a blocked step.
        const int tries = a == 0 ? 1 : 1 + o_.pull_retries;
        for (int t = 0; t < tries && !moved; ++t) {
          State next{s.p + o_.translation_step * d, s.q};
          if (a > 0) {
            Eigen::Vector3d side = random_unit(rng);
            side -= side.dot(d) * d;
            next.p += 0.5 * o_.translation_step * uniform01(rng()) * side;
            const double angle = 0.5 * o_.rotation_step * uniform01(rng());
            next.q = Eigen::Quaterniond(Eigen::AngleAxisd(angle, random_unit(rng))) * s.q;
            next.q.normalize();
          }
          if (valid(next)) s = next, moved = true;
        }
        if (!moved) break;
        if ((k % 4 == 3 || k + 1 == steps) && out(s)) return escaped(r, s);
      }
    }
    return r;
  }

 private:
  EscapeResult& escaped(EscapeResult& r, const State& s) const {
    r.escaped = true;
    r.escape = pose(s);
    return r;
  }

  void add_goal_roots(int attempts) {
    for (int a = 0; a < attempts && roots_ < o_.goal_roots; ++a) {
      Eigen::Vector3d dir = random_unit(rng_);
      // Under a pull, the goals lie on its downhill side (others would fail the bound anyway).
      if (pull_ && dir.dot(*pull_) < 0) dir -= 2.0 * dir.dot(*pull_) * *pull_;
      const double length = o_.escape_distance + 0.25 * o_.escape_distance * uniform01(rng_());
      const State s{pr_.pivot + length * dir, random_rotation(rng_)};
      if (out(s) && valid(s)) {
        goal_.push_back({s, -1});
        ++roots_;
      }
    }
  }

  int nearest(const std::vector<Node>& tree, const State& s) const {
    int best = 0;
    double best_d = std::numeric_limits<double>::infinity();
    for (int i = 0; i < static_cast<int>(tree.size()); ++i) {
      const double d =
          (tree[i].s.p - s.p).norm() + reach_ * 2.0 * fast_acos(std::abs(tree[i].s.q.dot(s.q)));
      if (d < best_d) best_d = d, best = i;
    }
    return best;
  }

  // Grows `tree` from its node nearest `target` toward it by at most `reach` (metric of
  // distance()), as far as the edge stays valid; `added` is the new node.
  Step extend(std::vector<Node>& tree, const State& target, double reach, int& added) {
    if (tree.empty()) return Step::kTrapped;
    const int n = nearest(tree, target);
    const State from = tree[n].s;
    const double d = distance(from, target);
    const bool whole = d <= reach;
    const State to = whole ? target : interpolate(from, target, reach / d);
    const int steps = std::max(
        1, static_cast<int>(std::ceil(std::max((to.p - from.p).norm() / o_.translation_step,
                                               from.q.angularDistance(to.q) / o_.rotation_step))));
    int last = 0;
    for (int k = 1; k <= steps && valid(interpolate(from, to, double(k) / steps)); ++k) last = k;
    if (last == 0) return Step::kTrapped;
    tree.push_back({last == steps ? to : interpolate(from, to, double(last) / steps), n});
    added = static_cast<int>(tree.size()) - 1;
    return whole && last == steps ? Step::kReached : Step::kAdvanced;
  }

  const EscapeProblem& pr_;
  const EscapeSearchOptions& o_;
  std::optional<Eigen::Vector3d> pull_;
  std::mt19937_64 rng_;
  double reach_ = 0.02;
  servo::Points moved_;
  std::vector<Node> start_, goal_;
  int roots_ = 0;
};

}  // namespace

EscapeProblem escape_problem(const robots::RobotModel& model, const Eigen::VectorXd& q,
                             const servo::Points& loop,
                             const std::vector<Eigen::Vector3d>& vertices,
                             std::function<bool(const Eigen::Isometry3d&)> collides) {
  SecureClaspReport scratch;
  detail::ClaspCheckContext c = detail::clasp_check_context(model, q, loop, scratch);
  EscapeProblem p;
  p.curves = std::move(c.curves);
  p.loop = loop;
  p.pivot = c.pivot;
  p.centroid = c.pivot;
  if (!vertices.empty()) {
    Eigen::Vector3d sum = Eigen::Vector3d::Zero();
    for (const auto& v : vertices) sum += v;
    p.centroid = sum / static_cast<double>(vertices.size());
  }
  robots::RobotData data(model);
  robots::forward_kinematics(model, q, data);
  p.approach = robots::vector_direction(data, model.v_fwd).normalized();
  p.collides = std::move(collides);
  return p;
}

EscapeResult search_escape(const EscapeProblem& problem, const EscapeSearchOptions& options,
                           const std::optional<Eigen::Vector3d>& pull) {
  if (pull) return Search(problem, options, pull->normalized()).rrt_connect();
  return Search(problem, options, std::nullopt).rrt_connect();
}

EscapeResult straight_pull(const EscapeProblem& problem, const EscapeSearchOptions& options,
                           const Eigen::Vector3d& pull) {
  const Eigen::Vector3d d = pull.normalized();
  return Search(problem, options, d).straight(d);
}

const char* stage_name(EscapeStage stage) {
  switch (stage) {
    case EscapeStage::kEscapeSearch:
      return "escape_search";
    case EscapeStage::kGravity:
      return "gravity";
    case EscapeStage::kApproach:
      return "approach";
  }
  return "";
}

VerificationStage run_escape_stage(EscapeStage stage, const EscapeProblem& problem,
                                   const EscapeSearchOptions& options) {
  const auto t0 = Clock::now();
  VerificationStage v;
  v.name = stage_name(stage);
  v.ran = true;
  EscapeSearchOptions o = options;
  o.seed = mix(options.seed, static_cast<std::uint64_t>(stage));
  EscapeResult r;
  if (stage == EscapeStage::kEscapeSearch) {
    r = search_escape(problem, o);
  } else {
    // Gravity lowers the object; a hand pulled back drags it along +v_fwd relative to the hand.
    const Eigen::Vector3d pull =
        stage == EscapeStage::kGravity ? Eigen::Vector3d(0, 0, -1) : problem.approach;
    r = straight_pull(problem, o, pull);
    if (!r.escaped && !r.timed_out) r = search_escape(problem, o, pull);
  }
  v.timed_out = r.timed_out;
  v.passed = !r.escaped && !r.timed_out;
  v.iterations = r.iterations;
  v.escape = r.escape;
  v.seconds = std::chrono::duration<double>(Clock::now() - t0).count();
  return v;
}

}  // namespace claspplan::tsrrt
