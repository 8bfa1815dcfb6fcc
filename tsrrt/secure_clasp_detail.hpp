// Internal pieces of the secure-clasp check (paper Sec. V-A) shared by check_secure_clasp() and the
// reference implementation the tests compare it with: the random motions, the escape test, the
// pivot and the Fig. 6 values. Not installed.
#pragma once

#include <cstdint>
#include <functional>
#include <random>
#include <vector>

#include <Eigen/Geometry>

#include "robots/robot_model.hpp"
#include "servo/linking.hpp"
#include "tsrrt/secure_clasp.hpp"

namespace claspplan::tsrrt::detail {

using Curves = std::vector<std::vector<Eigen::Vector3d>>;

/// What every sequence of a check shares: the closed hand's finger curves, the loop and the
/// pivot (the loop point nearest the hand: the clasped segment).
struct ClaspCheckContext {
  Curves curves;
  servo::Points loop;
  Eigen::Vector3d pivot = Eigen::Vector3d::Zero();
};

/// The context at q, and the report's Fig. 6 values (open and virtual linking at q).
ClaspCheckContext clasp_check_context(const robots::RobotModel& model, const Eigen::VectorXd& q,
                                      const servo::Points& loop, SecureClaspReport& report);

/// A uniformly distributed unit vector, by rejection from the cube (platform-independent).
Eigen::Vector3d random_unit(std::mt19937_64& rng);

/// The random stream of sequence `s` of a check with `seed`: the same whatever runs it.
std::uint64_t sequence_seed(std::uint64_t seed, int s);

/// Smallest distance from the loop's vertices to the finger curves' segments.
double loop_hand_distance(const servo::Points& loop, const Curves& curves);

/// Does the object, moved by T from its start, hold no more (see SecureClaspOptions)?
bool object_free(const ClaspCheckContext& c, const Eigen::Isometry3d& T, double free_distance);

/// One random motion: a screw drawn from rng, pursued from T in small steps until `collides`
/// (the object's pose from its start) says true or steps_per_motion ran; T is the last free pose.
/// Returns whether the object is free after it.
bool random_motion(const ClaspCheckContext& c, const SecureClaspOptions& o, std::mt19937_64& rng,
                   Eigen::Isometry3d& T,
                   const std::function<bool(const Eigen::Isometry3d&)>& collides);

}  // namespace claspplan::tsrrt::detail
