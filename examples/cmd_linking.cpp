// `claspplan linking CURVE_A CURVE_B [--virtual] [--json]`: Lk of two closed curves, or with
// --virtual the virtual linking (eq. 2) of a closed A and an open B.
#include <cmath>
#include <cstdio>
#include <iostream>

#include "core/input_error.hpp"
#include "examples/command.hpp"
#include "examples/curve_file.hpp"
#include "servo/linking.hpp"

namespace claspplan::cli {
namespace {

struct LinkingOptions {
  std::string curve_a, curve_b;
  bool virtual_linking = false;
  bool json = false;
};

int run_linking(const LinkingOptions& o) {
  const servo::Points a = read_curve_file(o.curve_a, /*closed=*/true);
  const servo::Points b = read_curve_file(o.curve_b, /*closed=*/!o.virtual_linking);

  // B closed (by its cord, with --virtual). A 2-point open curve closes to a degenerate loop that
  // links nothing; an open curve ending where it starts needs no cord.
  servo::Points b_closed = b;
  if (b_closed.size() > 2 && b_closed.front() == b_closed.back()) b_closed.pop_back();
  const bool degenerate = b_closed.size() < 3;
  // The Gauss sum also detects intersections; the crossing count gives the exact integer.
  const double gauss_closed = degenerate ? 0.0 : servo::gauss_linking(a, true, b_closed, true);
  const int lk = degenerate ? 0 : servo::linking_number(a, b_closed);
  if (std::abs(gauss_closed - lk) > 1e-6) {
    throw std::logic_error("crossing count " + std::to_string(lk) +
                           " disagrees with the Gauss sum " + std::to_string(gauss_closed));
  }
  nlohmann::json out = {{"linking", lk}, {"gauss_sum", gauss_closed}};
  if (!o.virtual_linking) {
    if (o.json) {
      print_json(out);
    } else {
      std::printf("Lk(A, B) = %d   (Gauss sum %.12f)\n", lk, gauss_closed);
    }
    return kOk;
  }

  const servo::VirtualLinking vlk = servo::virtual_linking(a, b);
  const double open = servo::gauss_linking(a, true, b, false);
  out["virtual_linking"] = vlk.value;
  out["open_linking"] = open;
  out["cord"] = vlk.cord;
  out["closed_length"] = vlk.closed_length;
  if (o.json) {
    print_json(out);
  } else {
    std::printf("Lk(A, B closed by its cord) = %d   (Gauss sum %.12f)\n", lk, gauss_closed);
    std::printf("cord %.6f m of a %.6f m virtual loop: closure 1 - cord/length = %.6f\n", vlk.cord,
                vlk.closed_length, vlk.closure());
    std::printf("VLk(A, B) = %.6f\n", vlk.value);
    std::printf("Gauss integral of A with the open B = %.6f\n", open);
  }
  return kOk;
}

}  // namespace

void add_linking_command(CLI::App& app, Action& action) {
  auto o = std::make_shared<LinkingOptions>();
  CLI::App* cmd = app.add_subcommand("linking", command_description("linking"));
  cmd->add_option("CURVE_A", o->curve_a, "closed curve file")->required();
  cmd->add_option("CURVE_B", o->curve_b, "curve file (closed, or open with --virtual)")->required();
  cmd->add_flag(
      "--virtual", o->virtual_linking,
      "B is an open finger curve: report VLk(A, B), Lk with B closed by its cord, and the "
      "Gauss integral with the open B");
  cmd->add_flag("--json", o->json, "print one JSON object instead of the summary");
  cmd->callback([o, &action] {
    action = [o] {
      try {
        return run_linking(*o);
      } catch (const servo::CurvesIntersect& e) {
        throw InputError(e.what());  // the user's own curves touch: their input is bad
      }
    };
  });
}

}  // namespace claspplan::cli
