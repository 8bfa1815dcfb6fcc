// Collision checking of the robot against the object, a static environment and itself (FCL 0.7).
//
// - Robot: the links' primitives (boxes, spheres, cylinders, capsules) from the URDF.
// - Object: a triangle mesh (the K_d triangles) as an FCL BVH (OBBRSS) with a movable pose.
// - Environment: static boxes and cylinders (table, walls, obstacles), and voxels of space no
//   sensor saw near the object (an OcTree).
// - Self-collision: every pair of links except (a) adjacent links: a link and its nearest ancestor
//   that has collision geometry (links without geometry are skipped, so the palm is adjacent to
//   link_6 through flange/tool0), (b) pairs whose relative pose does not depend on q (e.g. the
//   SDH thumb base and the palm), (c) the description's `collision.allowed_pairs`.
// - Links rigidly attached to the world (the root link and what is fixed to it) are not checked
//   against the object or the environment: they cannot move, and the base usually stands on the
//   table.
// Broad phase: each shape's world AABB (computed in closed form from the primitive) against the
// object's bounding box (tested in the object's frame) and each environment item's AABB; FCL's
// narrow phase runs only on overlaps and stops at the first contact.
//
// Motions are checked by interpolation (FCL's continuous collision is unreliable for meshes).
// A CollisionWorld keeps internal scratch state: use one per thread.
#pragma once

#include <memory>
#include <string>
#include <utility>
#include <vector>

#include <Eigen/Core>
#include <Eigen/Geometry>

#include "robots/kinematics.hpp"
#include "robots/robot_model.hpp"

namespace claspplan::robots {

/// Which two things touched (the first contact found).
struct CollisionReport {
  std::string first;   ///< a link name
  std::string second;  ///< a link name, "object", "box <i>" or "cylinder <i>"
  int first_link = -1;
  int second_link = -1;  ///< -1 unless `second` is a link
};

/// An object's collision geometry: FCL bounding-volume trees and, for exact round shapes, a
/// TriangleTree. Built once and shared read-only by any number of worlds and threads (the
/// secure-clasp check tests many hand poses against one object).
struct ObjectGeometry;

/// Builds it from a triangle mesh (vertices in the object frame); `exact_round_shapes` adds what
/// CollisionWorld::set_exact_round_shapes(true) needs. Triangles with a repeated vertex are
/// skipped. Throws std::invalid_argument for NaN/Inf vertices, indices out of range, or no
/// usable triangle.
std::shared_ptr<const ObjectGeometry> make_object_geometry(
    const std::vector<Eigen::Vector3d>& vertices, const std::vector<Eigen::Vector3i>& triangles,
    bool exact_round_shapes);

/// A robot shape against an environment item, as a collision query left them.
struct EnvironmentHit {
  int shape = -1;  ///< the robot's collision shape (-1: no hit)
  int item = -1;   ///< the environment item
  Eigen::Isometry3d shape_pose = Eigen::Isometry3d::Identity();  ///< the shape's, world frame
};

class CollisionWorld {
 public:
  /// Keeps its own copy of the model.
  explicit CollisionWorld(const RobotModel& model);
  ~CollisionWorld();
  CollisionWorld(CollisionWorld&&) noexcept;
  CollisionWorld& operator=(CollisionWorld&&) noexcept;
  CollisionWorld(const CollisionWorld&) = delete;
  CollisionWorld& operator=(const CollisionWorld&) = delete;

  const RobotModel& model() const;

  // --- Object ---------------------------------------------------------------------------------
  /// Replaces the object by a triangle mesh (vertices in the object frame). Triangles with a
  /// repeated vertex are skipped. Throws std::invalid_argument for NaN/Inf vertices, indices out
  /// of range, or no usable triangle.
  void set_object(const std::vector<Eigen::Vector3d>& vertices,
                  const std::vector<Eigen::Vector3i>& triangles);
  /// Shares a prebuilt object (with exact round shapes on, one built for them).
  void set_object(std::shared_ptr<const ObjectGeometry> geometry);
  /// The object's pose in the world (default identity).
  void set_object_pose(const Eigen::Isometry3d& pose);
  const Eigen::Isometry3d& object_pose() const;
  void clear_object();
  bool has_object() const;
  int object_triangles() const;

  // --- Static environment
  // -------------------------------------------------------------------------
  /// A box with full edge lengths `size`, centred at pose. Returns its index among the boxes.
  int add_box(const Eigen::Isometry3d& pose, const Eigen::Vector3d& size);
  /// A cylinder along the pose's z axis, centred at pose. Returns its index among the cylinders.
  int add_cylinder(const Eigen::Isometry3d& pose, double radius, double length);
  /// Cubes of edge `edge` centred at `centres` that the robot must not enter, held as an OctoMap
  /// OcTree that FCL collides against. `kind` says what they stand for:
  /// - kUnseen: the sensed space's unseen voxels near the object (perception/sensed_space.hpp),
  ///   reported as "unseen space", unless the same shape touches the object too (it went through
  ///   the seen surface into the unknown behind it, so it met the object first, and a collision
  ///   query says "object");
  /// - kMeasured: voxels holding measured points that the object's mesh leaves out (a wire too
  ///   thin for the depth surface), reported as "object": they are seen material. Add them before
  ///   unseen voxels: a shape through both met the material first.
  /// Centres should lie on a grid of spacing `edge` aligned with multiples of it (as
  /// SensedSpace's are). Throws std::invalid_argument for a non-finite centre or edge <= 0.
  /// Nothing is added for no centres.
  enum class VoxelKind { kUnseen, kMeasured };
  void add_voxels(const std::vector<Eigen::Vector3d>& centres, double edge,
                  VoxelKind kind = VoxelKind::kUnseen);
  void clear_environment();

