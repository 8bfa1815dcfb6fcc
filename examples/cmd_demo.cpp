// `claspplan demo`: the linking core on a built-in example. A two-finger curve closes step by step
// around one strand of a ring; Lk of the ring with the virtually closed finger loop switches from
// 0 to 1 once the strand runs through it, and VLk (eq. 2) then rises as the cord shortens.
#include <cmath>
#include <cstdio>

#include "examples/command.hpp"
#include "servo/linking.hpp"

namespace claspplan::cli {
namespace {

constexpr double kPi = 3.14159265358979323846;

struct DemoOptions {
  bool json = false;
};

// A ring of radius 0.1 m in the xy-plane; its strand at (0.1, 0, 0) runs along −y.
servo::Points ring() {
  servo::Points loop;
  for (int i = 0; i < 64; ++i) {
    const double t = -2.0 * kPi * i / 64;
    loop.emplace_back(0.1 * std::cos(t), 0.1 * std::sin(t), 0.0);
  }
  return loop;
}

// Fingertip → finger joints → palm → thumb joints → thumb tip, as a 9-point arc of radius 0.04 m
// in the xz-plane around the strand, opened by `span` radians and centred on the palm (−x side).
servo::Points finger_curve(double span) {
  servo::Points curve;
  for (int i = 0; i < 9; ++i) {
    const double t = kPi - span / 2.0 + span * i / 8.0;
    curve.emplace_back(0.1 + 0.04 * std::cos(t), 0.0, 0.04 * std::sin(t));
  }
  return curve;
}

int run_demo(const DemoOptions& o) {
  const servo::Points loop = ring();
  nlohmann::json steps = nlohmann::json::array();
  if (!o.json) {
    std::printf("A finger curve closes around a ring's strand (paper eq. 1-2):\n");
    std::printf("%10s %8s %10s %10s %14s\n", "span/deg", "Lk", "cord/m", "VLk", "open Gauss");
  }
  for (int deg = 50; deg <= 350; deg += 20) {
    const servo::Points finger = finger_curve(deg * kPi / 180.0);
    const servo::VirtualLinking vlk = servo::virtual_linking(loop, finger);
    const double open = servo::gauss_linking(loop, true, finger, false);
    steps.push_back({{"span", deg * kPi / 180.0},
                     {"linking", vlk.closed_linking},
                     {"cord", vlk.cord},
                     {"virtual_linking", vlk.value},
                     {"open_linking", open}});
    if (!o.json) {
      std::printf("%10d %8d %10.4f %10.4f %14.4f\n", deg, vlk.closed_linking, vlk.cord, vlk.value,
                  open);
    }
  }
  if (o.json) print_json({{"steps", steps}});
  return kOk;
}

}  // namespace

void add_demo_command(CLI::App& app, Action& action) {
  auto o = std::make_shared<DemoOptions>();
  CLI::App* cmd = app.add_subcommand("demo", "Run the built-in example");
  cmd->add_flag("--json", o->json, "print one JSON object instead of the table");
  cmd->callback([o, &action] { action = [o] { return run_demo(*o); }; });
}

}  // namespace claspplan::cli
