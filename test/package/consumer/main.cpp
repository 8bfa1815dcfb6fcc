// Uses each installed library once, with the include paths of the source tree; prints lines that
// test/package/package_test.cmake checks.
#include <cmath>
#include <cstdio>
#include <exception>
#include <stdexcept>
#include <string>
#include <vector>

#include "perception/cloud_filters.hpp"
#include "perception/complex.hpp"
#include "perception/homology.hpp"
#include "robots/collision_world.hpp"
#include "robots/hand_size.hpp"
#include "robots/robot_model.hpp"
#include "servo/linking.hpp"
#include "tsrrt/clasp_setup.hpp"

using namespace claspplan;

int main() try {
  // robots: a built-in robot (embedded in the library) and an installed model file.
  const robots::RobotModel sdh = robots::load_robot("kr5_sdh");
  const robots::HandSize size = robots::hand_size(sdh);
  std::printf("robot %s: %d arm + %d hand joints\n", sdh.name.c_str(), sdh.arm_dof, sdh.hand_dof);
  std::printf("hand size: finger thickness %.4f m, closed aperture %.4f m\n", size.finger_thickness,
              size.closed_aperture);
  const robots::RobotModel dlr = robots::load_robot(CLASPPLAN_ROBOTS_DIR "/kr5_dlr.yaml");
  std::printf("robot file %s: %d joints\n", dlr.name.c_str(), dlr.dof());

  // robots: collision checking (FCL); the home pose is free.
  robots::CollisionWorld world(sdh);
  std::printf("home in collision: %s\n", world.in_collision(sdh.home) ? "yes" : "no");

  // perception: a solid ring of points (CGAL Delaunay, K_d, homology) has one loop.
  PointCloud ring;
  for (int i = 0; i < 60; ++i)
    for (int j = 0; j < 8; ++j) {
      const double u = 2 * M_PI * i / 60, v = 2 * M_PI * (j + 0.5 * (i % 2)) / 8;
      const double r = 0.1 + 0.02 * std::cos(v);
      ring.emplace_back(r * std::cos(u), r * std::sin(u), 0.02 * std::sin(v));
    }
  ring = perception::unique_points(ring);
  const perception::SimplicialComplex k =
      perception::build_complex(perception::delaunay_3d(ring), perception::automatic_d(ring));
  const perception::HomologyBasis basis = perception::shortest_homology_basis(k);
  std::printf("ring: %zu points, beta1 %d\n", ring.size(), basis.beta1);

  // servo: two linked circles (a Hopf link).
  servo::Points a, b;
  for (int i = 0; i < 32; ++i) {
    const double t = 2 * M_PI * i / 32;
    a.emplace_back(std::cos(t), std::sin(t), 0);
    b.emplace_back(1 + std::cos(t), 0, std::sin(t));
  }
  std::printf("hopf link: linking number %d, gauss %.3f\n", std::abs(servo::linking_number(a, b)),
              std::abs(servo::gauss_linking(a, true, b, true)));

  // tsrrt: a tube around the loop, and the API refusing a request without a robot.
  TriangleMesh tube;
  tsrrt::loop_tube(a, 0.05, tube);
  std::printf("loop tube: %zu vertices, %zu triangles\n", tube.vertices.size(),
              tube.triangles.size());
  try {
    tsrrt::plan_clasp(tsrrt::ClaspRequest{});
    std::printf("plan_clasp without a robot: accepted\n");
  } catch (const std::invalid_argument&) {
    std::printf("plan_clasp without a robot: invalid_argument\n");
  }
  return 0;
} catch (const std::exception& e) {
  std::fprintf(stderr, "error: %s\n", e.what());
  return 1;
}
