#include "test/fuzz/fuzz_inputs.hpp"

#include <exception>
#include <functional>
#include <map>
#include <stdexcept>

#include "core/file_io.hpp"
#include "examples/curve_file.hpp"
#include "examples/result_file.hpp"
#include "examples/scenario.hpp"
#include "perception/camera.hpp"
#include "perception/sensor_cloud.hpp"
#include "robots/embedded_models.hpp"
#include "robots/robot_model.hpp"

namespace claspplan::fuzz {
namespace {

// The depth target's camera: small, so that a valid image decodes quickly.
perception::CameraModel depth_camera() {
  perception::CameraModel c;
  c.width = 32;
  c.height = 24;
  c.fx = c.fy = 30.0;
  c.cx = 15.5;
  c.cy = 11.5;
  c.depth_scale = 0.001;
  return c;
}

void geometry(const std::string& ext, const std::string& data) {
  parse_geometry(data, "fuzz." + ext);
}

// A cloud file as geometry and as sensor data (its grid, viewpoint and the depth view made of it):
// both readers run on every input, the first input error is rethrown.
void cloud(const std::string& ext, const std::string& data) {
  std::exception_ptr error;
  const auto attempt = [&](const std::function<void()>& f) {
    try {
      f();
    } catch (const std::invalid_argument&) {
      if (!error) error = std::current_exception();
    }
  };
  attempt([&] { geometry(ext, data); });
  attempt([&] {
    const std::string name = "fuzz." + ext;
    const perception::SensorCloud c = perception::parse_sensor_cloud(data, name);
    perception::check_metric_units(c.valid_points(), name);
    if (c.organized())
      perception::organized_cloud_view(c, Eigen::Isometry3d::Identity(), name);
    else if (c.viewpoint)
      perception::unorganized_cloud_view(c.points, c.viewpoint->translation(), name);
  });
  if (error) std::rethrow_exception(error);
}

// The URDF and hand description of the built-in kr5_sdh: the fixed half of the robot targets.
std::string sdh_file(const char* name) {
  const char* text = robots::embedded_model_file(name);
  if (!text) throw std::logic_error(std::string("not embedded: ") + name);
  return text;
}

using Parser = std::function<void(const std::string&)>;

const std::map<std::string, Parser>& parsers() {
  static const std::map<std::string, Parser> table = {
      {"depth_png",
       [](const std::string& d) {
         perception::DepthView view;
         view.camera = depth_camera();
         view.image = perception::decode_depth_png(d, view.camera, "fuzz.png");
         perception::depth_to_points(view);
       }},
      {"camera_yaml", [](const std::string& d) { perception::parse_camera_yaml(d, "fuzz.yaml"); }},
      {"pcd", [](const std::string& d) { cloud("pcd", d); }},
      {"ply", [](const std::string& d) { cloud("ply", d); }},
      {"xyz", [](const std::string& d) { cloud("xyz", d); }},
      {"obj", [](const std::string& d) { geometry("obj", d); }},
      {"stl", [](const std::string& d) { geometry("stl", d); }},
      {"off", [](const std::string& d) { geometry("off", d); }},
      {"urdf",
       [](const std::string& d) {
         robots::load_robot_from_text(sdh_file("kr5_sdh.yaml"), d, "kr5_sdh.yaml", "fuzz.urdf");
       }},
      {"hand_description",
       [](const std::string& d) {
         robots::load_robot_from_text(d, sdh_file("kr5_sdh.urdf"), "fuzz.yaml", "kr5_sdh.urdf");
       }},
      // Paths in a scenario are only resolved here, not read (each file has its own target).
      {"scenario", [](const std::string& d) { cli::load_scenario_text(d, "fuzz.yaml", "/fuzz"); }},
      // `claspplan linking` reads a closed and an open curve.
      {"curve",
       [](const std::string& d) {
         try {
           cli::parse_curve_text(d, "fuzz.xyz", true);
         } catch (const std::invalid_argument&) {
         }
         cli::parse_curve_text(d, "fuzz.xyz", false);
       }},
      {"result_json", [](const std::string& d) { cli::parse_result_file(d, "fuzz.json", true); }},
  };
  return table;
}

}  // namespace

std::vector<std::string> target_names() {
  std::vector<std::string> names;
  for (const auto& entry : parsers()) names.push_back(entry.first);
  return names;
}

void parse_input(const std::string& target, const std::string& data) {
  const auto it = parsers().find(target);
  if (it == parsers().end()) throw std::logic_error("no fuzz target named '" + target + "'");
  it->second(data);
}

}  // namespace claspplan::fuzz
