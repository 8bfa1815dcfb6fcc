#include "examples/result_pictures.hpp"

#include <algorithm>
#include <cmath>

#include <Eigen/Geometry>

#include "core/png_files.hpp"
#include "robots/kinematics.hpp"

namespace claspplan::cli {
namespace {

const cv::Scalar kArm(60, 140, 230);  // BGR: orange
const cv::Scalar kHand(150, 150, 150);
const cv::Scalar kObject(170, 200, 120);
const cv::Scalar kBox(200, 190, 180);
const cv::Scalar kLoop(30, 30, 220);        // red
const cv::Scalar kStartLoop(220, 120, 40);  // blue

TriangleMesh shape_mesh(const robots::CollisionShape& s) {
  using Type = robots::CollisionShape::Type;
  switch (s.type) {
    case Type::kBox:
      return box_mesh(s.size);
    case Type::kSphere:
      return sphere_mesh(s.radius);
    case Type::kCylinder:
      return cylinder_mesh(s.radius, s.length);
    case Type::kCapsule:
      return capsule_mesh(s.radius, s.length);
    case Type::kMesh:
      return *s.mesh;
  }
  return {};
}

// The hand's finger curves and the object give the framing of close-up views.
std::vector<Eigen::Vector3d> hand_points(const robots::RobotModel& model,
                                         const Eigen::VectorXd& q) {
  robots::RobotData data(model);
  robots::FingerCurvesData curves;
  robots::finger_curves(model, q, data, curves, false);
  std::vector<Eigen::Vector3d> points;
  for (const auto& c : curves.points) points.insert(points.end(), c.begin(), c.end());
  return points;
}

Eigen::Vector3d hand_centre(const robots::RobotModel& model, const Eigen::VectorXd& q) {
  Eigen::Vector3d sum = Eigen::Vector3d::Zero();
  const auto points = hand_points(model, q);
  for (const auto& p : points) sum += p;
  return sum / static_cast<double>(points.size());
}

// The robot's shapes at q (only the hand's with `hand_only`).
void draw_robot(SceneImage& image, const robots::RobotModel& model, const Eigen::VectorXd& q,
                bool hand_only) {
  robots::RobotData data(model);
  robots::forward_kinematics(model, q, data);
  for (const auto& shape : model.shapes) {
    const bool hand = model.links[shape.link].hand;
    if (hand_only && !hand) continue;
    image.draw_mesh(shape_mesh(shape), robots::shape_pose(data, shape).matrix(),
                    hand ? kHand : kArm);
  }
}

// The close-up view directions of the hand at q, each with its mirror image across the closing
// plane and a raised variant to fall back on: along the loop's tangent (front) and across the
// closing plane (side), a little from behind the hand, so the palm and the fingers' far side both
// show.
struct ClaspViews {
  std::vector<Eigen::Vector3d> front, side;
};
ClaspViews clasp_views(const robots::RobotModel& model, const Eigen::VectorXd& q) {
  robots::RobotData data(model);
  robots::forward_kinematics(model, q, data);
  const Eigen::Vector3d forward = robots::vector_direction(data, model.v_fwd);
  const Eigen::Vector3d sideways = robots::vector_direction(data, model.v_swd);
  const Eigen::Vector3d across = forward.cross(sideways);
  const Eigen::Vector3d front = sideways - 0.35 * forward;
  const Eigen::Vector3d side = across - 0.35 * forward + 0.3 * sideways;
  const Eigen::Vector3d up = Eigen::Vector3d::UnitZ();
  return {{front, -sideways - 0.35 * forward, front.normalized() + up},
          {side, -across - 0.35 * forward + 0.3 * sideways, side.normalized() + up}};
}

// The scene without the environment boxes that block the view's line of sight.
SceneGeometry cut_away(const SceneGeometry& scene, const View& view) {
  SceneGeometry out{scene.model, scene.object, {}, scene.loop};
  for (const auto& b : scene.boxes)
    if (!blocks_sight(b, view)) out.boxes.push_back(b);
  return out;
}

}  // namespace

bool blocks_sight(const EnvironmentBox& box, const View& view) {
  // The segment eye -> target clipped against the box's slabs, in the box's frame.
  const Eigen::Vector3d a = box.pose.inverse() * view.eye;
  const Eigen::Vector3d d = box.pose.inverse() * view.target - a;
  const Eigen::Vector3d half = 0.5 * box.size;
  double t0 = 0.0, t1 = 1.0;
  for (int i = 0; i < 3; ++i) {
    if (std::abs(d[i]) < 1e-12) {
      if (std::abs(a[i]) > half[i]) return false;
      continue;
    }
    double lo = (-half[i] - a[i]) / d[i], hi = (half[i] - a[i]) / d[i];
    if (lo > hi) std::swap(lo, hi);
    t0 = std::max(t0, lo);
    t1 = std::min(t1, hi);
    if (t0 > t1) return false;
  }
  return true;
}

View unobstructed_view(const std::vector<Eigen::Vector3d>& frame,
                       const std::vector<Eigen::Vector3d>& directions,
                       const std::vector<EnvironmentBox>& boxes) {
  View best;
  long fewest = -1;
  for (const auto& direction : directions) {
    const View view = framing_view(frame, direction);
    const long blocked = std::count_if(
        boxes.begin(), boxes.end(), [&](const EnvironmentBox& b) { return blocks_sight(b, view); });
    if (fewest < 0 || blocked < fewest) best = view, fewest = blocked;
    if (blocked == 0) break;
  }
  return best;
}

void draw_scene(SceneImage& image, const SceneGeometry& scene, const Eigen::VectorXd& q,
                bool hand_only) {
  for (const auto& b : scene.boxes) image.draw_mesh(box_mesh(b.size), b.pose.matrix(), kBox);
  image.draw_mesh(scene.object, Eigen::Matrix4d::Identity(), kObject);
  draw_robot(image, scene.model, q, hand_only);
  image.draw_polyline(scene.loop, true, kLoop, 3);
}

void write_clasp_views(const SceneGeometry& scene, const Eigen::VectorXd& q,
                       const std::string& dir) {
  const std::vector<Eigen::Vector3d> frame = hand_points(scene.model, q);
  const ClaspViews directions = clasp_views(scene.model, q);
  const std::pair<const char*, std::vector<Eigen::Vector3d>> views[] = {
      {"clasp_front.png", directions.front}, {"clasp_side.png", directions.side}};
  for (const auto& [name, candidates] : views) {
    const View view = unobstructed_view(frame, candidates, scene.boxes);
    SceneImage image(view);
    draw_scene(image, cut_away(scene, view), q, /*hand_only=*/true);
    image.draw_label("final clasp (" + scene.model.name + "), loop in red; arm not drawn");
    image.save(dir + "/" + name);
  }
}

void write_escape_view(const SceneGeometry& scene, const Eigen::VectorXd& q,
                       const Eigen::Isometry3d& escape, const std::string& file) {
  std::vector<Eigen::Vector3d> moved;
  for (const auto& p : scene.loop) moved.push_back(escape * p);
  std::vector<Eigen::Vector3d> frame = hand_points(scene.model, q);
  frame.insert(frame.end(), moved.begin(), moved.end());
  // As clasp_side.png; the environment is not drawn here.
  SceneImage image(unobstructed_view(frame, clasp_views(scene.model, q).side, scene.boxes));
  image.draw_mesh(scene.object, escape.matrix(), kObject);
  draw_robot(image, scene.model, q, /*hand_only=*/true);
  image.draw_polyline(scene.loop, true, kStartLoop, 2);
  image.draw_polyline(moved, true, kLoop, 3);
  image.draw_label("escape: the object got free of the closed hand (" + scene.model.name +
                   "); its loop in red, where it started in blue");
  image.save(file);
}

void write_tree_picture(const SceneGeometry& scene, const Eigen::VectorXd& q_start,
                        const tsrrt::ClaspStatistics& search,
                        const std::vector<Eigen::VectorXd>& path, const std::string& file) {
  std::vector<Eigen::Vector3d> tree, solution, pruned;
  for (const auto& x : search.tree_points) tree.push_back(x.position);
  for (int i : search.solution_nodes) solution.push_back(search.tree_points[i].position);
  for (const auto& q : path) pruned.push_back(hand_centre(scene.model, q));
  std::vector<Eigen::Vector3d> frame = tree;
  frame.insert(frame.end(), scene.loop.begin(), scene.loop.end());
  SceneImage image(framing_view(frame, Eigen::Vector3d(0.8, -1.0, 0.7)));
  draw_scene(image, scene, q_start);
  image.draw_points(tree, cv::Scalar(40, 40, 220), 3);
  image.draw_points(solution, cv::Scalar(220, 80, 30), 4);
  image.draw_polyline(pruned, false, cv::Scalar(40, 170, 40), 2, true);
  image.draw_label("TS-RRT: " + std::to_string(search.nodes) + " nodes (red), solution (blue), " +
                   "pruned path (green)");
  image.save(file);
}

void write_path_poses(const SceneGeometry& scene, const std::vector<Eigen::VectorXd>& path,
                      const std::string& file) {
  // Arc length along the joint-space path.
  std::vector<double> s(path.size(), 0.0);
  for (std::size_t i = 1; i < path.size(); ++i) s[i] = s[i - 1] + (path[i] - path[i - 1]).norm();
  std::vector<Eigen::Vector3d> frame;
  for (const auto& q : path) {
    const auto h = hand_points(scene.model, q);
    frame.insert(frame.end(), h.begin(), h.end());
  }
  frame.insert(frame.end(), scene.loop.begin(), scene.loop.end());
  const View view = framing_view(frame, Eigen::Vector3d(0.9, -0.9, 0.6), 480, 360);
  std::vector<cv::Mat> panels;
  for (int percent : {20, 40, 60, 80}) {
    const double target = s.back() * percent / 100.0;
    std::size_t i = 0;
    while (i + 2 < path.size() && s[i + 1] < target) ++i;
    const double span = s[i + 1] - s[i];
    const double f = span > 0.0 ? (target - s[i]) / span : 0.0;
    const Eigen::VectorXd q =
        path.size() > 1 ? Eigen::VectorXd(path[i] + f * (path[i + 1] - path[i])) : path.front();
    SceneImage image(view);
    draw_scene(image, scene, q);
    image.draw_label(std::to_string(percent) + "% of the path");
    panels.push_back(image.image());
  }
  cv::Mat top, bottom, all;
  cv::hconcat(panels[0], panels[1], top);
  cv::hconcat(panels[2], panels[3], bottom);
  cv::vconcat(top, bottom, all);
  write_png(file, all);
}

}  // namespace claspplan::cli
