#include "examples/paper_objects.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>

namespace claspplan::objects {
namespace {

using Eigen::Vector3d;
constexpr double kCell = 0.004;  // meshing resolution: 2.5 cells across the thinnest (1 cm) strap

// The upright x-z plane through `centre` (a ring's axis along y).
Eigen::Isometry3d xz_plane(const Vector3d& centre) {
  Eigen::Isometry3d pose = Eigen::Isometry3d::Identity();
  pose.translate(centre);
  pose.rotate(Eigen::AngleAxisd(M_PI / 2, Vector3d::UnitX()));
  return pose;
}

// A flat strap bent into a ring around the pose's z axis: centre-line radius R, `thickness`
// radially, `width` along the axis (a bag's strap rather than a round tube).
Sdf strap(const Eigen::Isometry3d& pose, double R, double thickness, double width) {
  const Eigen::Isometry3d inv = pose.inverse();
  return [=](const Vector3d& p) {
    const Vector3d l = inv * p;
    const Eigen::Vector2d q(std::abs(std::hypot(l.x(), l.y()) - R) - thickness / 2,
                            std::abs(l.z()) - width / 2);
    return q.cwiseMax(0.0).norm() + std::min(q.maxCoeff(), 0.0);
  };
}

// Meshes `f` inside the box from (-hx, -hy, 0) to (hx, hy, top), padded.
TriangleMesh mesh_upright(const Sdf& f, double hx, double hy, double top) {
  const double pad = 3 * kCell;
  return mesh_from_sdf(f,
                       Eigen::AlignedBox3d(Vector3d(-hx - pad, -hy - pad, -pad),
                                           Vector3d(hx + pad, hy + pad, top + pad)),
                       kCell);
}

PaperObject make_purse() {
  Purse p;  // the existing purse_1 scenarios' purse: a 30 cm box, 2.4 cm round handle
  p.body = {0.30, 0.14, 0.18};
  p.handle_radius = 0.12;
  p.handle_tube = 0.012;
  p.cell = kCell;
  PaperObject o{"purse", purse(p), 1, 9, purse_handle_centre(p), purse_handle_centre(p)};
  return o;
}

// A shoulder bag: a soft box with one flat strap (1 cm x 3 cm) arching 16 cm over its top.
PaperObject make_bag() {
  const Vector3d body(0.36, 0.12, 0.28);
  const double R = 0.16;
  const Sdf solid = sdf::smooth_unite(sdf::box({0, 0, body.z() / 2}, body / 2, 0.03),
                                      strap(xz_plane({0, 0, body.z()}), R, 0.01, 0.03), 0.005);
  const Vector3d hole(0, 0, body.z() + R / 2);
  return {"bag", mesh_upright(solid, body.x() / 2, body.y() / 2, body.z() + R + 0.01), 1, 23, hole,
          hole};
}

// A duffel travel bag: a well-rounded 50 x 28 x 26 cm body with a round top handle (2.4 cm).
PaperObject make_travel_bag() {
  const Vector3d body(0.50, 0.28, 0.26);
  const double R = 0.09, tube = 0.012;
  const Sdf solid = sdf::smooth_unite(sdf::box({0, 0, body.z() / 2}, body / 2, 0.09),
                                      sdf::torus(xz_plane({0, 0, body.z()}), R, tube), 0.5 * tube);
  const Vector3d hole(0, 0, body.z() + (R - tube) / 2);
  return {"travelbag", mesh_upright(solid, body.x() / 2, body.y() / 2, body.z() + R + tube),
          1,           10,
          hole,        hole};
}

// A push mower: a deck on four wheels, two handle bars rising backwards (+x) from the deck's
// rear, a lower cross bar and the grip: two loops (deck-bars-cross bar, cross bar-grip).
PaperObject make_lawn_mower() {
  const double tube = 0.012, half_width = 0.15;
  Sdf solid = sdf::box({0, 0, 0.13}, {0.21, 0.19, 0.07}, 0.03);
  for (double x : {-0.14, 0.14})
    for (double y : {-1.0, 1.0})
      solid = sdf::unite(solid, sdf::cylinder({x, y * 0.17, 0.07}, {x, y * 0.22, 0.07}, 0.07));
  const Vector3d foot(0.16, 0, 0.19), top(0.52, 0, 0.76);  // bar ends (y = +-half_width)
  auto at = [&](const Vector3d& p, double y) { return Vector3d(p.x(), y, p.z()); };
  const Vector3d cross = foot + 0.45 * (top - foot);
  for (double y : {-half_width, half_width})
    solid = sdf::unite(solid, sdf::capsule(at(foot, y), at(top, y), tube));
  solid = sdf::unite(solid, sdf::capsule(at(cross, -half_width), at(cross, half_width), tube));
  solid = sdf::unite(solid, sdf::capsule(at(top, -half_width), at(top, half_width), 0.015));
  const Vector3d grip_hole = (cross + top) / 2;
  const Vector3d lower_hole = (foot + cross) / 2 + Vector3d(0, 0, 0.02);
  PaperObject o{"lawnmower", mesh_upright(solid, 0.54, 0.23, top.z() + 0.02), 2, 24, grip_hole,
                lower_hole};
  // Centre it in x (the deck spans -0.21..0.21, the grip reaches 0.53).
  for (auto& v : o.mesh.vertices) v.x() -= 0.16;
  o.clasp.x() -= 0.16;
  o.hidden.x() -= 0.16;
  return o;
}

// A chair: a 40 x 40 cm seat 42 cm high on four 3 cm legs joined by stretchers on all four sides
// (4 loops under the seat), back posts with three rails (3 loops in the backrest).
PaperObject make_chair() {
  const double leg = 0.015, rail = 0.012, stretcher = 0.01, half = 0.18, seat = 0.42;
  Sdf solid = sdf::box({0, 0, seat - 0.015}, {0.20, 0.20, 0.015}, 0.005);
  const Vector3d corner[4] = {
      {-half, -half, 0}, {half, -half, 0}, {half, half, 0}, {-half, half, 0}};
  for (const auto& c : corner) {
    const double height = c.x() > 0 ? 0.86 : seat - 0.01;  // rear legs go on as back posts
    solid = sdf::unite(solid, sdf::cylinder(c, c + Vector3d(0, 0, height), leg));
  }
  const Vector3d lift(0, 0, 0.15);
  for (int i = 0; i < 4; ++i)
    solid =
        sdf::unite(solid, sdf::capsule(corner[i] + lift, corner[(i + 1) % 4] + lift, stretcher));
  for (double z : {0.56, 0.70, 0.84})
    solid = sdf::unite(solid, sdf::capsule({half, -half, z}, {half, half, z}, rail));
  return {"chair",
          mesh_upright(solid, 0.20, 0.20, 0.86),
          7,
          17,
          Vector3d(half, 0, 0.77) /* the top backrest loop */,
          Vector3d(-half, 0, 0.5 * (0.15 + seat)) /* the front loop under the seat */};
}

}  // namespace

const std::vector<std::string>& paper_object_names() {
  static const std::vector<std::string> names = {"purse", "bag", "travelbag", "lawnmower", "chair"};
  return names;
}

PaperObject paper_object(const std::string& name) {
  if (name == "purse") return make_purse();
  if (name == "bag") return make_bag();
  if (name == "travelbag") return make_travel_bag();
  if (name == "lawnmower") return make_lawn_mower();
  if (name == "chair") return make_chair();
  throw std::invalid_argument("unknown paper object '" + name +
                              "' (purse, bag, travelbag, lawnmower, chair)");
}

}  // namespace claspplan::objects
