// Procedural test objects: closed, watertight triangle meshes whose topology is known, and the
// example depth files rendered from them.
//
// Two ways to build a shape:
//  - parametric meshes (sphere_mesh, torus_mesh): exact vertices on the surface;
//  - implicit solids: a signed distance function (negative inside) built from the primitives and
//    CSG operations in objects::sdf, meshed by marching tetrahedra (mesh_from_sdf). Marching
//    tetrahedra has no ambiguous cases, so the mesh is always a closed 2-manifold with the
//    solid's topology (given a cell small enough for the thinnest part).
// New objects (bag, travel bag, lawn mower, chair, ...) are a few lines of sdf:: calls each.
#pragma once

#include <cstdint>
#include <functional>
#include <string>
#include <vector>

#include <Eigen/Core>
#include <Eigen/Geometry>

#include "core/input_error.hpp"
#include "core/mesh.hpp"
#include "perception/camera.hpp"
#include "perception/depth_render.hpp"

namespace claspplan::objects {

/// A signed distance (or any function negative inside, positive outside, roughly Lipschitz-1).
using Sdf = std::function<double(const Eigen::Vector3d&)>;

/// UV sphere: `slices` around z, `stacks` from pole to pole (poles are single vertices).
TriangleMesh sphere_mesh(double radius, const Eigen::Vector3d& centre = Eigen::Vector3d::Zero(),
                         int slices = 64, int stacks = 32);

/// Torus with major radius R (centre line) and minor radius r < R around the pose's z axis.
/// Genus 1; its hole's shortest loop has length 2 pi (R - r).
TriangleMesh torus_mesh(double R, double r,
                        const Eigen::Isometry3d& pose = Eigen::Isometry3d::Identity(),
                        int major = 96, int minor = 48);

/// The zero level set of `f` inside `box`, by marching tetrahedra (6 Kuhn tetrahedra per cube)
/// on a grid of spacing `cell`; triangles face outwards (towards positive f). The solid must not
/// touch the box. Throws InputError for a bad box/cell or more than 2e8 grid nodes.
TriangleMesh mesh_from_sdf(const Sdf& f, const Eigen::AlignedBox3d& box, double cell);

namespace sdf {
Sdf sphere(const Eigen::Vector3d& centre, double radius);
/// Axis-aligned box with half extents `half`, edges rounded by `rounding` (inside the extents).
Sdf box(const Eigen::Vector3d& centre, const Eigen::Vector3d& half, double rounding = 0.0);
/// Torus around the pose's z axis through the pose's origin.
Sdf torus(const Eigen::Isometry3d& pose, double R, double r);
/// A round tube of radius r around the segment a-b, with hemispherical ends.
Sdf capsule(const Eigen::Vector3d& a, const Eigen::Vector3d& b, double r);
/// A cylinder of radius r with flat ends at a and b.
Sdf cylinder(const Eigen::Vector3d& a, const Eigen::Vector3d& b, double r);
Sdf unite(Sdf a, Sdf b);
Sdf subtract(Sdf a, Sdf b);  ///< a minus b
Sdf intersect(Sdf a, Sdf b);
/// Polynomial smooth union / difference with blend radius k (rounded joints and hole edges).
Sdf smooth_unite(Sdf a, Sdf b, double k);
Sdf smooth_subtract(Sdf a, Sdf b, double k);
/// f in the frame `pose` (the shape moved by pose).
Sdf moved(Sdf f, const Eigen::Isometry3d& pose);
}  // namespace sdf

/// A thick plate with round through-holes in a row: a solid of genus `holes` (>= 0), lying on
/// z = 0, centred in x and y. Its surface has beta1 = 2 x holes; the solid has beta1 = holes.
struct HoledPlate {
  int holes = 2;
  double hole_radius = 0.05;
  double thickness = 0.05;
  double margin = 0.05;     ///< material between holes and around them
  double rounding = 0.012;  ///< edge and hole-rim rounding
  double cell = 0.005;      ///< meshing resolution
};
TriangleMesh holed_plate(const HoledPlate& p);

/// A purse: a rounded box standing on z = 0 with an arched round handle on top (half a torus in
/// the x-z plane whose other half is buried in the body). As a solid beta1 = 1: the handle's hole,
/// 2 x (handle_radius - handle_tube) wide and handle_radius - handle_tube high.
struct Purse {
  Eigen::Vector3d body{0.30, 0.12, 0.20};  ///< width (x), depth (y), height (z)
  double body_rounding = 0.02;
  double handle_radius = 0.09;  ///< centre line of the arch
  double handle_tube = 0.012;   ///< radius of the handle's cross-section
  double cell = 0.004;
};
TriangleMesh purse(const Purse& p = {});
/// The purse's handle hole: the top of the body, handle centre (for tests and scenarios).
Eigen::Vector3d purse_handle_centre(const Purse& p = {});

/// An open container standing on z = 0 (a cup, a mug, a jug): a round wall with a bottom, open
/// at the top, and optionally a side handle (half a torus on the +x side, in the x-z plane). The
/// mouth is no through-hole: as a solid, beta1 = 1 with a handle (its hole), 0 without.
struct Container {
  double radius = 0.045;  ///< outer radius of the wall
  double height = 0.10;
  double wall = 0.004;         ///< wall and bottom thickness
  double handle_radius = 0.0;  ///< centre line of the handle's arch; 0 = no handle
  double handle_tube = 0.008;  ///< radius of the handle's cross-section
  double handle_height = 0.5;  ///< handle centre as a fraction of the height
  double cell = 0.003;
};
TriangleMesh container(const Container& c);
/// The handle's hole centre (for tests).
Eigen::Vector3d container_handle_centre(const Container& c);

/// A horizontal square (two triangles, facing +z), e.g. a table under the object.
TriangleMesh ground_plane(double size, double z = 0.0,
                          const Eigen::Vector2d& centre = Eigen::Vector2d::Zero());

/// A Kinect-like 640x480 camera (fx = fy = 525) at `position` looking at `target`, image up
/// towards world +z, depth_scale 0.0002 m; it renders complete synthetic scenes, so a pixel without
/// a reading saw nothing (no_reading_is_free).
perception::CameraModel kinect_camera(const Eigen::Vector3d& position,
                                      const Eigen::Vector3d& target);

/// Cameras for the purse's example depth files: 1 (front, from above) or 2 (plus back left).
std::vector<perception::CameraModel> purse_cameras(int count);

/// Renders `scene` from each camera and writes `<stem>_<i>.png` and `<stem>_<i>.yaml` into
/// `dir` (created if needed); returns the paths as (png, yaml) pairs, in camera order.
std::vector<std::pair<std::string, std::string>> write_depth_files(
    const TriangleMesh& scene, const std::vector<perception::CameraModel>& cameras,
    const std::string& dir, const std::string& stem, const perception::DepthNoise& noise = {});

/// The example depth files of the purse on a table (1 or 2 cameras): what scenario files use.
std::vector<std::pair<std::string, std::string>> write_purse_depth_example(
    const std::string& dir, int cameras = 2, const perception::DepthNoise& noise = {});

}  // namespace claspplan::objects
