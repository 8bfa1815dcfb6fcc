// The URDF part of a robot model: parsing (urdfdom), the link tree and the collision shapes
// (primitives and meshes; placeholder geometry skipped with a warning).
#include <algorithm>
#include <cmath>
#include <map>
#include <memory>
#include <mutex>
#include <sstream>
#include <vector>

#include <console_bridge/console.h>

#include "core/input_error.hpp"
#include "robots/mesh_resources.hpp"
#include "robots/robot_model_detail.hpp"

namespace claspplan::robots::robot_model_detail {

namespace {

// urdfdom reports problems through console_bridge; keep the first error for the message and
// keep stderr clean.
class CaptureErrors : public console_bridge::OutputHandler {
 public:
  void log(const std::string& text, console_bridge::LogLevel level, const char*, int) override {
    if (level >= console_bridge::CONSOLE_BRIDGE_LOG_ERROR && first_error.empty()) {
      first_error = one_line(text);
    }
  }
  std::string first_error;
};

std::mutex& urdf_mutex() {
  static std::mutex m;
  return m;
}

Eigen::Isometry3d to_isometry(const urdf::Pose& p) {
  Eigen::Isometry3d t = Eigen::Isometry3d::Identity();
  t.translation() = Eigen::Vector3d(p.position.x, p.position.y, p.position.z);
  t.linear() =
      Eigen::Quaterniond(p.rotation.w, p.rotation.x, p.rotation.y, p.rotation.z).toRotationMatrix();
  return t;
}

bool finite(const Eigen::Isometry3d& t) {
  return t.matrix().allFinite();
}

// Reads the meshes of one URDF once each (links often share a file) and records what it skips.
struct ShapeReader {
  const std::string& urdf_file;
  std::vector<std::string>& warnings;
  std::vector<std::string> left_out;  // links whose subtrees are not read (an arm's own gripper)
  std::map<std::string, std::shared_ptr<const TriangleMesh>> meshes;  // by path and scale
  std::string cut_root;  // a subtree's root: the joint above it (of any type) is not read

  void skip(const urdf::Link& link, const std::string& what) {
    warnings.push_back(urdf_file + ": link '" + link.name + "': " + what +
                       ": placeholder geometry, skipped");
  }

  // The mesh shape, or false for a placeholder (no file name, a zero scale).
  bool mesh(const urdf::Link& link, const urdf::Mesh& m, CollisionShape& s) {
    const Eigen::Vector3d scale(m.scale.x, m.scale.y, m.scale.z);
    if (!scale.allFinite()) fail(urdf_file, "link '" + link.name + "': mesh scale is not finite");
    if (m.filename.empty() || (scale.array() == 0.0).any()) {
      skip(link, m.filename.empty() ? "mesh without a file name" : "mesh scaled to zero");
      return false;
    }
    std::string path;
    try {
      path = resolve_mesh_uri(m.filename, urdf_file);
    } catch (const InputError& e) {
      fail(urdf_file, "link '" + link.name + "': " + e.what());
    }
    std::ostringstream key;
    key << path << ' ' << scale.x() << ' ' << scale.y() << ' ' << scale.z();
    auto& cached = meshes[key.str()];
    if (!cached) {
      TriangleMesh mesh = read_mesh_resource(path);
      for (auto& v : mesh.vertices) v = v.cwiseProduct(scale);
      if (scale.prod() < 0.0)  // mirrored: keep the triangles facing out
        for (auto& t : mesh.triangles) std::swap(t[1], t[2]);
      cached = std::make_shared<const TriangleMesh>(std::move(mesh));
    }
    s.type = CollisionShape::Type::kMesh;
    s.mesh = cached;
    s.source = path;
    return true;
  }

