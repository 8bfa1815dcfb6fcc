// The scene a clasp is planned in, from the object model: which loop to clasp (or why none can
// be), and the object's collision model around it.
#pragma once

#include <optional>
#include <string>
#include <vector>

#include <Eigen/Core>

#include "perception/pipeline.hpp"

namespace claspplan::tsrrt {

/// The claspable loop to clasp: the one with a point nearest `hint`, else the best ranked; -1
/// (an index into object.loops) when no loop is claspable.
int choose_loop(const perception::ObjectModel& object, const std::optional<Eigen::Vector3d>& hint);

/// One line on why an object has no claspable loop: no loops at all, only unstable ones, or the
/// first three loops' verdicts.
std::string no_loop_reason(const perception::ObjectModel& object);

/// The loop's material in the collision model (m): see loop_tube().
constexpr double kLoopTubeRadius = 0.003;

/// The object's collision model everywhere (planning, closing, verification): the surface the
/// depth cameras saw (K_d is for topology: its long triangles web across holes), else K_d's
/// triangles for clouds and whole-surface samples; and a thin tube along the clasped loop, so the
/// loop itself is always material. `workspace` crops the depth surface (the perception's crop).
/// Throws std::invalid_argument when there is no surface at all; `name` prefixes the message.
void object_collision_mesh(const perception::ObjectModel& object, const perception::Loop& loop,
                           const Eigen::AlignedBox3d& workspace, const std::string& name,
                           std::vector<Eigen::Vector3d>& vertices,
                           std::vector<Eigen::Vector3i>& triangles);

}  // namespace claspplan::tsrrt
