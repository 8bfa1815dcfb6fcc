// `claspplan loops INPUT... [--camera CAM]... [--points N] [--d METRES] [--min-hole METRES]
//  [--seed N] [--view X,Y,Z]... [--targets K] [--robot NAME] [--png FILE] [--json]`: perception
// only (paper Sec. IV-A): the object's loops, ranked (for a hand with --robot), and the clasp
// targets on the best one.
// Also the hidden `claspplan render-example DIR`, which writes the purse's example depth files.
#include <cmath>
#include <cstdio>
#include <optional>
#include <sstream>

#include "core/input_error.hpp"
#include "examples/command.hpp"
#include "examples/objects.hpp"
#include "perception/drawing.hpp"
#include "perception/pipeline.hpp"
#include "robots/hand_size.hpp"

namespace claspplan::cli {
namespace {

struct LoopsOptions {
  std::vector<std::string> inputs, cameras, views;
  std::string crop, png, sensed_png, robot;
  int points = 2000;
  double d = 0.0;
  double min_hole = 0.03;
  int targets = 12;
  long long seed = 1;
  bool keep_plane = false;
  bool json = false;
};

std::vector<double> numbers(const std::string& text, size_t count, const std::string& what) {
  std::vector<double> v;
  std::stringstream ss(text);
  std::string item;
  while (std::getline(ss, item, ',')) {
    char* end = nullptr;
    const double x = std::strtod(item.c_str(), &end);
    if (item.empty() || end != item.c_str() + item.size() || !std::isfinite(x))
      throw InputError(what + " '" + text + "': '" + item + "' is not a finite number");
    v.push_back(x);
  }
  if (v.size() != count)
    throw InputError(what + " '" + text + "' must have " + std::to_string(count) +
                     " comma-separated numbers");
  return v;
}

nlohmann::json vec(const Eigen::Vector3d& p) {
  return {p.x(), p.y(), p.z()};
}

// Bar thickness along the loop; null where the material is a wall or body (no bar).
nlohmann::json bar_profile(const perception::Loop& l) {
  nlohmann::json a = nlohmann::json::array();
  for (double b : l.bar_profile) a.push_back(std::isfinite(b) ? nlohmann::json(b) : nullptr);
  return a;
}

// `loops --json`: one object with the model, its loops, the sensed space and the timings.
nlohmann::json loops_json(const LoopsOptions& o, const perception::ObjectModel& model,
                          const std::optional<robots::HandSize>& hand) {
  using namespace perception;
  nlohmann::json loops = nlohmann::json::array();
  for (const auto& l : model.loops) {
    nlohmann::json pts = nlohmann::json::array();
    for (const auto& p : l.points) pts.push_back(vec(p));
    loops.push_back(
        {{"length", l.length},
         {"rank", l.rank},
         {"claspable", l.claspable},
         {"verdict", perception::verdict_name(l.verdict)},
         {"reason", l.reason},
         {"hole_width", l.hole_width},
         {"bar_thickness", std::isfinite(l.bar_thickness) ? nlohmann::json(l.bar_thickness)
                                                          : nlohmann::json(nullptr)},
         {"fit", l.fit},
         {"bar_profile", bar_profile(l)},
         {"centre", vec(l.centre)},
         {"normal", vec(l.normal)},
         {"points", pts}});
  }
  nlohmann::json targets = nlohmann::json::array();
  for (const auto& t : model.targets)
    targets.push_back({{"p", vec(t.point)}, {"tangent", vec(t.tangent)}});
  const auto& tm = model.timings;
  nlohmann::json out = {{"beta1", model.beta1},
                        {"stable_loops", static_cast<int>(model.loops.size())},
                        {"unstable_loops", model.unstable_loops},
                        {"persistence_d", model.persistence_d},
                        {"d", model.d},
                        {"d_rule", model.d_rule},
                        {"objects", model.objects},
                        {"mean_spacing", model.mean_spacing},
                        {"points", static_cast<int>(model.cloud.size())},
                        {"input_points", model.input_points},
                        {"loops", loops},
                        {"targets", targets},
                        {"seconds", tm.total},
                        {"timings",
                         {{"preprocess", tm.preprocess},
                          {"spacing", tm.downsample},
                          {"delaunay", tm.delaunay},
                          {"complex", tm.complex},
                          {"homology", tm.homology},
                          {"sensed", tm.sensed},
                          {"ranking", tm.ranking}}}};
  if (model.support_plane) {
    const Eigen::Vector4d& p = *model.support_plane;
    out["support_plane"] = {p[0], p[1], p[2], p[3]};
  }
  if (model.sensed) {
    const auto n = model.sensed->counts();
    const Eigen::AlignedBox3d& box = model.sensed->region();
    out["sensed"] = {{"resolution", model.sensed->resolution()},
                     {"region", {vec(box.min()), vec(box.max())}},
                     {"unknown", n[0]},
                     {"free", n[1]},
                     {"occupied", n[2]}};
  }
  if (!o.png.empty()) out["png"] = o.png;
  if (!o.sensed_png.empty()) out["sensed_png"] = o.sensed_png;
  if (hand) {
    out["hand"] = {{"robot", o.robot},
                   {"finger_thickness", hand->finger_thickness},
                   {"closed_aperture", hand->closed_aperture}};
  }
  return out;
}

// The human summary.
void print_loops(const LoopsOptions& o, const perception::ObjectModel& model,
                 const std::optional<robots::HandSize>& hand) {
  std::printf("beta1 = %d   d = %.4f m   (%s)\n", model.beta1, model.d, model.d_rule.c_str());
  std::printf("points: %zu (from %d input points)\n", model.cloud.size(), model.input_points);
  if (model.unstable_loops > 0) {
    std::printf(
        "stable loops: %zu (%d more fill in by d' = %.4f m: sampling gaps or thin tubes, "
        "dropped)\n",
        model.loops.size(), model.unstable_loops, model.persistence_d);
  }
  if (hand) {
    std::printf("hand %s: fingers %.4f m thick, closed aperture %.4f m\n", o.robot.c_str(),
                hand->finger_thickness, hand->closed_aperture);
  }
  if (model.loops.empty()) {
    std::printf("no loops: K_d has no hole at this d (beta1 = 0), nothing to clasp\n");
  }
  for (const auto& l : model.loops) {
    std::printf("loop rank %d: length %.4f m, hole %.4f m wide: %s\n", l.rank, l.length,
                l.hole_width, l.reason.c_str());
  }
  if (!model.targets.empty()) {
    std::printf("clasp targets: %zu on loop rank 1\n", model.targets.size());
  } else if (!model.loops.empty()) {
    std::printf("no claspable loop (see the reasons above)\n");
  }
  std::printf("pipeline: %.3f s\n", model.timings.total);
}

int run_loops(const LoopsOptions& o) {
  using namespace perception;
  std::vector<Eigen::Vector3d> views;
  for (const auto& v : o.views) {
    const auto x = numbers(v, 3, "--view");
    views.emplace_back(x[0], x[1], x[2]);
  }
  PerceptionOptions po;
  po.points = o.points;
  po.d = o.d;
  po.min_hole = o.min_hole;
  po.targets = o.targets;
  if (o.seed < 0) throw InputError("--seed must be >= 0");
  po.seed = static_cast<std::uint64_t>(o.seed);
  po.remove_plane = !o.keep_plane;
  if (!o.crop.empty()) {
    const auto c = numbers(o.crop, 6, "--crop");
    if (!(c[0] < c[3] && c[1] < c[4] && c[2] < c[5]))
      throw InputError("--crop needs XMIN < XMAX, YMIN < YMAX, ZMIN < ZMAX");
    po.workspace =
        Eigen::AlignedBox3d(Eigen::Vector3d(c[0], c[1], c[2]), Eigen::Vector3d(c[3], c[4], c[5]));
  }
  std::optional<robots::HandSize> hand;
  if (!o.robot.empty()) {
    hand = robots::hand_size(robots::load_robot(o.robot));
    po.finger_thickness = hand->finger_thickness;
    po.closed_aperture = hand->closed_aperture;
  }
  po.progress = [](const std::string& m) { progress(m); };
  const PerceptionInputs inputs = load_inputs(o.inputs, o.cameras, views);
  const ObjectModel model = build_object_model(inputs, po);
  if (!o.png.empty()) {
    draw_object_model_png(model, o.png);
    progress("loops: wrote " + o.png);
  }
  if (!o.sensed_png.empty()) {
    if (!model.sensed)
      throw InputError(
          "--sensed-png: no input has a sensor origin (depth views, an organized cloud, a cloud "
          "with a viewpoint)");
    const Loop* first = model.loops.empty() ? nullptr : &model.loops.front();
    draw_sensed_space_png(*model.sensed, first ? first->centre : model.sensed->region().center(),
                          first ? first->points : std::vector<Eigen::Vector3d>{},
                          first ? "loop rank 1: " + first->reason : "no loop", o.sensed_png);
    progress("loops: wrote " + o.sensed_png);
  }

  if (o.json) {
    print_json(loops_json(o, model, hand));
  } else {
    print_loops(o, model, hand);
  }
  return kOk;
}

struct RenderOptions {
  std::string dir;
  int cameras = 2;
  double sigma = 0.0;
  long long seed = 1;
};

}  // namespace

void add_loops_command(CLI::App& app, Action& action) {
  auto o = std::make_shared<LoopsOptions>();
  CLI::App* cmd = app.add_subcommand("loops", command_description("loops"));
  cmd->add_option("INPUT", o->inputs,
                  "depth PNGs (16-bit, one --camera each, in order), clouds or meshes")
      ->required();
  cmd->add_option("--camera", o->cameras, "camera YAML for the next depth PNG (repeatable)")
      ->allow_extra_args(false);
  cmd->add_option("--points", o->points, "N, points after down-sampling (default 2000)");
  cmd->add_option("--d", o->d,
                  "K_d edge length bound in metres (default: automatic, 3.5 x the mean "
                  "nearest-neighbour spacing of the N points)");
  cmd->add_option("--min-hole", o->min_hole,
                  "narrowest hole a finger can pass, metres (default 0.03)");
  cmd->add_option("--targets", o->targets, "clasp targets on the best loop (default 12)");
  cmd->add_option("--seed", o->seed, "seed of every random choice (default 1)");
  cmd->add_option("--view", o->views,
                  "X,Y,Z: sample meshes only where visible from this position (repeatable; "
                  "write --view=X,Y,Z when X is negative)")
      ->allow_extra_args(false);
  cmd->add_option("--crop", o->crop,
                  "XMIN,YMIN,ZMIN,XMAX,YMAX,ZMAX: workspace box for depth points (world frame)");
  cmd->add_flag("--keep-plane", o->keep_plane, "do not remove the supporting plane from depth");
  cmd->add_option("--robot", o->robot,
                  "rank the loops for this robot's hand (built-in name or hand-description "
                  "file): holes its fingers pass, bars its closed hand encloses");
  cmd->add_option("--png", o->png, "draw K_d with its loops (best in red) to this PNG");
  cmd->add_option("--sensed-png", o->sensed_png,
                  "draw the sensed space (free, occupied, unknown) through the first loop to "
                  "this PNG");
  cmd->add_flag("--json", o->json, "print one JSON object instead of the summary");
  cmd->callback([o, &action] { action = [o] { return run_loops(*o); }; });

  // Hidden helper: the purse's example depth files (what scenario files and demos use).
  auto r = std::make_shared<RenderOptions>();
  CLI::App* render = app.add_subcommand(
      "render-example", "Write the purse-on-a-table example depth files (PNG + camera YAML)");
  render->group("");
  render->add_option("DIR", r->dir, "output directory")->required();
  render->add_option("--cameras", r->cameras, "1 or 2 cameras (default 2)");
  render->add_option("--noise", r->sigma, "Gaussian depth noise, metres (default 0)");
  render->add_option("--seed", r->seed, "noise seed");
  render->add_flag("--json", "print the written files as JSON");
  render->callback([r, render, &action] {
    const bool json = render->count("--json") > 0;
    action = [r, json] {
      perception::DepthNoise noise;
      noise.sigma = r->sigma;
      noise.seed = static_cast<std::uint64_t>(std::max(0LL, r->seed));
      if (!(r->sigma >= 0)) throw InputError("--noise must be >= 0");
      const auto files = objects::write_purse_depth_example(r->dir, r->cameras, noise);
      nlohmann::json out = nlohmann::json::array();
      for (const auto& [png, yaml] : files) {
        if (!json) std::printf("%s --camera %s\n", png.c_str(), yaml.c_str());
        out.push_back({{"depth", png}, {"camera", yaml}});
      }
      if (json) print_json({{"files", out}});
      return kOk;
    };
  });
}

}  // namespace claspplan::cli
