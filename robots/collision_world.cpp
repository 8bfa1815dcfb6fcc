#include "robots/collision_world.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <optional>
#include <stdexcept>

#include <fcl/geometry/bvh/BVH_model.h>
#include <fcl/geometry/octree/octree.h>
#include <fcl/geometry/shape/box.h>
#include <fcl/geometry/shape/capsule.h>
#include <fcl/geometry/shape/cylinder.h>
#include <fcl/geometry/shape/sphere.h>
#include <fcl/narrowphase/collision.h>
#include <fcl/narrowphase/distance.h>
#include <octomap/OcTree.h>

#include "robots/motion_sampling.hpp"
#include "robots/object_geometry.hpp"
#include "robots/triangle_tree.hpp"

namespace claspplan::robots {
namespace {

// Closed-form half extents of a primitive's axis-aligned box, for a shape rotated by R (a mesh:
// its own box's).
struct Primitive {
  CollisionShape::Type type;
  Eigen::Vector3d centre{0, 0, 0};  // mesh: its box's centre in the shape frame
  Eigen::Vector3d half{0, 0, 0};    // box (mesh: its box's) half sizes
  double radius = 0.0;
  double half_length = 0.0;  // cylinder / capsule: half of the axis length

  Box3 bounds(const Eigen::Isometry3d& tf) const {
    const Eigen::Matrix3d& R = tf.linear();
    Eigen::Vector3d e = Eigen::Vector3d::Zero();
    switch (type) {
      case CollisionShape::Type::kBox:
      case CollisionShape::Type::kMesh:
        e = R.cwiseAbs() * half;
        break;
      case CollisionShape::Type::kSphere:
        e.setConstant(radius);
        break;
      case CollisionShape::Type::kCapsule:
        e = R.col(2).cwiseAbs() * half_length + Eigen::Vector3d::Constant(radius);
        break;
      case CollisionShape::Type::kCylinder: {
        const Eigen::Vector3d a = R.col(2);
        for (int k = 0; k < 3; ++k)
          e[k] =
              std::abs(a[k]) * half_length + radius * std::sqrt(std::max(0.0, 1.0 - a[k] * a[k]));
        break;
      }
    }
    const Eigen::Vector3d c = tf * centre;
    return {c - e, c + e};
  }
};

struct RobotShape {
  int link = -1;
  Geometry geometry;
  Eigen::Isometry3d origin;
  Primitive primitive;
};

struct EnvItem {
  std::string name;
  Geometry geometry;
  Eigen::Isometry3d pose;
  Box3 box;
  // add_voxels' kind; none for a box or a cylinder.
  std::optional<CollisionWorld::VoxelKind> voxels = std::nullopt;
};

Geometry make_geometry(const CollisionShape& s) {
  switch (s.type) {
    case CollisionShape::Type::kBox:
      return std::make_shared<fcl::Boxd>(s.size);
    case CollisionShape::Type::kSphere:
      return std::make_shared<fcl::Sphered>(s.radius);
    case CollisionShape::Type::kCylinder:
      return std::make_shared<fcl::Cylinderd>(s.radius, s.length);
    case CollisionShape::Type::kCapsule:
      return std::make_shared<fcl::Capsuled>(s.radius, s.length);
    case CollisionShape::Type::kMesh: {
      std::vector<fcl::Triangle> triangles;
      for (const auto& t : s.mesh->triangles) triangles.emplace_back(t[0], t[1], t[2]);
      return build_bvh<Mesh>(s.mesh->vertices, triangles);
    }
  }
  throw std::logic_error("unknown collision shape type");
}

Primitive make_primitive(const CollisionShape& s) {
  Primitive p;
  p.type = s.type;
  p.half = 0.5 * s.size;
  if (s.type == CollisionShape::Type::kMesh) {
    const Eigen::AlignedBox3d b = shape_bounds(s);
    p.centre = b.center();
    p.half = 0.5 * b.sizes();
  }
  p.radius = s.radius;
  p.half_length = 0.5 * s.length;
  return p;
}

bool fcl_collide(const fcl::CollisionGeometryd* a, const Eigen::Isometry3d& ta,
                 const fcl::CollisionGeometryd* b, const Eigen::Isometry3d& tb) {
  fcl::CollisionRequestd request(1, false);  // the first contact is enough
  fcl::CollisionResultd result;
  fcl::collide(a, ta, b, tb, request, result);
  return result.isCollision();
}

// Where a and b touch: FCL's first contact point, or the middle of their boxes' overlap when
// FCL gives none for this pair of geometries.
Eigen::Vector3d fcl_contact_point(const fcl::CollisionGeometryd* a, const Eigen::Isometry3d& ta,
                                  const fcl::CollisionGeometryd* b, const Eigen::Isometry3d& tb,
                                  const Box3& box_a, const Box3& box_b) {
  fcl::CollisionRequestd request(1, /*enable_contact=*/true);
  fcl::CollisionResultd result;
  fcl::collide(a, ta, b, tb, request, result);
  if (result.numContacts() > 0 && result.getContact(0).pos.allFinite())
    return result.getContact(0).pos;
  return 0.5 * (box_a.lo.cwiseMax(box_b.lo) + box_a.hi.cwiseMin(box_b.hi));
}

}  // namespace

struct CollisionWorld::Impl {
  RobotModel model;
  RobotData data;
  RobotData scratch;  // for motion_free, so that `data` stays usable by the caller

