#include "examples/grasp_rrt.hpp"

#include <algorithm>
#include <chrono>
#include <random>

#include <Eigen/Cholesky>

#include "core/random_draws.hpp"
#include "robots/kinematics.hpp"
#include "tsrrt/elapsed.hpp"

namespace claspplan::cli {
namespace {

using tsrrt::Clock;
using tsrrt::since;

struct Node {
  Eigen::VectorXd q;
  Eigen::Vector3d tcp;
  int parent = -1;
};

// A point of the seen surface with its outward normal (away from the object's centre: the depth
// surface's triangles have no inside).
struct SurfacePoint {
  Eigen::Vector3d p, n;
};

class GraspRrt {
 public:
  GraspRrt(const tsrrt::ClaspScene& scene, tsrrt::ClaspResult& r, const GraspRrtOptions& o)
      : scene_(scene),
        model_(scene.robot),
        r_(r),
        o_(o),
        data_(model_),
        rng_(scene.planning.planner.seed),
        lower_(model_.lower()),
        upper_(model_.upper()) {
    const auto& v = r.collision_mesh.vertices;
    for (const auto& p : v) centre_ += p;
    if (!v.empty()) centre_ /= static_cast<double>(v.size());
  }

  void run() {
    const tsrrt::PlannerParameters& pp = scene_.planning.planner;
    add(r_.start, -1);
    const auto start = Clock::now();
    int iterations = 0;
    int approaches = 0, contacts = 0, grasps_scored_low = 0;
    for (;; ++iterations) {
      if (pp.time_limit > 0 ? since(start) >= pp.time_limit : iterations >= pp.max_cycles) break;
      if (uniform01(rng_()) < o_.approach_probability) {
        ++approaches;
        const int contact = approach(surface_point());
        if (contact < 0) continue;
        ++contacts;
        if (grasp(contact)) break;
        ++grasps_scored_low;
      } else {
        extend();
      }
    }
    r_.statistics.cycles = iterations;
    r_.statistics.nodes = static_cast<int>(nodes_.size());
    if (!r_.succeeded()) {
      r_.reason = "Grasp-RRT baseline: no grasp scored in " + std::to_string(iterations) +
                  " iterations (" + std::to_string(approaches) + " approaches, " +
                  std::to_string(contacts) + " reached the object, " +
                  std::to_string(grasps_scored_low) + " closed with too few fingers on it)";
    }
  }

 private:
  int add(const Eigen::VectorXd& q, int parent) {
    robots::forward_kinematics(model_, q, data_);
    nodes_.push_back({q, robots::point_position(data_, model_.tcp), parent});
    return static_cast<int>(nodes_.size()) - 1;
  }

  bool free(const Eigen::VectorXd& q0, const Eigen::VectorXd& q1, bool* object_contact) {
    robots::CollisionReport report;
    if (scene_.world.motion_free(q0, q1, scene_.planning.collision_resolution, &report))
      return true;
    *object_contact = report.second == "object";
    return false;
  }

  // RRT-EXTEND in the arm's joint space, the hand open.
  void extend() {
    Eigen::VectorXd q_rand = r_.start;
    for (int j = 0; j < model_.arm_dof; ++j)
      q_rand[j] = lower_[j] + uniform01(rng_()) * (upper_[j] - lower_[j]);
    int near = 0;
    double best = std::numeric_limits<double>::infinity();
    for (std::size_t i = 0; i < nodes_.size(); ++i) {
      const double d = (nodes_[i].q - q_rand).head(model_.arm_dof).squaredNorm();
      if (d < best) best = d, near = static_cast<int>(i);
    }
    Eigen::VectorXd dq = q_rand - nodes_[near].q;
    const double length = dq.head(model_.arm_dof).norm();
    if (length > o_.step) dq *= o_.step / length;
    const Eigen::VectorXd q_new = nodes_[near].q + dq;
    bool contact = false;
    if (free(nodes_[near].q, q_new, &contact)) add(q_new, near);
  }

  SurfacePoint surface_point() {
    const auto& v = r_.collision_mesh.vertices;
    const auto& t = r_.collision_mesh.triangles;
    const Eigen::Vector3i& tri = t[uniform_index(rng_(), t.size())];
    double a = uniform01(rng_()), b = uniform01(rng_());
    if (a + b > 1.0) a = 1.0 - a, b = 1.0 - b;
    SurfacePoint s;
    s.p = v[tri[0]] + a * (v[tri[1]] - v[tri[0]]) + b * (v[tri[2]] - v[tri[0]]);
    s.n = (v[tri[1]] - v[tri[0]]).cross(v[tri[2]] - v[tri[0]]).normalized();
    if (s.n.dot(s.p - centre_) < 0) s.n = -s.n;
    return s;
  }

