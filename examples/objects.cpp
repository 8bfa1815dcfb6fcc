#include "examples/objects.hpp"

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <stdexcept>
#include <unordered_map>

#include "core/input_error.hpp"

namespace claspplan::objects {

namespace {

constexpr double kPi = 3.14159265358979323846;

// Flips each triangle whose normal points against `outward(centroid)`.
template <class Outward>
void orient(TriangleMesh& m, Outward outward) {
  for (auto& t : m.triangles) {
    const Eigen::Vector3d& a = m.vertices[t[0]];
    const Eigen::Vector3d& b = m.vertices[t[1]];
    const Eigen::Vector3d& c = m.vertices[t[2]];
    if ((b - a).cross(c - a).dot(outward((a + b + c) / 3.0)) < 0) std::swap(t[1], t[2]);
  }
}

}  // namespace

TriangleMesh sphere_mesh(double radius, const Eigen::Vector3d& centre, int slices, int stacks) {
  if (!(radius > 0) || slices < 3 || stacks < 2)
    throw InputError("sphere_mesh: radius > 0, slices >= 3, stacks >= 2");
  TriangleMesh m;
  m.vertices.push_back(centre + Eigen::Vector3d(0, 0, radius));
  for (int i = 1; i < stacks; ++i) {
    const double th = kPi * i / stacks;
    for (int j = 0; j < slices; ++j) {
      const double ph = 2 * kPi * j / slices;
      m.vertices.push_back(centre + radius * Eigen::Vector3d(std::sin(th) * std::cos(ph),
                                                             std::sin(th) * std::sin(ph),
                                                             std::cos(th)));
    }
  }
  m.vertices.push_back(centre - Eigen::Vector3d(0, 0, radius));
  const int south = static_cast<int>(m.vertices.size()) - 1;
  auto ring = [&](int i, int j) { return 1 + (i - 1) * slices + (j % slices); };
  for (int j = 0; j < slices; ++j) m.triangles.push_back({0, ring(1, j), ring(1, j + 1)});
  for (int i = 1; i + 1 < stacks; ++i)
    for (int j = 0; j < slices; ++j) {
      m.triangles.push_back({ring(i, j), ring(i + 1, j), ring(i + 1, j + 1)});
      m.triangles.push_back({ring(i, j), ring(i + 1, j + 1), ring(i, j + 1)});
    }
  for (int j = 0; j < slices; ++j)
    m.triangles.push_back({south, ring(stacks - 1, j + 1), ring(stacks - 1, j)});
  orient(m, [&](const Eigen::Vector3d& p) { return Eigen::Vector3d(p - centre); });
  return m;
}

TriangleMesh torus_mesh(double R, double r, const Eigen::Isometry3d& pose, int major, int minor) {
  if (!(r > 0) || !(R > r) || major < 3 || minor < 3)
    throw InputError("torus_mesh: need R > r > 0, major >= 3, minor >= 3");
  TriangleMesh m;
  for (int i = 0; i < major; ++i) {
    const double u = 2 * kPi * i / major;
    for (int j = 0; j < minor; ++j) {
      const double v = 2 * kPi * j / minor;
      m.vertices.push_back(pose * Eigen::Vector3d((R + r * std::cos(v)) * std::cos(u),
                                                  (R + r * std::cos(v)) * std::sin(u),
                                                  r * std::sin(v)));
    }
  }
  auto id = [&](int i, int j) { return (i % major) * minor + (j % minor); };
  for (int i = 0; i < major; ++i)
    for (int j = 0; j < minor; ++j) {
      m.triangles.push_back({id(i, j), id(i + 1, j), id(i + 1, j + 1)});
      m.triangles.push_back({id(i, j), id(i + 1, j + 1), id(i, j + 1)});
    }
  const Eigen::Isometry3d inv = pose.inverse();
  orient(m, [&](const Eigen::Vector3d& p) {
    const Eigen::Vector3d l = inv * p;
    const Eigen::Vector3d core = R * Eigen::Vector3d(l.x(), l.y(), 0).normalized();
    return Eigen::Vector3d(pose.linear() * (l - core));
  });
  return m;
}

TriangleMesh mesh_from_sdf(const Sdf& f, const Eigen::AlignedBox3d& box, double cell) {
  if (box.isEmpty() || !(cell > 0) || !box.min().allFinite() || !box.max().allFinite())
    throw InputError("mesh_from_sdf: need a non-empty box and a cell > 0");
  const Eigen::Vector3d size = box.sizes();
  const long nx = std::max(1L, std::lround(std::ceil(size.x() / cell)));
  const long ny = std::max(1L, std::lround(std::ceil(size.y() / cell)));
  const long nz = std::max(1L, std::lround(std::ceil(size.z() / cell)));
  const long sx = nx + 1, sy = ny + 1, sz = nz + 1;
  if (static_cast<double>(sx) * sy * sz > 2e8)
    throw InputError("mesh_from_sdf: grid too fine (more than 2e8 nodes)");
  auto node_pos = [&](long i, long j, long k) {
    return Eigen::Vector3d(box.min().x() + i * cell, box.min().y() + j * cell,
                           box.min().z() + k * cell);
  };
  std::vector<double> value(static_cast<size_t>(sx * sy * sz));
  for (long k = 0; k < sz; ++k)
    for (long j = 0; j < sy; ++j)
      for (long i = 0; i < sx; ++i) {
        double v = f(node_pos(i, j, k));
        if (v == 0.0) v = 1e-12;  // no vertex exactly on the surface: no degenerate cases
        value[static_cast<size_t>(i + sx * (j + sy * k))] = v;
      }
  TriangleMesh m;
  std::unordered_map<std::uint64_t, int> edge_vertex;
  auto pos_of = [&](long id) { return node_pos(id % sx, (id / sx) % sy, id / (sx * sy)); };
  auto vertex_on = [&](long a, long b) {
    if (a > b) std::swap(a, b);
    const std::uint64_t key =
        static_cast<std::uint64_t>(a) * static_cast<std::uint64_t>(sx * sy * sz) +
        static_cast<std::uint64_t>(b);
    const auto it = edge_vertex.find(key);
    if (it != edge_vertex.end()) return it->second;
    const double fa = value[a], fb = value[b];
    const double t = fa / (fa - fb);
    m.vertices.push_back(pos_of(a) + t * (pos_of(b) - pos_of(a)));
    const int id = static_cast<int>(m.vertices.size()) - 1;
    edge_vertex.emplace(key, id);
    return id;
  };
  // Kuhn triangulation: 6 tetrahedra along the cube's main diagonal; consistent across cubes.
  static const int kTets[6][4] = {{0, 1, 3, 7}, {0, 1, 5, 7}, {0, 2, 3, 7},
                                  {0, 2, 6, 7}, {0, 4, 5, 7}, {0, 4, 6, 7}};
  auto emit = [&](int a, int b, int c, const Eigen::Vector3d& outward) {
    Eigen::Vector3i t(a, b, c);
    const Eigen::Vector3d& p = m.vertices[a];
    if ((m.vertices[b] - p).cross(m.vertices[c] - p).dot(outward) < 0) std::swap(t[1], t[2]);
    m.triangles.push_back(t);
  };
  for (long k = 0; k < nz; ++k)
    for (long j = 0; j < ny; ++j)
      for (long i = 0; i < nx; ++i) {
        long corner[8];
        bool any_in = false, any_out = false;
        for (int c = 0; c < 8; ++c) {
          corner[c] = (i + (c & 1)) + sx * ((j + ((c >> 1) & 1)) + sy * (k + ((c >> 2) & 1)));
          (value[corner[c]] < 0 ? any_in : any_out) = true;
        }
        if (!any_in || !any_out) continue;
        for (const auto& tet : kTets) {
          long in[4], out[4];
          int ni = 0, no = 0;
          for (int q = 0; q < 4; ++q) {
            const long id = corner[tet[q]];
            if (value[id] < 0)
              in[ni++] = id;
            else
              out[no++] = id;
          }
          if (ni == 0 || no == 0) continue;
          Eigen::Vector3d cin = Eigen::Vector3d::Zero(), cout = Eigen::Vector3d::Zero();
          for (int q = 0; q < ni; ++q) cin += pos_of(in[q]) / ni;
          for (int q = 0; q < no; ++q) cout += pos_of(out[q]) / no;
          const Eigen::Vector3d outward = cout - cin;
          if (ni == 1) {
            emit(vertex_on(in[0], out[0]), vertex_on(in[0], out[1]), vertex_on(in[0], out[2]),
                 outward);
          } else if (ni == 3) {
            emit(vertex_on(out[0], in[0]), vertex_on(out[0], in[1]), vertex_on(out[0], in[2]),
                 outward);
          } else {  // a quad: (in0,out0) (in0,out1) (in1,out1) (in1,out0)
            const int a = vertex_on(in[0], out[0]), b = vertex_on(in[0], out[1]);
            const int c = vertex_on(in[1], out[1]), d = vertex_on(in[1], out[0]);
            emit(a, b, c, outward);
            emit(a, c, d, outward);
          }
        }
      }
  if (m.triangles.empty()) throw InputError("mesh_from_sdf: no surface inside the box");
  return m;
}

namespace sdf {

Sdf sphere(const Eigen::Vector3d& c, double r) {
  return [=](const Eigen::Vector3d& p) { return (p - c).norm() - r; };
}

Sdf box(const Eigen::Vector3d& c, const Eigen::Vector3d& half, double rounding) {
  const Eigen::Vector3d inner = half - Eigen::Vector3d::Constant(rounding);
  return [=](const Eigen::Vector3d& p) {
    const Eigen::Vector3d q = (p - c).cwiseAbs() - inner;
    return q.cwiseMax(0.0).norm() + std::min(q.maxCoeff(), 0.0) - rounding;
  };
}

Sdf torus(const Eigen::Isometry3d& pose, double R, double r) {
  const Eigen::Isometry3d inv = pose.inverse();
  return [=](const Eigen::Vector3d& p) {
    const Eigen::Vector3d l = inv * p;
    return Eigen::Vector2d(std::hypot(l.x(), l.y()) - R, l.z()).norm() - r;
  };
}

Sdf capsule(const Eigen::Vector3d& a, const Eigen::Vector3d& b, double r) {
  return [=](const Eigen::Vector3d& p) {
    const Eigen::Vector3d ab = b - a;
    const double t = std::clamp((p - a).dot(ab) / std::max(ab.squaredNorm(), 1e-300), 0.0, 1.0);
    return (p - a - t * ab).norm() - r;
  };
}

Sdf cylinder(const Eigen::Vector3d& a, const Eigen::Vector3d& b, double r) {
  return [=](const Eigen::Vector3d& p) {
    const Eigen::Vector3d axis = (b - a).normalized();
    const double h = (b - a).norm() / 2;
    const Eigen::Vector3d rel = p - (a + b) / 2;
    const double along = rel.dot(axis);
    const double radial = (rel - along * axis).norm();
    const Eigen::Vector2d d(radial - r, std::abs(along) - h);
    return std::min(std::max(d.x(), d.y()), 0.0) + d.cwiseMax(0.0).norm();
  };
}

Sdf unite(Sdf a, Sdf b) {
  return [=](const Eigen::Vector3d& p) { return std::min(a(p), b(p)); };
}
Sdf subtract(Sdf a, Sdf b) {
  return [=](const Eigen::Vector3d& p) { return std::max(a(p), -b(p)); };
}
Sdf intersect(Sdf a, Sdf b) {
  return [=](const Eigen::Vector3d& p) { return std::max(a(p), b(p)); };
}
Sdf smooth_unite(Sdf a, Sdf b, double k) {
  return [=](const Eigen::Vector3d& p) {
    const double da = a(p), db = b(p);
    const double h = std::clamp(0.5 + 0.5 * (db - da) / k, 0.0, 1.0);
    return db + h * (da - db) - k * h * (1 - h);
  };
}
Sdf smooth_subtract(Sdf a, Sdf b, double k) {
  return [=](const Eigen::Vector3d& p) {
    const double da = a(p), db = b(p);
    const double h = std::clamp(0.5 - 0.5 * (da + db) / k, 0.0, 1.0);
    return da + h * (-db - da) + k * h * (1 - h);
  };
}
Sdf moved(Sdf f, const Eigen::Isometry3d& pose) {
  const Eigen::Isometry3d inv = pose.inverse();
  return [=](const Eigen::Vector3d& p) { return f(inv * p); };
}

}  // namespace sdf

TriangleMesh holed_plate(const HoledPlate& p) {
  if (p.holes < 0 || !(p.hole_radius > 0) || !(p.thickness > 2 * p.rounding) || !(p.margin > 0) ||
      !(p.cell > 0))
    throw InputError("holed_plate: bad parameters");
  const double length = p.holes > 0 ? p.holes * 2 * p.hole_radius + (p.holes + 1) * p.margin
                                    : 2 * p.hole_radius + 2 * p.margin;
  const double width = 2 * p.hole_radius + 2 * p.margin;
  Sdf solid =
      sdf::box({0, 0, p.thickness / 2}, {length / 2, width / 2, p.thickness / 2}, p.rounding);
  for (int i = 0; i < p.holes; ++i) {
    const double x = -length / 2 + p.margin + p.hole_radius + i * (2 * p.hole_radius + p.margin);
    solid = sdf::smooth_subtract(
        solid, sdf::cylinder({x, 0, -1.0}, {x, 0, p.thickness + 1.0}, p.hole_radius), p.rounding);
  }
  const double pad = 2 * p.cell + p.rounding;
  const Eigen::AlignedBox3d box(
      Eigen::Vector3d(-length / 2 - pad, -width / 2 - pad, -pad),
      Eigen::Vector3d(length / 2 + pad, width / 2 + pad, p.thickness + pad));
  return mesh_from_sdf(solid, box, p.cell);
}

namespace {
Eigen::Isometry3d handle_pose(const Purse& p) {
  Eigen::Isometry3d pose = Eigen::Isometry3d::Identity();
  pose.linear() = Eigen::AngleAxisd(-kPi / 2, Eigen::Vector3d::UnitX()).toRotationMatrix();
  pose.translation() = Eigen::Vector3d(0, 0, p.body.z());  // ring in the x-z plane
  return pose;
}
}  // namespace

TriangleMesh purse(const Purse& p) {
  if (!(p.body.minCoeff() > 0) || !(p.handle_tube > 0) || !(p.handle_radius > p.handle_tube) ||
      p.handle_radius + p.handle_tube >= std::min(p.body.x() / 2, p.body.z()) ||
      p.handle_tube >= p.body.y() / 2 || !(p.cell > 0))
    throw InputError("purse: the handle must fit on the body (bad parameters)");
  const Sdf body = sdf::box({0, 0, p.body.z() / 2}, p.body / 2, p.body_rounding);
  const Sdf handle = sdf::torus(handle_pose(p), p.handle_radius, p.handle_tube);
  const Sdf solid = sdf::smooth_unite(body, handle, 0.5 * p.handle_tube);
  const double pad = 2 * p.cell;
  const double hx = p.body.x() / 2 + pad, hy = p.body.y() / 2 + pad;
  const Eigen::AlignedBox3d box(
      Eigen::Vector3d(-hx, -hy, -pad),
      Eigen::Vector3d(hx, hy, p.body.z() + p.handle_radius + p.handle_tube + pad));
  return mesh_from_sdf(solid, box, p.cell);
}

Eigen::Vector3d purse_handle_centre(const Purse& p) {
  return {0, 0, p.body.z() + 0.5 * (p.handle_radius - p.handle_tube)};
}

TriangleMesh container(const Container& c) {
  if (!(c.radius > 2 * c.wall) || !(c.height > 2 * c.wall) || !(c.wall > 0) || !(c.cell > 0) ||
      (c.handle_radius > 0 && !(c.handle_radius > c.handle_tube && c.handle_tube > 0)) ||
      (c.handle_radius > 0 && c.handle_radius + c.handle_tube >= c.height / 2))
    throw InputError("container: bad parameters");
  const Eigen::Vector3d up(0, 0, 1);
  Sdf solid =
      sdf::subtract(sdf::cylinder(Eigen::Vector3d::Zero(), c.height * up, c.radius),
                    sdf::cylinder(c.wall * up, (c.height + c.wall) * up, c.radius - c.wall));
  double reach = c.radius;
  if (c.handle_radius > 0) {
    // Half a torus on the +x side: its centre on the wall, its ends buried in the wall.
    Eigen::Isometry3d pose = Eigen::Isometry3d::Identity();
    pose.translate(Eigen::Vector3d(c.radius - c.wall, 0, c.handle_height * c.height));
    pose.rotate(Eigen::AngleAxisd(M_PI / 2, Eigen::Vector3d::UnitX()));
    const Sdf ring = sdf::torus(pose, c.handle_radius, c.handle_tube);
    const Sdf outside = [r = c.radius - c.wall](const Eigen::Vector3d& p) {
      return std::hypot(p.x(), p.y()) < r ? r - std::hypot(p.x(), p.y()) : -1.0;
    };
    solid = sdf::smooth_unite(solid, sdf::intersect(ring, outside), 0.5 * c.handle_tube);
    reach = c.radius + c.handle_radius + c.handle_tube;
  }
  const double pad = 2 * c.cell;
  const Eigen::AlignedBox3d box(Eigen::Vector3d(-c.radius - pad, -c.radius - pad, -pad),
                                Eigen::Vector3d(reach + pad, c.radius + pad, c.height + pad));
  return mesh_from_sdf(solid, box, c.cell);
}

Eigen::Vector3d container_handle_centre(const Container& c) {
  return {c.radius - c.wall + 0.5 * (c.handle_radius - c.handle_tube), 0,
          c.handle_height * c.height};
}

TriangleMesh ground_plane(double size, double z, const Eigen::Vector2d& c) {
  TriangleMesh m;
  const double h = size / 2;
  m.vertices = {{c.x() - h, c.y() - h, z},
                {c.x() + h, c.y() - h, z},
                {c.x() + h, c.y() + h, z},
                {c.x() - h, c.y() + h, z}};
  m.triangles = {{0, 1, 2}, {0, 2, 3}};
  return m;
}

perception::CameraModel kinect_camera(const Eigen::Vector3d& position,
                                      const Eigen::Vector3d& target) {
  perception::CameraModel c = perception::look_at_camera(position, target, 0.1, 640, 480);
  c.fx = c.fy = 525.0;
  c.cx = 319.5;
  c.cy = 239.5;
  c.depth_scale = 0.0002;
  c.no_reading_is_free = true;  // it renders complete synthetic scenes
  return c;
}

std::vector<perception::CameraModel> purse_cameras(int count) {
  if (count < 1 || count > 2) throw InputError("purse_cameras: 1 or 2 cameras");
  const Eigen::Vector3d target(0, 0, 0.16);
  std::vector<perception::CameraModel> cams{kinect_camera({0.25, -0.75, 0.65}, target)};
  if (count == 2) cams.push_back(kinect_camera({-0.35, 0.70, 0.70}, target));
  return cams;
}

std::vector<std::pair<std::string, std::string>> write_depth_files(
    const TriangleMesh& scene, const std::vector<perception::CameraModel>& cameras,
    const std::string& dir, const std::string& stem, const perception::DepthNoise& noise) {
  std::filesystem::create_directories(dir);
  std::vector<std::pair<std::string, std::string>> files;
  for (size_t i = 0; i < cameras.size(); ++i) {
    perception::DepthNoise n = noise;
    n.seed = noise.seed + i;
    const auto image = perception::render_depth(scene, cameras[i], n);
    const std::string base =
        (std::filesystem::path(dir) / (stem + "_" + std::to_string(i))).string();
    perception::write_depth_png(image, cameras[i], base + ".png");
    perception::write_camera_yaml(cameras[i], base + ".yaml");
    files.emplace_back(base + ".png", base + ".yaml");
  }
  return files;
}

std::vector<std::pair<std::string, std::string>> write_purse_depth_example(
    const std::string& dir, int cameras, const perception::DepthNoise& noise) {
  TriangleMesh scene = purse();
  append_mesh(scene, ground_plane(1.2));
  return write_depth_files(scene, purse_cameras(cameras), dir, "purse", noise);
}

}  // namespace claspplan::objects