  std::vector<RobotShape> shapes;
  std::vector<bool> static_link;  // rigidly attached to the world
  std::vector<int> rigid_group;
  std::vector<int> geometric_parent;

  // Per query: shapes' world transforms and boxes.
  std::vector<Eigen::Isometry3d> tf;
  std::vector<Box3> box;
  // object_in_collision: the configuration every shape is placed at (empty: not placed since a
  // query placed some), and the shape that touched the object last.
  Eigen::VectorXd placed_q;
  int last_hit = -1;
  // The last full check's contact with the environment: shape and item (-1: none). The shape
  // stays placed (tf, box) until the next check.
  std::pair<int, int> env_hit{-1, -1};

  Eigen::VectorXd reach;  // motion_reach(model), once a motion check bounds travel
  double travel = 0.0;
  bool self_enabled = true;
  bool hand_self_enabled = true;
  std::vector<std::pair<int, int>> link_pairs;   // self-collision link pairs
  std::vector<std::pair<int, int>> shape_pairs;  // the same as shape pairs

  std::shared_ptr<const ObjectGeometry> object;
  bool exact_round = false;
  Eigen::Isometry3d object_pose = Eigen::Isometry3d::Identity();
  Eigen::Isometry3d object_pose_inv = Eigen::Isometry3d::Identity();

  std::vector<EnvItem> environment;
  int boxes = 0, cylinders = 0;

  explicit Impl(const RobotModel& m) : model(m), data(m), scratch(m) {
    const size_t n = model.links.size();
    static_link.assign(n, false);
    rigid_group.assign(n, 0);
    geometric_parent.assign(n, -1);
    for (size_t i = 0; i < n; ++i) {
      const Link& l = model.links[i];
      const bool moves = l.type != JointType::kFixed && l.q_index >= 0;
      rigid_group[i] = (l.parent < 0) ? 0 : (moves ? static_cast<int>(i) : rigid_group[l.parent]);
      static_link[i] = rigid_group[i] == 0;
      int p = l.parent;
      while (p >= 0 && model.links[p].shapes.empty()) p = model.links[p].parent;
      geometric_parent[i] = p;
    }
    for (const CollisionShape& s : model.shapes)
      shapes.push_back({s.link, make_geometry(s), s.origin, make_primitive(s)});
    tf.resize(shapes.size());
    box.resize(shapes.size());
    rebuild_pairs();
  }

  void rebuild_pairs() {
    link_pairs.clear();
    shape_pairs.clear();
    if (!self_enabled) return;
    const int n = static_cast<int>(model.links.size());
    for (int a = 0; a < n; ++a) {
      if (model.links[a].shapes.empty()) continue;
      for (int b = a + 1; b < n; ++b) {
        if (model.links[b].shapes.empty()) continue;
        if (geometric_parent[a] == b || geometric_parent[b] == a) continue;
        if (rigid_group[a] == rigid_group[b]) continue;
        if (std::binary_search(model.allowed_pairs.begin(), model.allowed_pairs.end(),
                               std::make_pair(a, b)))
          continue;
        if (!hand_self_enabled && model.links[a].hand && model.links[b].hand) continue;
        link_pairs.emplace_back(a, b);
        for (int sa : model.links[a].shapes)
          for (int sb : model.links[b].shapes) shape_pairs.emplace_back(sa, sb);
      }
    }
  }