  // The primitive or mesh shape of one <collision>, or false for placeholder geometry: a zero
  // size is a placeholder (some public URDFs carry them), a negative or non-finite one an error.
  bool shape(const urdf::Link& link, const urdf::Geometry& g, CollisionShape& s) {
    const auto sizes = [&](const Eigen::VectorXd& v, const std::string& what) {
      if (!v.allFinite() || (v.array() < 0).any())
        fail(urdf_file, "link '" + link.name + "': " + what + " must be finite and > 0");
      if ((v.array() == 0).any()) {
        skip(link, what + " zero");
        return false;
      }
      return true;
    };
    switch (g.type) {
      case urdf::Geometry::BOX: {
        const auto& b = static_cast<const urdf::Box&>(g);
        s.type = CollisionShape::Type::kBox;
        s.size = Eigen::Vector3d(b.dim.x, b.dim.y, b.dim.z);
        return sizes(s.size, "box sizes");
      }
      case urdf::Geometry::SPHERE: {
        s.type = CollisionShape::Type::kSphere;
        s.radius = static_cast<const urdf::Sphere&>(g).radius;
        return sizes(Eigen::Matrix<double, 1, 1>(s.radius), "sphere radius");
      }
      case urdf::Geometry::CYLINDER: {
        const auto& cy = static_cast<const urdf::Cylinder&>(g);
        s.type = CollisionShape::Type::kCylinder;
        s.radius = cy.radius;
        s.length = cy.length;
        return sizes(Eigen::Vector2d(s.radius, s.length), "cylinder radius and length");
      }
      case urdf::Geometry::MESH:
        return mesh(link, static_cast<const urdf::Mesh&>(g), s);
    }
    fail(urdf_file, "link '" + link.name + "': unknown collision geometry type");
  }
};

// Converts the URDF <collision> elements of one link; merges cylinder + two end spheres into a
// capsule (URDF has no capsule primitive).
std::vector<CollisionShape> link_shapes(const urdf::Link& link, int index, ShapeReader& reader) {
  const std::string& file = reader.urdf_file;
  std::vector<CollisionShape> shapes;
  for (const auto& c : link.collision_array) {
    if (!c || !c->geometry) continue;
    CollisionShape s;
    s.link = index;
    s.origin = to_isometry(c->origin);
    if (!finite(s.origin)) fail(file, "link '" + link.name + "': collision origin is not finite");
    if (reader.shape(link, *c->geometry, s)) shapes.push_back(s);
  }
  // Capsule merge.
  std::vector<bool> used(shapes.size(), false);
  std::vector<CollisionShape> merged;
  for (size_t i = 0; i < shapes.size(); ++i) {
    if (shapes[i].type != CollisionShape::Type::kCylinder || used[i]) continue;
    const CollisionShape& cy = shapes[i];
    const Eigen::Vector3d axis = cy.origin.linear().col(2);
    const Eigen::Vector3d ends[2] = {cy.origin.translation() + 0.5 * cy.length * axis,
                                     cy.origin.translation() - 0.5 * cy.length * axis};
    int found[2] = {-1, -1};
    for (int e = 0; e < 2; ++e) {
      for (size_t j = 0; j < shapes.size(); ++j) {
        if (used[j] || j == i || static_cast<int>(j) == found[0]) continue;
        const CollisionShape& sp = shapes[j];
        if (sp.type == CollisionShape::Type::kSphere && std::abs(sp.radius - cy.radius) < 1e-9 &&
            (sp.origin.translation() - ends[e]).norm() < 1e-6) {
          found[e] = static_cast<int>(j);
          break;
        }
      }
    }
    if (found[0] >= 0 && found[1] >= 0) {
      used[i] = used[found[0]] = used[found[1]] = true;
      CollisionShape cap = cy;
      cap.type = CollisionShape::Type::kCapsule;
      merged.push_back(cap);
    }
  }
  for (size_t i = 0; i < shapes.size(); ++i)
    if (!used[i]) merged.push_back(shapes[i]);
  return merged;
}

// Appends link l (child of parent) and, depth-first, its subtree.
void add_subtree(const urdf::Link& l, int parent, ShapeReader& reader, RobotModel& m,
                 UrdfJoints& joints) {
  const std::string& urdf_file = reader.urdf_file;
  Link link;
  link.name = l.name;
  link.parent = parent;
  if (l.parent_joint && l.name != reader.cut_root) {
    const urdf::Joint& j = *l.parent_joint;
    link.joint = j.name;
    link.origin = to_isometry(j.parent_to_joint_origin_transform);
    if (!finite(link.origin)) fail(urdf_file, "joint '" + j.name + "': origin is not finite");
    switch (j.type) {
      case urdf::Joint::FIXED:
        link.type = JointType::kFixed;
        break;
      case urdf::Joint::REVOLUTE:
      case urdf::Joint::CONTINUOUS:
        link.type = JointType::kRevolute;
        break;
      case urdf::Joint::PRISMATIC:
        link.type = JointType::kPrismatic;
        break;
      default:
        fail(urdf_file,
             "joint '" + j.name +
                 "': only fixed, revolute, continuous and prismatic joints are supported");
    }
    if (link.type != JointType::kFixed) {
      link.axis = Eigen::Vector3d(j.axis.x, j.axis.y, j.axis.z);
      if (!link.axis.allFinite() || link.axis.norm() < 1e-9)
        fail(urdf_file, "joint '" + j.name + "': axis must be a finite non-zero vector");
      link.axis.normalize();
    }
    joints.joint_of_link[l.name] = &j;
  }
  const int index = static_cast<int>(m.links.size());
  m.links.push_back(link);
  for (const auto& s : link_shapes(l, index, reader)) {
    m.links[index].shapes.push_back(static_cast<int>(m.shapes.size()));
    m.shapes.push_back(s);
  }
  for (const auto& child : l.child_links)
    if (std::find(reader.left_out.begin(), reader.left_out.end(), child->name) ==
        reader.left_out.end())
      add_subtree(*child, index, reader, m, joints);
}

}  // namespace

urdf::ModelInterfaceSharedPtr parse_urdf(const std::string& text, const std::string& file) {
  if (text.find_first_not_of(" \t\r\n") == std::string::npos) fail(file, "the URDF is empty");
  std::lock_guard<std::mutex> lock(urdf_mutex());
  CaptureErrors capture;
  console_bridge::OutputHandler* previous = console_bridge::getOutputHandler();
  console_bridge::useOutputHandler(&capture);
  urdf::ModelInterfaceSharedPtr model;
  try {
    model = urdf::parseURDF(text);
  } catch (const std::exception& e) {
    capture.first_error = one_line(e.what());
  }
  console_bridge::useOutputHandler(previous);
  if (!model) {
    fail(file, "not a valid URDF: " + (capture.first_error.empty() ? std::string("parse failed")
                                                                   : capture.first_error));
  }
  return model;
}

UrdfJoints read_urdf_tree(const urdf::ModelInterface& urdf, const std::string& urdf_file,
                          RobotModel& m, const std::vector<std::string>& left_out) {
  // Links, parents first (depth-first; urdfdom orders children by joint name).
  const auto urdf_root = urdf.getRoot();
  if (!urdf_root) fail(urdf_file, "the URDF has no root link");
  UrdfJoints joints;
  for (const std::string& link : left_out)
    if (!urdf.getLink(link) || link == urdf_root->name)
      fail(urdf_file, "hand_urdf.replaces: '" + link + "' is not a link below the URDF's root");
  ShapeReader reader{urdf_file, m.warnings, left_out, {}, {}};
  add_subtree(*urdf_root, -1, reader, m, joints);
  for (size_t i = 1; i < m.links.size(); ++i)
    joints.link_by_joint[m.links[i].joint] = static_cast<int>(i);
  return joints;
}

void attach_urdf_tree(const urdf::ModelInterface& urdf, const std::string& urdf_file, int parent,
                      const Eigen::Isometry3d& origin, RobotModel& m, UrdfJoints& joints,
                      const std::string& root_link) {
  const auto root = root_link.empty() ? urdf.getRoot() : urdf.getLink(root_link);
  if (!root)
    fail(urdf_file, root_link.empty()
                        ? std::string("the URDF has no root link")
                        : "the hand's root link '" + root_link + "' is not in the URDF");
  const int first = static_cast<int>(m.links.size());
  ShapeReader reader{urdf_file, m.warnings, {}, {}, root->name};
  add_subtree(*root, parent, reader, m, joints);
  m.links[first].origin = origin;
  m.links[first].joint = m.links[parent].name + "_to_" + root->name;  // the mount, fixed
  std::map<std::string, int> names;
  for (std::size_t i = 0; i < m.links.size(); ++i)
    if (!names.emplace(m.links[i].name, static_cast<int>(i)).second)
      fail(urdf_file, "link '" + m.links[i].name + "' is also in the arm's URDF");
  for (std::size_t i = first; i < m.links.size(); ++i) {
    if (!joints.link_by_joint.emplace(m.links[i].joint, static_cast<int>(i)).second)
      fail(urdf_file, "joint '" + m.links[i].joint + "' is also in the arm's URDF");
  }
}

}  // namespace claspplan::robots::robot_model_detail
