#include "perception/pipeline.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <stdexcept>

#include "core/file_io.hpp"
#include "core/input_error.hpp"
#include "core/parallel.hpp"
#include "core/stopped.hpp"
#include "perception/cloud_filters.hpp"
#include "perception/depth_render.hpp"
#include "perception/sensor_cloud.hpp"

namespace claspplan::perception {

namespace {

// Down-sampling works on at most this many times N points (a seeded random subset first); depth
// points are thinned evenly to 3 N before the outlier filter, its cost dominating the 100 ms
// budget.
constexpr int kOversample = 4;
constexpr int kDepthOversample = 3;
constexpr int kDepthPool = 16;  // the random pool the even subset is drawn from
// How far below and around the workspace the supporting plane is looked for (m).
constexpr double kSupportMargin = 0.1;

double seconds_since(std::chrono::steady_clock::time_point t0) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
}

std::string lower_ext(const std::string& path) {
  std::string e = std::filesystem::path(path).extension().string();
  for (char& ch : e) ch = static_cast<char>(std::tolower(static_cast<unsigned char>(ch)));
  return e;
}

void validate_options(const PerceptionOptions& o) {
  if (o.points < 4 || o.points > kMaxPoints)
    throw InputError("--points must be in 4.." + std::to_string(kMaxPoints) + ", got " +
                     std::to_string(o.points));
  if (!(o.d >= 0) || !std::isfinite(o.d))
    throw InputError("--d must be > 0 metres (or 0 for automatic), got " + std::to_string(o.d));
  if (!(o.d_factor > 0) || !std::isfinite(o.d_factor))
    throw InputError("the automatic-d factor must be > 0");
  if (!(o.persistence >= 0) || !std::isfinite(o.persistence))
    throw InputError("the persistence factor must be >= 0");
  if (!(o.finger_thickness >= 0 && o.closed_aperture >= 0) ||
      !std::isfinite(o.finger_thickness + o.closed_aperture))
    throw InputError("hand sizes must be finite and >= 0");
  if (!(o.min_hole > 0) || !std::isfinite(o.min_hole))
    throw InputError("--min-hole must be > 0 metres, got " + std::to_string(o.min_hole));
  if (o.targets < 1 || o.targets > 100000)
    throw InputError("--targets must be in 1..100000, got " + std::to_string(o.targets));
}

void say(const PerceptionOptions& o, const std::string& msg) {
  if (o.progress) o.progress(msg);
}

std::string fmt(const char* f, double a, double b = 0, double c = 0) {
  char buf[256];
  std::snprintf(buf, sizeof buf, f, a, b, c);
  return buf;
}

}  // namespace

void add_cloud(PerceptionInputs& in, const CloudFile& file) {
  if (!file.pose.matrix().allFinite())
    throw InputError(file.path + ": the cloud's pose is not finite");
  SensorCloud cloud = read_sensor_cloud(file.path);
  if (file.viewpoint) cloud.viewpoint = file.viewpoint;
  check_metric_units(cloud.valid_points(), file.path);
  if (cloud.organized()) {
    in.depth_views.push_back(organized_cloud_view(cloud, file.pose, file.path));
    return;
  }
  PointCloud points = cloud.valid_points();
  for (auto& p : points) p = file.pose * p;
  // An unorganized PCD's identity VIEWPOINT is the format's default, written whatever the sensor
  // was (PCL's writers do): it gives no origin. Only a `viewpoint` given with the file, or a
  // VIEWPOINT that differs from the default, does.
  const bool default_viewpoint = !file.viewpoint && cloud.viewpoint &&
                                 cloud.viewpoint->isApprox(Eigen::Isometry3d::Identity());
  if (cloud.viewpoint && !default_viewpoint) {
    in.depth_views.push_back(
        unorganized_cloud_view(points, file.pose * cloud.viewpoint->translation(), file.path));
    return;
  }
  in.clouds.push_back(std::move(points));
}