  void check_data(const RobotData& d) const {
    if (d.link_poses.size() != model.links.size() || d.q.size() != model.dof())
      throw std::invalid_argument(model.name + ": RobotData does not belong to this robot");
  }

  void place(const RobotData& d, int s) {
    placed_q.resize(0);
    if (s == env_hit.first) env_hit = {-1, -1};  // moved: its contact is gone
    tf[s] = d.link_poses[shapes[s].link] * shapes[s].origin;
    box[s] = shapes[s].primitive.bounds(tf[s]);
  }

  void place_all(const RobotData& d) {
    for (size_t s = 0; s < shapes.size(); ++s) place(d, static_cast<int>(s));
  }

  // Shape vs object, both culled by the object's box in the object's frame.
  bool shape_hits_object(int s) {
    if (!object) return false;
    const Eigen::Isometry3d local = object_pose_inv * tf[s];
    const Primitive& p = shapes[s].primitive;
    if (!p.bounds(local).overlaps(object->local_box)) return false;
    if (exact_round && object->tree &&
        (p.type == CollisionShape::Type::kSphere || p.type == CollisionShape::Type::kCapsule)) {
      const Eigen::Vector3d axis = local.linear().col(2) * p.half_length;
      return object->tree->touches_capsule(local.translation() - axis, local.translation() + axis,
                                           p.radius);
    }
    return fcl_collide(shapes[s].geometry.get(), tf[s], object_for(p.type), object_pose);
  }

  // What a shape collides the object as: FCL collides two meshes only in one kind of bounding
  // volume (else it warns and reports no contact), so a robot mesh (OBBRSS) meets the object's
  // OBBRSS tree even where the exact round shapes' OBB tree is in use.
  const fcl::CollisionGeometryd* object_for(CollisionShape::Type type) const {
    if (type == CollisionShape::Type::kMesh && object->tree) return &object->distance_mesh();
    return object->collide.get();
  }

  int shape_hits_environment(int s) {
    for (size_t e = 0; e < environment.size(); ++e) {
      if (!box[s].overlaps(environment[e].box)) continue;
      if (fcl_collide(shapes[s].geometry.get(), tf[s], environment[e].geometry.get(),
                      environment[e].pose))
        return static_cast<int>(e);
    }
    return -1;
  }

  bool shapes_collide(int a, int b) {
    if (!box[a].overlaps(box[b])) return false;
    return fcl_collide(shapes[a].geometry.get(), tf[a], shapes[b].geometry.get(), tf[b]);
  }

  void report(CollisionReport* r, int link_a, const std::string& other, int link_b = -1) const {
    if (!r) return;
    r->first = model.links[link_a].name;
    r->first_link = link_a;
    r->second = link_b >= 0 ? model.links[link_b].name : other;
    r->second_link = link_b;
  }

  bool external(int s, CollisionReport* r) {
    const int link = shapes[s].link;
    if (static_link[link]) return false;
    const int e = shape_hits_environment(s);
    // Measured voxels are the object's material. Unseen voxels lie behind the seen surface too:
    // a shape through both met the object first.
    using Kind = CollisionWorld::VoxelKind;
    const bool object = (e >= 0 && environment[e].voxels == Kind::kMeasured) ||
                        ((e < 0 || environment[e].voxels == Kind::kUnseen) && shape_hits_object(s));
    if (object) {
      report(r, link, "object");
      return true;
    }
    if (e >= 0) {
      report(r, link, environment[e].name);
      env_hit = {s, e};
      return true;
    }
    return false;
  }

