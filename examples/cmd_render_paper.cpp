// `claspplan render-paper DIR [--scene NAME]... [--noise M] [--dropout P]`: renders the paper's
// experiment scenes (examples/paper_scenes.hpp) with the synthetic depth sensor into
// DIR/<scene>/view_<i>.png + .yaml and scene.json. examples/scripts/paper_examples.sh runs it to
// regenerate examples/depth/ and the scenarios that read them.
#include <cstdio>

#include "examples/command.hpp"
#include "examples/paper_scenes.hpp"

namespace claspplan::cli {
namespace {

struct RenderPaperOptions {
  std::string dir;
  std::vector<std::string> scenes;
  double sigma = 0.001;
  double dropout = 0.02;
  bool json = false;
};

int run_render_paper(const RenderPaperOptions& o) {
  if (!(o.sigma >= 0 && o.sigma <= 0.1)) throw std::invalid_argument("--noise must be in [0, 0.1]");
  if (!(o.dropout >= 0 && o.dropout < 1))
    throw std::invalid_argument("--dropout must be in [0, 1)");
  const std::vector<std::string> names = o.scenes.empty() ? paper_scene_names() : o.scenes;
  nlohmann::json out = nlohmann::json::object();
  for (const auto& name : names) {
    const PaperScene scene = paper_scene(name);
    const auto files = write_paper_scene(scene, o.dir + "/" + name, o.sigma, o.dropout);
    if (!o.json)
      std::printf("%s: %zu files in %s/%s\n", name.c_str(), files.size(), o.dir.c_str(),
                  name.c_str());
    out[name] = files;
  }
  if (o.json) print_json({{"scenes", out}});
  return kOk;
}

}  // namespace

void add_render_paper_command(CLI::App& app, Action& action) {
  auto o = std::make_shared<RenderPaperOptions>();
  CLI::App* cmd = app.add_subcommand("render-paper", command_description("render-paper"));
  cmd->add_option("DIR", o->dir, "output directory")->required();
  cmd->add_option("--scene", o->scenes, "only this scene, e.g. chair_2 (repeatable)")
      ->allow_extra_args(false);
  cmd->add_option("--noise", o->sigma, "Gaussian depth noise, metres")->capture_default_str();
  cmd->add_option("--dropout", o->dropout, "probability of a pixel without reading")
      ->capture_default_str();
  cmd->add_flag("--json", o->json, "print the written files as JSON");
  cmd->callback([o, &action] { action = [o] { return run_render_paper(*o); }; });
}

}  // namespace claspplan::cli