PerceptionInputs load_inputs(const std::vector<std::string>& paths,
                             const std::vector<std::string>& cameras,
                             const std::vector<Eigen::Vector3d>& view_positions) {
  PerceptionInputs in;
  in.view_positions = view_positions;
  size_t pngs = 0;
  for (const auto& p : paths) pngs += lower_ext(p) == ".png";
  if (pngs != cameras.size())
    throw InputError(std::to_string(pngs) + " depth image(s) but " +
                     std::to_string(cameras.size()) +
                     " --camera file(s): give one camera per PNG, in the same order");
  // The depth images are decoded on all cores (their PNG inflation dominates); the other files
  // are read in order.
  std::vector<std::pair<std::string, std::string>> depth_jobs;  // (image, camera)
  for (const auto& p : paths) {
    if (lower_ext(p) == ".png") {
      depth_jobs.emplace_back(p, cameras[depth_jobs.size()]);
      continue;
    }
    const std::string ext = lower_ext(p);
    if (ext != ".pcd" && ext != ".xyz") {  // a mesh, or a .ply that may hold either
      GeometryFile g = read_geometry(p);
      if (g.is_mesh) {
        in.meshes.push_back(std::move(g.mesh));
        continue;
      }
    }
    CloudFile file;
    file.path = p;
    add_cloud(in, file);
  }
  const std::size_t first = in.depth_views.size();  // after the clouds' views
  in.depth_views.resize(first + depth_jobs.size());
  parallel_chunks(depth_jobs.size(), 0, [&](std::size_t begin, std::size_t end) {
    for (std::size_t i = begin; i < end; ++i) {
      const auto& [image, camera] = depth_jobs[i];
      DepthView& v = in.depth_views[first + i];
      v.camera = read_camera_yaml(camera);
      v.image = read_depth_png(image, v.camera);
      if (v.image.valid_count() == 0)
        throw InputError(image + ": the depth image has no reading (all pixels are 0)");
    }
  });
  return in;
}

namespace {

struct Prepared {
  PointCloud cloud;
  PointCloud pool;  // the points farthest-point sampling chose the cloud from
  std::vector<DepthView> views;
  int input_points = 0, plane_points = 0, outliers = 0;
  std::optional<Eigen::Vector4d> plane;
};

Prepared prepare(const PerceptionInputs& in, const PerceptionOptions& o) {
  validate_options(o);
  if (in.depth_views.empty() && in.clouds.empty() && in.meshes.empty())
    throw InputError("no input: give depth images with --camera, clouds or meshes");
  const int n = o.points;
  const int budget = kOversample * n;
  Prepared r;
  PointCloud all;
  // Sensor data (depth views, and clouds without a sensor origin after them): back-projection to
  // the world frame, crop, supporting plane, outliers.
  if (!in.depth_views.empty() || !in.clouds.empty()) {
    // The support is searched a little below and around the workspace: a crop just above the
    // table must not hide it (loop ranking needs to know where the table is). Points outside
    // that box are never stored.
    Eigen::AlignedBox3d around = o.workspace;
    if (o.remove_plane && !around.isEmpty()) {
      around.min() -= Eigen::Vector3d(kSupportMargin, kSupportMargin, kSupportMargin);
      around.max().head<2>() += Eigen::Vector2d::Constant(kSupportMargin);
    }
    for (const auto& v : in.depth_views) validate_camera(v.camera, "camera");
    // The views side by side in one buffer, each by its own core (a copy or a second buffer of
    // hundreds of thousands of points costs more than the arithmetic), then closed up in order.
    std::vector<std::size_t> offset{0};
    for (const auto& v : in.depth_views) offset.push_back(offset.back() + v.image.valid_count());
    PointCloud depth(offset.back());  // Eigen vectors: not initialised
    std::vector<DepthPixels> pixels(in.depth_views.size());
    parallel_chunks(pixels.size(), 0, [&](std::size_t begin, std::size_t end) {
      for (std::size_t i = begin; i < end; ++i)
        pixels[i] = back_project(in.depth_views[i], around, depth.data() + offset[i]);
    });
    std::size_t size = 0;
    for (std::size_t i = 0; i < pixels.size(); ++i) {
      std::copy_n(depth.begin() + offset[i], pixels[i].kept, depth.begin() + size);
      size += pixels[i].kept;
      r.input_points += pixels[i].valid;
      r.views.push_back(in.depth_views[i]);
    }
    depth.resize(size);
    for (const auto& c : in.clouds) {
      validate_cloud(c, "cloud");
      r.input_points += static_cast<int>(c.size());
      for (const auto& p : c)
        if (around.isEmpty() || around.contains(p)) depth.push_back(p);
    }
    if (r.input_points == 0) throw InputError("the depth images have no reading (all 0)");
    if (!o.workspace.isEmpty() && std::none_of(depth.begin(), depth.end(), [&](const auto& p) {
          return o.workspace.contains(p);
        }))
      throw InputError("no sensed point lies inside the workspace box");
    if (o.remove_plane) {
      PlaneRemovalOptions po;
      po.seed = o.seed;
      PlaneRemovalResult pr = remove_supporting_plane(depth, po);
      r.plane_points = pr.plane_points;
      if (pr.removed) r.plane = pr.plane;
      depth = std::move(pr.kept);
    }
    depth = crop_to_box(depth, o.workspace);
    if (depth.empty())
      throw InputError(o.remove_plane ? "no sensed point above the supporting plane"
                                      : "no sensed point lies inside the workspace box");
    // Evenly over space rather than over pixels: a thin part seen by few pixels keeps its points.
    depth =
        even_subset(random_subset(depth, kDepthPool * n, o.seed), kDepthOversample * n, o.seed + 3);
    const size_t before = depth.size();
    if (o.outlier_k > 0) depth = remove_statistical_outliers(depth, o.outlier_k, o.outlier_stddev);
    r.outliers = static_cast<int>(before - depth.size());
    all.insert(all.end(), depth.begin(), depth.end());
  }
  if (!in.meshes.empty()) {
    TriangleMesh scene;
    for (const auto& m : in.meshes) {
      validate_mesh(m, "mesh");
      append_mesh(scene, m);
    }
    PointCloud samples;
    if (!in.view_positions.empty()) {
      const auto views = render_views(scene, in.view_positions);
      samples = sample_visible_surface(scene, views, budget, o.seed);
      r.views.insert(r.views.end(), views.begin(), views.end());
    } else {
      samples = sample_surface(scene, budget, o.seed);
    }
    r.input_points += static_cast<int>(samples.size());
    all.insert(all.end(), samples.begin(), samples.end());
  }
  all = unique_points(all);
  if (all.size() < 4)
    throw InputError("fewer than 4 distinct points (" + std::to_string(all.size()) +
                     ") after filtering: nothing to triangulate");
  r.pool = random_subset(all, budget, o.seed + 1);
  r.cloud = spatial_order(farthest_point_sample(r.pool, n, o.seed + 2));
  return r;
}

}  // namespace