  // --- Options
  // ------------------------------------------------------------------------------------
  /// Self-collision checks on/off (default on).
  void set_self_collision(bool enabled);
  /// Checks between two hand links (finger against finger or palm) on/off (default on).
  void set_hand_self_collision(bool enabled);
  /// Spheres and capsules against the object by their exact distance to its triangles (own
  /// bounding-box tree, TriangleTree) instead of FCL's GJK: several times faster; the answer
  /// differs only where a shape touches a triangle within GJK's tolerance. Default off.
  void set_exact_round_shapes(bool enabled);
  /// Motions are also sampled so that no point of the robot travels more than `metres` between
  /// two checked configurations (motion_sampling.hpp's bound), whatever the joint resolution: at
  /// 0.02 rad a point 0.6 m out moves 12 mm, and a finger can step over a 4 mm wire. 0: off (the
  /// default). Throws std::invalid_argument for a negative or non-finite value.
  void set_motion_travel(double metres);
  double motion_travel() const;
  /// The link pairs (i < j) that self-collision checks, with the options in force.
  std::vector<std::pair<int, int>> self_collision_pairs() const;

  // --- Queries (data must come from forward_kinematics with this model) -------------------------
  /// Any contact: robot vs object, robot vs environment, robot vs itself.
  bool in_collision(const RobotData& data, CollisionReport* report = nullptr);
  /// Every pair of the robot's links in contact with each other (link names, in the order the
  /// checks meet them, each pair once): all the pairs to allow at once, not one per run.
  std::vector<std::pair<std::string, std::string>> self_contacts(const RobotData& data);
  /// Runs FK at q first (q.size() == dof, finite).
  bool in_collision(const Eigen::VectorXd& q, CollisionReport* report = nullptr);

  /// Does the robot touch the object (environment and self-collision not tested)? For many object
  /// poses against one configuration, as in the secure-clasp check: the shapes are placed once
  /// per configuration and the shape that touched last is tried first (the same answer as the
  /// object part of in_collision, found sooner).
  bool object_in_collision(const RobotData& data);

  /// Does `link` touch the object or the environment (and, with `include_self`, another link of
  /// the robot that self-collision would check against it)? Used to close fingers until contact.
  bool link_in_collision(const RobotData& data, int link, CollisionReport* report = nullptr,
                         bool include_self = false);

  /// Is `link` within `clearance` of the object? A collision query with every shape of the link
  /// grown by `clearance` (spheres and capsules exactly; boxes and cylinders grow their sizes, so
  /// edges and corners reach up to 0.42·clearance farther). About as cheap as link_in_collision:
  /// the query for closing a finger until it is about to touch.
  bool link_near_object(const RobotData& data, int link, double clearance);

  /// Distance from `link`'s shapes to the object, capped at max_distance (returned when the
  /// object is farther, or when there is no object); 0 when they touch. Shapes whose bounding box
  /// is farther than max_distance from the object's are skipped, but a shape near a fine mesh
  /// costs FCL's exact distance (~0.1 ms near a 30,000-triangle mesh): prefer link_near_object.
  double link_object_distance(const RobotData& data, int link, double max_distance = 0.05);

  /// The straight joint-space motion q0 -> q1 is free when every configuration on it, sampled so
  /// that no joint moves more than `resolution` (rad or m) between samples (nor any robot point
  /// more than set_motion_travel()'s distance), is free. Both ends are
  /// checked; samples are visited coarse-to-fine (bisection order), so collisions show early.
  bool motion_free(const Eigen::VectorXd& q0, const Eigen::VectorXd& q1, double resolution,
                   CollisionReport* report = nullptr) {
    return motion_free(q0, q1, resolution, motion_travel(), report);
  }
  /// The same with its own travel bound (m, >= 0; 0: joint resolution alone) in place of
  /// set_motion_travel()'s, for a caller that needs a finer check than the world's other users.
  bool motion_free(const Eigen::VectorXd& q0, const Eigen::VectorXd& q1, double resolution,
                   double travel, CollisionReport* report = nullptr);

  /// What the last in_collision, link_in_collision or motion_free touched of the environment (a
  /// box, a cylinder, unseen space): no hit when its contact was another (the object, the robot
  /// itself), it found none, or a later query moved the shape. Cheap to keep; contact_point() makes
  /// it a point.
  EnvironmentHit environment_hit() const;

  /// Where `hit` touched, world frame: FCL's contact point, or the middle of the two bounding
  /// boxes' overlap; NaN for no hit. A contact point costs more than the yes/no answer, which is
  /// all most callers need, so it is computed only on request. The hit must come from this world
  /// with its environment unchanged since.
  Eigen::Vector3d contact_point(const EnvironmentHit& hit) const;
  /// contact_point() of each hit, in order.
  std::vector<Eigen::Vector3d> contact_points(const std::vector<EnvironmentHit>& hits) const {
    std::vector<Eigen::Vector3d> points;
    for (const EnvironmentHit& hit : hits) points.push_back(contact_point(hit));
    return points;
  }

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace claspplan::robots