  bool check(const RobotData& d, CollisionReport* r) {
    if (r) *r = CollisionReport{};
    env_hit = {-1, -1};
    place_all(d);
    for (size_t s = 0; s < shapes.size(); ++s)
      if (external(static_cast<int>(s), r)) return true;
    for (const auto& [a, b] : shape_pairs) {
      if (shapes_collide(a, b)) {
        report(r, shapes[a].link, "", shapes[b].link);
        return true;
      }
    }
    return false;
  }
};

CollisionWorld::CollisionWorld(const RobotModel& model) : impl_(std::make_unique<Impl>(model)) {}
CollisionWorld::~CollisionWorld() = default;
CollisionWorld::CollisionWorld(CollisionWorld&&) noexcept = default;
CollisionWorld& CollisionWorld::operator=(CollisionWorld&&) noexcept = default;

const RobotModel& CollisionWorld::model() const {
  return impl_->model;
}

void CollisionWorld::set_object(const std::vector<Eigen::Vector3d>& vertices,
                                const std::vector<Eigen::Vector3i>& triangles) {
  impl_->object = make_object_geometry(vertices, triangles, impl_->exact_round);
}

void CollisionWorld::set_object(std::shared_ptr<const ObjectGeometry> geometry) {
  if (!geometry) throw std::invalid_argument("collision object: no geometry");
  if (impl_->exact_round && !geometry->tree)
    throw std::logic_error("set_object: exact round shapes need a geometry built for them");
  impl_->object = std::move(geometry);
}

void CollisionWorld::set_object_pose(const Eigen::Isometry3d& pose) {
  if (!pose.matrix().allFinite()) throw std::invalid_argument("object pose is not finite");
  impl_->object_pose = pose;
  impl_->object_pose_inv = pose.inverse();
}

const Eigen::Isometry3d& CollisionWorld::object_pose() const {
  return impl_->object_pose;
}
void CollisionWorld::clear_object() {
  impl_->object.reset();
}
bool CollisionWorld::has_object() const {
  return impl_->object != nullptr;
}
int CollisionWorld::object_triangles() const {
  return impl_->object ? impl_->object->triangles : 0;
}

int CollisionWorld::add_box(const Eigen::Isometry3d& pose, const Eigen::Vector3d& size) {
  if (!pose.matrix().allFinite() || !size.allFinite() || (size.array() <= 0).any())
    throw std::invalid_argument("environment box: pose and sizes must be finite, sizes > 0");
  Primitive p;
  p.type = CollisionShape::Type::kBox;
  p.half = 0.5 * size;
  const int index = impl_->boxes++;
  impl_->environment.push_back(
      {"box " + std::to_string(index), std::make_shared<fcl::Boxd>(size), pose, p.bounds(pose)});
  return index;
}

int CollisionWorld::add_cylinder(const Eigen::Isometry3d& pose, double radius, double length) {
  if (!pose.matrix().allFinite() || !std::isfinite(radius) || !std::isfinite(length) ||
      radius <= 0 || length <= 0)
    throw std::invalid_argument(
        "environment cylinder: pose, radius and length must be finite, > 0");
  Primitive p;
  p.type = CollisionShape::Type::kCylinder;
  p.radius = radius;
  p.half_length = 0.5 * length;
  const int index = impl_->cylinders++;
  impl_->environment.push_back({"cylinder " + std::to_string(index),
                                std::make_shared<fcl::Cylinderd>(radius, length), pose,
                                p.bounds(pose)});
  return index;
}

void CollisionWorld::add_voxels(const std::vector<Eigen::Vector3d>& centres, double edge,
                                VoxelKind kind) {
  if (!(edge > 0) || !std::isfinite(edge))
    throw std::invalid_argument("environment voxels: the edge must be finite and > 0");
  if (centres.empty()) return;
  auto tree = std::make_shared<octomap::OcTree>(edge);
  Eigen::AlignedBox3d bounds;
  for (const auto& c : centres) {
    if (!c.allFinite()) throw std::invalid_argument("environment voxels: a centre is not finite");
    // The node's log-odds set at once (no sensor model: these voxels are occupied by rule).
    tree->setNodeValue(octomap::point3d(static_cast<float>(c.x()), static_cast<float>(c.y()),
                                        static_cast<float>(c.z())),
                       tree->getClampingThresMaxLog(), /*lazy_eval=*/true);
    bounds.extend(c);
  }
  tree->updateInnerOccupancy();
  tree->prune();  // uniform blocks of 8 become one node: fewer nodes for FCL to visit
  const Eigen::Vector3d half = Eigen::Vector3d::Constant(0.5 * edge);
  impl_->environment.push_back(
      {kind == VoxelKind::kUnseen ? "unseen space" : "measured points",
       std::make_shared<fcl::OcTreed>(std::shared_ptr<const octomap::OcTree>(std::move(tree))),
       Eigen::Isometry3d::Identity(), Box3{bounds.min() - half, bounds.max() + half}, kind});
}

void CollisionWorld::clear_environment() {
  impl_->environment.clear();
  impl_->boxes = impl_->cylinders = 0;
}

void CollisionWorld::set_self_collision(bool enabled) {
  impl_->self_enabled = enabled;
  impl_->rebuild_pairs();
}

void CollisionWorld::set_exact_round_shapes(bool enabled) {
  if (enabled && impl_->object && !impl_->object->tree)
    throw std::logic_error("set_exact_round_shapes(true) must come before set_object()");
  impl_->exact_round = enabled;
}

void CollisionWorld::set_hand_self_collision(bool enabled) {
  impl_->hand_self_enabled = enabled;
  impl_->rebuild_pairs();
}

std::vector<std::pair<int, int>> CollisionWorld::self_collision_pairs() const {
  return impl_->link_pairs;
}

bool CollisionWorld::in_collision(const RobotData& data, CollisionReport* report) {
  impl_->check_data(data);
  return impl_->check(data, report);
}

std::vector<std::pair<std::string, std::string>> CollisionWorld::self_contacts(
    const RobotData& data) {
  Impl& m = *impl_;
  m.check_data(data);
  m.place_all(data);
  std::vector<std::pair<std::string, std::string>> out;
  for (const auto& [a, b] : m.shape_pairs) {
    const std::pair<std::string, std::string> links{m.model.links[m.shapes[a].link].name,
                                                    m.model.links[m.shapes[b].link].name};
    if (std::find(out.begin(), out.end(), links) == out.end() && m.shapes_collide(a, b))
      out.push_back(links);
  }
  return out;
}

bool CollisionWorld::in_collision(const Eigen::VectorXd& q, CollisionReport* report) {
  if (!q.allFinite()) throw std::invalid_argument(impl_->model.name + ": q is not finite");
  forward_kinematics(impl_->model, q, impl_->data);
  return impl_->check(impl_->data, report);
}

bool CollisionWorld::object_in_collision(const RobotData& data) {
  Impl& m = *impl_;
  m.check_data(data);
  const int n = static_cast<int>(m.shapes.size());
  if (m.placed_q.size() == 0 || m.placed_q != data.q) {
    m.place_all(data);
    m.placed_q = data.q;
  }
  const auto hits = [&](int s) {
    return !m.static_link[m.shapes[s].link] && m.shape_hits_object(s);
  };
  if (m.last_hit >= 0 && hits(m.last_hit)) return true;
  for (int s = 0; s < n; ++s)
    if (s != m.last_hit && hits(s)) {
      m.last_hit = s;
      return true;
    }
  return false;
}

bool CollisionWorld::link_in_collision(const RobotData& data, int link, CollisionReport* report,
                                       bool include_self) {
  Impl& m = *impl_;
  m.check_data(data);
  if (link < 0 || link >= static_cast<int>(m.model.links.size()))
    throw std::invalid_argument("link index " + std::to_string(link) + " out of range");
  if (report) *report = CollisionReport{};
  const auto& own = m.model.links[link].shapes;
  for (int s : own) {
    m.place(data, s);
    if (m.external(s, report)) return true;
  }
  if (!include_self) return false;
  for (const auto& [a, b] : m.link_pairs) {
    if (a != link && b != link) continue;
    const int other = a == link ? b : a;
    for (int s : m.model.links[other].shapes) m.place(data, s);
    for (int s : own) {
      for (int o : m.model.links[other].shapes) {
        if (m.shapes_collide(s, o)) {
          m.report(report, link, "", other);
          return true;
        }
      }
    }
  }
  return false;
}

bool CollisionWorld::link_near_object(const RobotData& data, int link, double clearance) {
  Impl& m = *impl_;
  m.check_data(data);
  if (link < 0 || link >= static_cast<int>(m.model.links.size()))
    throw std::invalid_argument("link index " + std::to_string(link) + " out of range");
  if (!(clearance >= 0) || !std::isfinite(clearance))
    throw std::invalid_argument("link_near_object: clearance must be finite and >= 0");
  if (!m.object) return false;
  for (int s : m.model.links[link].shapes) {
    m.place(data, s);
    CollisionShape grown = m.model.shapes[s];
    Eigen::Isometry3d tf = m.tf[s];
    if (grown.type == CollisionShape::Type::kMesh) {  // its box, which holds it
      const Eigen::AlignedBox3d box = shape_bounds(grown);
      grown.type = CollisionShape::Type::kBox;
      grown.size = box.sizes();
      tf = tf * Eigen::Translation3d(box.center());
    }
    grown.radius += clearance;
    grown.size += Eigen::Vector3d::Constant(2 * clearance);
    if (grown.type == CollisionShape::Type::kCylinder) grown.length += 2 * clearance;
    const Primitive p = make_primitive(grown);
    if (!p.bounds(m.object_pose_inv * tf).overlaps(m.object->local_box)) continue;
    const Geometry g = make_geometry(grown);
    if (fcl_collide(g.get(), tf, m.object_for(grown.type), m.object_pose)) return true;
  }
  return false;
}

double CollisionWorld::link_object_distance(const RobotData& data, int link, double max_distance) {
  Impl& m = *impl_;
  m.check_data(data);
  if (link < 0 || link >= static_cast<int>(m.model.links.size()))
    throw std::invalid_argument("link index " + std::to_string(link) + " out of range");
  double best = max_distance;
  if (!m.object) return best;
  for (int s : m.model.links[link].shapes) {
    m.place(data, s);
    const Eigen::Isometry3d local = m.object_pose_inv * m.tf[s];
    if (m.shapes[s].primitive.bounds(local).distance(m.object->local_box) >= best) continue;
    const Mesh& mesh = m.object->distance_mesh();
    if (fcl_collide(m.shapes[s].geometry.get(), m.tf[s], &mesh, m.object_pose)) return 0.0;
    // FCL's own GJK is ~1.7x faster than libccd for mesh distances (measured); not for collisions.
    fcl::DistanceRequestd request(false, false, 0.0, 0.0, 1e-6, fcl::GST_INDEP);
    fcl::DistanceResultd result;
    const double d =
        fcl::distance(m.shapes[s].geometry.get(), m.tf[s], &mesh, m.object_pose, request, result);
    best = std::min(best, std::max(0.0, d));
  }
  return best;
}

EnvironmentHit CollisionWorld::environment_hit() const {
  const Impl& m = *impl_;
  const auto [s, e] = m.env_hit;
  if (s < 0) return {};
  return {s, e, m.tf[s]};
}

Eigen::Vector3d CollisionWorld::contact_point(const EnvironmentHit& hit) const {
  const Impl& m = *impl_;
  if (hit.shape < 0) return Eigen::Vector3d::Constant(std::numeric_limits<double>::quiet_NaN());
  const RobotShape& shape = m.shapes.at(hit.shape);
  const auto& item = m.environment.at(hit.item);
  return fcl_contact_point(shape.geometry.get(), hit.shape_pose, item.geometry.get(), item.pose,
                           shape.primitive.bounds(hit.shape_pose), item.box);
}

void CollisionWorld::set_motion_travel(double metres) {
  if (!(metres >= 0) || !std::isfinite(metres))
    throw std::invalid_argument("set_motion_travel: the distance must be finite and >= 0");
  impl_->travel = metres;
}

double CollisionWorld::motion_travel() const {
  return impl_->travel;
}

bool CollisionWorld::motion_free(const Eigen::VectorXd& q0, const Eigen::VectorXd& q1,
                                 double resolution, double travel, CollisionReport* report) {
  Impl& m = *impl_;
  const int dof = m.model.dof();
  if (q0.size() != dof || q1.size() != dof)
    throw std::invalid_argument(m.model.name + ": motion_free needs two configurations of " +
                                std::to_string(dof) + " values");
  if (!q0.allFinite() || !q1.allFinite() || !(travel >= 0) || !std::isfinite(travel))
    throw std::invalid_argument(m.model.name + ": motion_free: q or the travel is not finite");
  if (travel > 0 && m.reach.size() == 0) m.reach = motion_reach(m.model);  // once
  const int steps = motion_steps(m.reach, travel, q0, q1, resolution);
  return all_samples_free(steps, [&](int k) {
    forward_kinematics(m.model, q0 + (static_cast<double>(k) / steps) * (q1 - q0), m.scratch);
    return !m.check(m.scratch, report);
  });
}

}  // namespace claspplan::robots