PointCloud object_points(const PerceptionInputs& in, const PerceptionOptions& o,
                         std::vector<DepthView>* views_out) {
  Prepared r = prepare(in, o);
  if (views_out) *views_out = std::move(r.views);
  return std::move(r.cloud);
}

namespace {

// Steps 3-6 on m.cloud: d, K_d, the stable loops, the sensed space, the ranking and the targets.
void loops_of_cloud(ObjectModel& m, const PerceptionOptions& o, bool sensor_origin_missing) {
  using Clock = std::chrono::steady_clock;
  auto t = Clock::now();
  m.mean_spacing = mean_spacing(m.cloud);
  if (o.d > 0) {
    m.d = o.d;
    m.d_rule = fmt("d = %.4f m as given (%.2f x the mean spacing %.4f m)", m.d,
                   m.d / m.mean_spacing, m.mean_spacing);
  } else {
    m.d = o.d_factor * m.mean_spacing;
    m.d_rule =
        fmt("automatic d = %.2f x mean spacing %.4f m = %.4f m", o.d_factor, m.mean_spacing, m.d);
  }
  m.timings.downsample = seconds_since(t);

  t = Clock::now();
  const DelaunayGraph dg = delaunay_3d(m.cloud);
  m.timings.delaunay = seconds_since(t);
  stop_point(o.stop);
  t = Clock::now();
  m.complex = build_complex(dg, m.d);
  m.timings.complex = seconds_since(t);
  stop_point(o.stop);
  // Progress only once the input is known to be valid, so that errors stay one line on stderr.
  if (m.plane_points_removed > 0)
    say(o, fmt("perception: removed the supporting plane (%.0f points)", m.plane_points_removed));
  say(o, fmt("perception: %.0f points (from %.0f); ", static_cast<double>(m.cloud.size()),
             m.input_points) +
             m.d_rule);
  say(o, fmt("perception: K_d has %.0f edges and %.0f triangles (Delaunay: %.0f tetrahedra)",
             static_cast<double>(m.complex.edges.size()),
             static_cast<double>(m.complex.triangles.size()),
             static_cast<double>(dg.tetrahedra.size())));

  t = Clock::now();
  // Stability: only the loops that the next scale keeps open (sampling gaps and noise fill in).
  HomologyBasis basis;
  if (o.persistence > 0) {
    // Holes a finger passes stay open to about their width; thinner tubes and sampling gaps close.
    // (Never above min_hole, so that a hole too narrow for a large hand is still reported.)
    const double min_hole = o.finger_thickness > 0
                                ? std::min(o.min_hole, o.finger_thickness + kFingerClearance)
                                : o.min_hole;
    m.persistence_d = std::max(o.persistence * m.d, 0.8 * min_hole);
    basis = persistent_homology_basis(m.complex, build_complex(dg, m.persistence_d), o.homology);
    m.unstable_loops = basis.beta1 - static_cast<int>(basis.cycles.size());
  } else {
    basis = shortest_homology_basis(m.complex, o.homology);
  }
  m.beta1 = basis.beta1;
  m.timings.homology = seconds_since(t);
  stop_point(o.stop);
  say(o, fmt("perception: beta1 = %.0f (%.0f Dijkstra roots)", basis.beta1, basis.roots));

  t = Clock::now();
  // Cast on demand: ranking asks about a few places, the planner casts the whole region.
  if (!m.views.empty())
    m.sensed = std::make_shared<const SensedSpace>(
        m.views, object_region(bounds(m.cloud), o.sensed.margin), o.sensed);
  m.sensor_origin_missing = sensor_origin_missing && !m.sensed;
  m.timings.sensed = seconds_since(t);

  t = Clock::now();
  for (const BasisCycle& c : basis.cycles) {
    Loop l;
    l.vertices = c.vertices;
    for (int v : l.vertices) l.points.push_back(m.cloud[v]);
    m.loops.push_back(std::move(l));
  }
  if (m.unstable_loops > 0)
    say(o, fmt("perception: %.0f of the loops are not stable (they fill in by d' = %.4f m)",
               m.unstable_loops, m.persistence_d));
  RankingOptions ro;
  ro.min_hole = o.min_hole;
  ro.support_plane = m.support_plane;
  ro.link_distance = m.d;
  ro.finger_thickness = o.finger_thickness;
  ro.closed_aperture = o.closed_aperture;
  ro.sensed = m.sensed.get();
  ro.sensor_origin_missing = m.sensor_origin_missing;
  rank_loops(m.loops, m.cloud, m.views, ro);
  if (const Loop* best = m.best()) m.targets = clasp_targets(*best, o.targets, o.closed_aperture);
  m.timings.ranking = seconds_since(t);
}

// A model of the prepared inputs (steps 1-2) before its points and loops.
ObjectModel model_of_inputs(const Prepared& r) {
  ObjectModel m;
  m.views = r.views;
  m.input_points = r.input_points;
  m.plane_points_removed = r.plane_points;
  m.support_plane = r.plane;
  m.outliers_removed = r.outliers;
  return m;
}

// Objects closer than this (or 4 spacings of the pool) are one (m); an object holds at least this
// share of the points.
constexpr double kObjectGap = 0.02;
constexpr double kObjectShare = 0.1;

// Step 7: the model with each object of the crop sampled as if it were alone, when the crop holds
// two or more objects and that model has a claspable loop.
std::optional<ObjectModel> objects_alone(const Prepared& r, const PerceptionOptions& o,
                                         bool sensor_origin_missing) {
  if (r.pool.size() <= static_cast<std::size_t>(o.points)) return std::nullopt;
  // Sparse points (few of them over a large scene) must not break one object into pieces.
  const double gap = std::max(kObjectGap, 4.0 * mean_spacing(r.pool));
  const std::vector<int> labels = object_labels(r.pool, gap, kObjectShare);
  const int objects = *std::max_element(labels.begin(), labels.end()) + 1;
  if (objects < 2) return std::nullopt;
  ObjectModel m = model_of_inputs(r);
  m.objects = objects;
  m.cloud =
      spatial_order(farthest_point_sample(r.pool, o.points, o.seed + 2, labels, 2 * o.points));
  say(o, fmt("perception: no claspable loop; again with each of the %.0f objects sampled alone "
             "(%.0f points)",
             static_cast<double>(objects), static_cast<double>(m.cloud.size())));
  try {
    loops_of_cloud(m, o, sensor_origin_missing);
  } catch (const InputError& e) {  // more points, more loops: the first pass's result stands
    say(o, std::string("perception: the second pass stopped: ") + e.what());
    return std::nullopt;
  }
  if (!m.best()) {
    say(o, "perception: no claspable loop either: the first pass's loops are kept");
    return std::nullopt;
  }
  m.d_rule += fmt(" (each of %.0f objects sampled alone)", static_cast<double>(objects));
  return m;
}

}  // namespace

ObjectModel build_object_model(const PerceptionInputs& in, const PerceptionOptions& o) {
  using Clock = std::chrono::steady_clock;
  const auto t_start = Clock::now();
  Prepared r = prepare(in, o);
  ObjectModel m = model_of_inputs(r);
  m.timings.preprocess = seconds_since(t_start);
  stop_point(o.stop);
  m.cloud = std::move(r.cloud);
  loops_of_cloud(m, o, !in.clouds.empty());
  if (o.per_object_pass && !m.best()) {
    if (std::optional<ObjectModel> alone = objects_alone(r, o, !in.clouds.empty())) {
      alone->timings.preprocess = m.timings.preprocess;
      m = std::move(*alone);
    }
  }
  m.timings.total = seconds_since(t_start);
  return m;
}

}  // namespace claspplan::perception