  // The approach: from the node whose hand is nearest the stand-off point, the hand driven to the
  // surface point with its approach direction against the normal (damped least squares on the
  // arm), until it touches the object. Returns the last free node, or -1.
  int approach(const SurfacePoint& s) {
    if (!s.n.allFinite()) return -1;
    const Eigen::Vector3d standoff = s.p + o_.standoff * s.n;
    int node = 0;
    double best = std::numeric_limits<double>::infinity();
    for (std::size_t i = 0; i < nodes_.size(); ++i) {
      const double d = (nodes_[i].tcp - standoff).squaredNorm();
      if (d < best) best = d, node = static_cast<int>(i);
    }
    const int arm = model_.arm_dof;
    for (int step = 0; step < o_.approach_steps; ++step) {
      const Eigen::VectorXd& q = nodes_[node].q;
      robots::forward_kinematics(model_, q, data_);
      Eigen::Vector3d e_p = s.p - nodes_[node].tcp;
      if (e_p.norm() > o_.approach_step) e_p *= o_.approach_step / e_p.norm();
      const Eigen::Vector3d e_v = 0.3 * (-s.n - robots::vector_direction(data_, model_.v_fwd));
      Eigen::Matrix<double, 6, Eigen::Dynamic> J(6, arm);
      J.topRows<3>() =
          robots::point_jacobian(model_, data_, model_.tcp.link, model_.tcp.point).leftCols(arm);
      J.bottomRows<3>() = robots::vector_jacobian(model_, data_, model_.v_fwd).leftCols(arm);
      Eigen::Matrix<double, 6, 1> e;
      e << e_p, e_v;
      const Eigen::Matrix<double, 6, 6> JJt =
          J * J.transpose() + 1e-4 * Eigen::Matrix<double, 6, 6>::Identity();
      Eigen::VectorXd q_new = q;
      q_new.head(arm) += J.transpose() * JJt.ldlt().solve(e);
      q_new = model_.clamp(q_new);
      bool contact = false;
      if (!free(q, q_new, &contact)) return contact ? node : -1;
      node = add(q_new, node);
    }
    return -1;  // the hand did not reach the object
  }

  // Closes the hand at `node` and scores the grasp; a scored grasp ends the search and is checked
  // as a clasp.
  bool grasp(int node) {
    const auto t = Clock::now();
    const Eigen::VectorXd q =
        tsrrt::close_fingers(model_, scene_.world, nodes_[node].q, scene_.planning.closing);
    r_.timings.closing += since(t);
    ++r_.statistics.clasp_candidates;
    robots::forward_kinematics(model_, q, data_);
    const double touch = 2.0 * scene_.planning.closing.clearance + 0.001;
    int touching = 0;
    bool thumb = false, has_thumb = false;
    for (const auto& finger : model_.fingers) {
      has_thumb |= finger.thumb;
      for (int link : finger.links) {
        if (scene_.world.link_near_object(data_, link, touch)) {
          ++touching;
          thumb |= finger.thumb;
          break;
        }
      }
    }
    if (touching < o_.min_contact_fingers || (has_thumb && !thumb)) return false;
    r_.status = tsrrt::ClaspStatus::kSuccess;
    for (int i = node; i >= 0; i = nodes_[i].parent) r_.motion.waypoints.push_back(nodes_[i].q);
    std::reverse(r_.motion.waypoints.begin(), r_.motion.waypoints.end());
    r_.motion.waypoints.push_back(q);
    const auto t_check = Clock::now();
    r_.verification = scene_.checker.check(q, scene_.loop.points);
    r_.timings.verification += since(t_check);
    r_.verified = r_.verification.secure;
    r_.reason = r_.verified ? "verified clasp (a grasp that is a clasp)"
                            : "a grasp with " + std::to_string(touching) +
                                  " fingers on the object, but not a clasp: the object got free "
                                  "in " +
                                  std::to_string(r_.verification.escaped_sequences) + " of " +
                                  std::to_string(r_.verification.sequences) + " sequences";
    return true;
  }

  const tsrrt::ClaspScene& scene_;
  const robots::RobotModel& model_;
  tsrrt::ClaspResult& r_;
  const GraspRrtOptions& o_;
  robots::RobotData data_;
  std::mt19937_64 rng_;
  Eigen::VectorXd lower_, upper_;
  Eigen::Vector3d centre_ = Eigen::Vector3d::Zero();
  std::vector<Node> nodes_;
};

}  // namespace

void grasp_rrt(const tsrrt::ClaspScene& scene, tsrrt::ClaspResult& result,
               const GraspRrtOptions& options) {
  if (result.collision_mesh.triangles.empty()) {
    result.reason = "Grasp-RRT baseline: the object has no surface to approach";
    return;
  }
  GraspRrt(scene, result, options).run();
}

}  // namespace claspplan::cli
