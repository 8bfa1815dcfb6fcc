// Perception (issue 3 budgets): depth files -> loops -> clasp targets at 2000 points within 100 ms
// on one core, the scaling at 10,000 and 40,000 points (aim: 1 s at 10,000), and the kernels
// (Delaunay, K_d, shortest basis) separately.
#include <algorithm>
#include <filesystem>
#include <map>
#include <memory>

#include <benchmark/benchmark.h>

#include "examples/objects.hpp"
#include "perception/cloud_filters.hpp"
#include "perception/complex.hpp"
#include "perception/depth_render.hpp"
#include "perception/depth_surface.hpp"
#include "perception/homology.hpp"
#include "perception/next_view.hpp"
#include "perception/pipeline.hpp"

namespace claspplan::perception {
namespace {

// The purse on a table from two cameras with 1 mm depth noise, written once: at the Kinect
// resolution (scale 1: 640x480, about 42,000 object points) and at twice it (scale 2: 1280x960,
// about 170,000), so that N = 40,000 is still a real down-sampling.
struct DepthFiles {
  std::filesystem::path dir;
  std::vector<std::string> pngs, cameras;
  explicit DepthFiles(int scale) {
    dir = std::filesystem::temp_directory_path() /
          ("claspplan-perception-bench-" + std::to_string(scale));
    std::vector<CameraModel> cams = objects::purse_cameras(2);
    for (auto& c : cams) {
      c.width *= scale, c.height *= scale, c.fx *= scale, c.fy *= scale;
      c.cx = (c.width - 1) / 2.0, c.cy = (c.height - 1) / 2.0;
    }
    TriangleMesh scene = objects::purse();
    append_mesh(scene, objects::ground_plane(1.2));
    DepthNoise noise;
    noise.sigma = 0.001;
    for (const auto& [png, yaml] :
         objects::write_depth_files(scene, cams, dir.string(), "purse", noise)) {
      pngs.push_back(png);
      cameras.push_back(yaml);
    }
  }
  ~DepthFiles() {
    std::error_code ec;
    std::filesystem::remove_all(dir, ec);
  }
};

const DepthFiles& depth_files(int scale = 2) {
  static std::map<int, std::unique_ptr<DepthFiles>> files;
  auto& f = files[scale];
  if (!f) f = std::make_unique<DepthFiles>(scale);
  return *f;
}

// Reading the two depth images and their cameras alone (PNG inflation most of it).
void BM_LoadDepthFiles(benchmark::State& state) {
  const DepthFiles& f = depth_files(static_cast<int>(state.range(0)));
  for (auto _ : state) benchmark::DoNotOptimize(load_inputs(f.pngs, f.cameras).depth_views.data());
}
BENCHMARK(BM_LoadDepthFiles)->Arg(1)->Arg(2)->Unit(benchmark::kMillisecond);

// The whole pipeline from the files: PNG and YAML reading, back-projection, plane and outlier
// removal, down-sampling, Delaunay, K_d, the exact shortest basis, ranking and 12 targets.
// Arguments: N, resolution scale.
void BM_DepthFileToTargets(benchmark::State& state) {
  const DepthFiles& f = depth_files(static_cast<int>(state.range(1)));
  PerceptionOptions o;
  o.points = static_cast<int>(state.range(0));
  int beta1 = 0;
  PerceptionTimings last;
  for (auto _ : state) {
    const ObjectModel m = build_object_model(load_inputs(f.pngs, f.cameras), o);
    beta1 = m.beta1;
    last = m.timings;
    if (!m.best()) state.SkipWithError("no claspable loop");
    benchmark::DoNotOptimize(m.targets.data());
  }
  state.counters["beta1"] = beta1;
  // The last run's stages, milliseconds.
  state.counters["prep_ms"] = 1e3 * last.preprocess;
  state.counters["delaunay_ms"] = 1e3 * last.delaunay;
  state.counters["homology_ms"] = 1e3 * last.homology;
}
BENCHMARK(BM_DepthFileToTargets)
    ->Args({2000, 1})
    ->Args({2000, 2})
    ->Args({10000, 2})
    ->Args({40000, 2})
    ->Unit(benchmark::kMillisecond);

// The object points the kernels below work on (the pipeline's own output for the files above).
const PointCloud& object_cloud(int n) {
  static std::map<int, PointCloud> clouds;
  auto it = clouds.find(n);
  if (it == clouds.end()) {
    PerceptionOptions o;
    o.points = n;
    const DepthFiles& f = depth_files();
    it = clouds.emplace(n, object_points(load_inputs(f.pngs, f.cameras), o)).first;
  }
  return it->second;
}

void BM_Delaunay(benchmark::State& state) {
  const PointCloud& pts = object_cloud(static_cast<int>(state.range(0)));
  for (auto _ : state) benchmark::DoNotOptimize(delaunay_3d(pts).edges.data());
}
BENCHMARK(BM_Delaunay)->Arg(2000)->Arg(10000)->Arg(40000)->Unit(benchmark::kMillisecond);

void BM_BuildComplex(benchmark::State& state) {
  const PointCloud& pts = object_cloud(static_cast<int>(state.range(0)));
  const DelaunayGraph g = delaunay_3d(pts);
  const double d = automatic_d(pts);
  for (auto _ : state) benchmark::DoNotOptimize(build_complex(g, d).edges.data());
}
BENCHMARK(BM_BuildComplex)->Arg(2000)->Arg(10000)->Arg(40000)->Unit(benchmark::kMillisecond);

void BM_ShortestBasis(benchmark::State& state) {
  const PointCloud& pts = object_cloud(static_cast<int>(state.range(0)));
  const SimplicialComplex k = build_complex(delaunay_3d(pts), automatic_d(pts));
  HomologyOptions o;
  o.fast = state.range(1) != 0;
  HomologyBasis b;
  for (auto _ : state) b = shortest_homology_basis(k, o);
  state.counters["beta1"] = b.beta1;
  state.counters["roots"] = b.roots;
  state.counters["triangles"] = static_cast<double>(k.triangles.size());
}
BENCHMARK(BM_ShortestBasis)
    ->Args({2000, 1})
    ->Args({10000, 1})
    ->Args({40000, 1})
    ->Unit(benchmark::kMillisecond);
// The straightforward version (every vertex a root), for comparison.
BENCHMARK(BM_ShortestBasis)->Args({2000, 0})->Iterations(2)->Unit(benchmark::kMillisecond);

// What the pipeline computes: the loops that persist from K_d to K_d' (d' = 0.024 m, as for the
// default 3 cm narrowest hole), on all cores / one thread.
void BM_PersistentBasis(benchmark::State& state) {
  const PointCloud& pts = object_cloud(static_cast<int>(state.range(0)));
  const DelaunayGraph g = delaunay_3d(pts);
  const double d = automatic_d(pts);
  const SimplicialComplex k = build_complex(g, d),
                          larger = build_complex(g, std::max(1.25 * d, 0.024));
  HomologyOptions o;
  o.threads = static_cast<int>(state.range(1));
  HomologyBasis b;
  for (auto _ : state) b = persistent_homology_basis(k, larger, o);
  state.counters["beta1"] = b.beta1;
  state.counters["loops"] = static_cast<double>(b.cycles.size());
  state.counters["roots"] = b.roots;
}
BENCHMARK(BM_PersistentBasis)
    ->Args({2000, 0})
    ->Args({10000, 0})
    ->Args({40000, 0})
    ->Args({40000, 1})
    ->Unit(benchmark::kMillisecond);

// The same basis on the whole surface of a thick torus (beta1 = 2, long loops): the harder case
// for the bounded searches.
void BM_ShortestBasisTorus(benchmark::State& state) {
  PerceptionInputs in;
  in.meshes.push_back(objects::torus_mesh(0.1, 0.03));
  PerceptionOptions o;
  o.points = static_cast<int>(state.range(0));
  const PointCloud pts = object_points(in, o);
  const SimplicialComplex k = build_complex(delaunay_3d(pts), automatic_d(pts));
  HomologyBasis b;
  for (auto _ : state) b = shortest_homology_basis(k);
  state.counters["beta1"] = b.beta1;
  state.counters["roots"] = b.roots;
}
BENCHMARK(BM_ShortestBasisTorus)->Arg(2000)->Arg(10000)->Unit(benchmark::kMillisecond);

void BM_FarthestPointSampling(benchmark::State& state) {
  PerceptionInputs in;
  in.meshes.push_back(objects::purse());
  const PointCloud dense = sample_surface(in.meshes[0], 4 * static_cast<int>(state.range(0)), 1);
  for (auto _ : state)
    benchmark::DoNotOptimize(
        farthest_point_indices(dense, static_cast<int>(state.range(0)), 1).data());
}
BENCHMARK(BM_FarthestPointSampling)->Arg(2000)->Arg(10000)->Unit(benchmark::kMillisecond);

// The scene rendered by each camera with 1 mm depth noise (seeds 1, 2, ...).
std::vector<DepthView> noisy_views(const TriangleMesh& scene,
                                   const std::vector<CameraModel>& cams) {
  std::vector<DepthView> views;
  for (size_t i = 0; i < cams.size(); ++i) {
    DepthNoise noise;
    noise.sigma = 0.001;
    noise.seed = 1 + i;
    views.push_back({cams[i], render_depth(scene, cams[i], noise)});
  }
  return views;
}

// The seen-surface collision mesh (depth_surface.hpp) of two 640x480 views with 1 mm noise, stride
// 2, the floor removed by its plane (5 mm margin). Argument: 0 = the upright ring of the tests
// (R = 10 cm, r = 1.2 cm, at x = 0.55 m), 1 = the purse on its table (the example depth files).
void BM_DepthSurfaceMesh(benchmark::State& state) {
  TriangleMesh scene;
  std::vector<CameraModel> cams;
  if (state.range(0) == 0) {
    const Eigen::Vector3d centre(0.55, 0.0, 0.112);
    Eigen::Isometry3d pose = Eigen::Isometry3d::Identity();
    pose.translation() = centre;
    pose.linear() =
        Eigen::AngleAxisd(1.5707963267948966, Eigen::Vector3d::UnitX()).toRotationMatrix();
    scene = objects::torus_mesh(0.10, 0.012, pose);
    append_mesh(scene, objects::ground_plane(1.2, 0.0, {0.55, 0.0}));
    cams = {objects::kinect_camera({0.25, -0.55, 0.50}, centre),
            objects::kinect_camera({0.85, 0.60, 0.45}, centre)};
  } else {
    scene = objects::purse();
    append_mesh(scene, objects::ground_plane(1.2));
    cams = objects::purse_cameras(2);
  }
  const std::vector<DepthView> views = noisy_views(scene, cams);
  DepthSurfaceOptions o;
  o.support_plane = Eigen::Vector4d(0, 0, 1, 0);
  TriangleMesh m;
  for (auto _ : state) {
    m = depth_surface_mesh(views, o);
    benchmark::DoNotOptimize(m.triangles.data());
  }
  state.counters["triangles"] = static_cast<double>(m.triangles.size());
  state.counters["vertices"] = static_cast<double>(m.vertices.size());
}
BENCHMARK(BM_DepthSurfaceMesh)->Arg(0)->Arg(1)->Unit(benchmark::kMillisecond);

// The sensed space (sensed_space.hpp) of two 640x480 views of the purse on its table, 1 mm noise:
// the object's region (its bounds grown by 8 cm) at 5 mm voxels, and (argument 1) the list of
// voxels the robot must not enter taken from it; (argument 2) with the planner's finer voxels
// near the loop (SensedSpace::refined) cast too, over a handle's box at the purse's top: a
// 14 x 6 cm loop grown by 3 cm.
void BM_SensedSpace(benchmark::State& state) {
  TriangleMesh scene = objects::purse();
  append_mesh(scene, objects::ground_plane(1.2));
  const std::vector<DepthView> views = noisy_views(scene, objects::purse_cameras(2));
  Eigen::AlignedBox3d purse_box = bounds(objects::purse());
  const Eigen::AlignedBox3d region = object_region(purse_box, SensedSpaceOptions().margin);
  std::size_t blocked = 0;
  long voxels = 0;
  for (auto _ : state) {
    const SensedSpace space(views, region);
    voxels = space.dims().prod();
    if (state.range(0) == 0) benchmark::DoNotOptimize(space.counts());  // the whole grid cast
    if (state.range(0) == 1) blocked = space.blocked_voxels(Eigen::Vector4d(0, 0, 1, 0)).size();
    if (state.range(0) == 2) {
      const SensedSpaceOptions o;
      const Eigen::Vector3d top(purse_box.center().x(), purse_box.center().y(),
                                purse_box.max().z());
      const Eigen::AlignedBox3d loop(top - Eigen::Vector3d(0.07, 0.0, 0.06),
                                     top + Eigen::Vector3d(0.07, 0.0, 0.0));
      const SensedSpace fine =
          space.refined(object_region(loop, o.loop_margin), o.loop_resolution, o.loop_max_voxels);
      benchmark::DoNotOptimize(space.counts());
      benchmark::DoNotOptimize(fine.counts());
      state.counters["finer_voxels"] = static_cast<double>(fine.dims().prod());
      state.counters["finer_mm"] = 1e3 * fine.resolution();
    }
    benchmark::DoNotOptimize(voxels);
  }
  state.counters["voxels"] = static_cast<double>(voxels);
  state.counters["blocked"] = static_cast<double>(blocked);
}
BENCHMARK(BM_SensedSpace)->Arg(0)->Arg(1)->Arg(2)->Unit(benchmark::kMillisecond);

// The next best view (next_view.hpp) for a search that ran into the purse's unseen space: 4,000
// contact points spread over the unknown voxels above its table (two views, as above).
void BM_NextView(benchmark::State& state) {
  TriangleMesh scene = objects::purse();
  append_mesh(scene, objects::ground_plane(1.2));
  const std::vector<DepthView> views = noisy_views(scene, objects::purse_cameras(2));
  const SensedSpace space(views, object_region(bounds(objects::purse()), 0.08));
  std::vector<Eigen::Vector3d> unknown;
  for (const auto& c : space.blocked_voxels())
    if (c.z() > 0.01) unknown.push_back(c);
  std::vector<Eigen::Vector3d> contacts;
  for (std::size_t i = 0; i < 4000; ++i) contacts.push_back(unknown[i * unknown.size() / 4000]);
  std::optional<ViewSuggestion> view;
  for (auto _ : state) {
    view = view_into_unknown(space, contacts, Eigen::Vector4d(0, 0, 1, 0));
    benchmark::DoNotOptimize(view);
  }
  state.counters["visible_share"] = view ? view->visible / view->unknown : 0.0;
}
BENCHMARK(BM_NextView)->Unit(benchmark::kMillisecond);

}  // namespace
}  // namespace claspplan::perception
