// A picture of K_d with its loops, the best one in red (like the paper's Fig. 3), via OpenCV.
#pragma once

#include <string>

#include "perception/next_view.hpp"
#include "perception/pipeline.hpp"

namespace claspplan::perception {

/// Draws the triangles of K_d (grey, shaded, back to front), its edges in no triangle (thin grey),
/// the loops (blue; the best claspable one thick red) and a caption, seen from the first camera's
/// direction if the model has views, else obliquely. Throws std::runtime_error if the file cannot
/// be written.
void draw_object_model_png(const ObjectModel& model, const std::string& path, int width = 900,
                           int height = 700);

/// The layout of draw_sensed_space_png()'s picture, in pixels: a title row, three square panels
/// side by side with gaps, then the caption's lines.
struct SensedPictureLayout {
  static constexpr int title = 24;
  static constexpr int panel = 320;
  static constexpr int gap = 10;
};

/// Draws the sensed map (sensed_space.hpp) in three slices through `centre` (world axes: the
/// x-z plane, the y-z plane and the x-y plane): free voxels white, occupied dark blue, unknown
/// orange, outside the region grey; `loop` (optional) in red, projected onto each slice; `view`
/// (optional, a next best view) as a green line of sight to a dot at its target; `finer`
/// (optional, SensedSpace::refined() of it) stands for `space` inside its region, outlined in
/// grey. Throws std::invalid_argument for an empty map, std::runtime_error if the file cannot be
/// written.
void draw_sensed_space_png(const SensedSpace& space, const Eigen::Vector3d& centre,
                           const std::vector<Eigen::Vector3d>& loop, const std::string& caption,
                           const std::string& path, const ViewSuggestion* view = nullptr,
                           const SensedSpace* finer = nullptr);

}  // namespace claspplan::perception
