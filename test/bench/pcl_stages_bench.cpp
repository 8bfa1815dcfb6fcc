// Our cloud stages against PCL's own operations on the same points (issue "A library people can
// build on": use PCL where it has the operation unless a measurement shows it worse). The input is
// the purse seen by two cameras (about 42,000 object points after back-projection); PCL's timings
// include the conversion to and from pcl::PointCloud<pcl::PointXYZ> that using it costs.
#include <benchmark/benchmark.h>
#include <pcl/filters/crop_box.h>
#include <pcl/filters/farthest_point_sampling.h>
#include <pcl/filters/statistical_outlier_removal.h>
#include <pcl/filters/voxel_grid.h>
#include <pcl/point_cloud.h>
#include <pcl/point_types.h>

#include "examples/objects.hpp"
#include "perception/cloud_filters.hpp"
#include "perception/depth_render.hpp"

namespace claspplan::perception {
namespace {

const PointCloud& purse_points() {
  static const PointCloud points = [] {
    TriangleMesh scene = objects::purse();
    append_mesh(scene, objects::ground_plane(1.0));
    PointCloud all;
    for (const auto& camera : objects::purse_cameras(2)) {
      DepthView v{camera, render_depth(scene, camera)};
      for (const auto& p : depth_to_points(v))
        if (p.z() > 0.005) all.push_back(p);
    }
    return all;
  }();
  return points;
}

pcl::PointCloud<pcl::PointXYZ>::Ptr to_pcl(const PointCloud& cloud) {
  auto out = std::make_shared<pcl::PointCloud<pcl::PointXYZ>>();
  out->reserve(cloud.size());
  for (const auto& p : cloud) out->emplace_back(p.x(), p.y(), p.z());
  return out;
}

PointCloud from_pcl(const pcl::PointCloud<pcl::PointXYZ>& cloud) {
  PointCloud out;
  out.reserve(cloud.size());
  for (const auto& p : cloud) out.emplace_back(p.x, p.y, p.z);
  return out;
}

const Eigen::AlignedBox3d kBox(Eigen::Vector3d(-0.1, -0.05, 0.02), Eigen::Vector3d(0.1, 0.05, 0.3));

void BM_CropOurs(benchmark::State& state) {
  const PointCloud& in = purse_points();
  for (auto _ : state) benchmark::DoNotOptimize(crop_to_box(in, kBox));
  state.counters["points"] = static_cast<double>(in.size());
}
BENCHMARK(BM_CropOurs)->Unit(benchmark::kMillisecond);

void BM_CropPclCropBox(benchmark::State& state) {
  const PointCloud& in = purse_points();
  for (auto _ : state) {
    pcl::CropBox<pcl::PointXYZ> crop;
    crop.setInputCloud(to_pcl(in));
    crop.setMin(Eigen::Vector4f(-0.1f, -0.05f, 0.02f, 1.0f));
    crop.setMax(Eigen::Vector4f(0.1f, 0.05f, 0.3f, 1.0f));
    pcl::PointCloud<pcl::PointXYZ> out;
    crop.filter(out);
    benchmark::DoNotOptimize(from_pcl(out));
  }
}
BENCHMARK(BM_CropPclCropBox)->Unit(benchmark::kMillisecond);

// Down-sampling to N = 2000 from the pipeline's 4 N seeded subset.
void BM_DownsampleOursFarthestPoint(benchmark::State& state) {
  const PointCloud in = random_subset(purse_points(), 8000, 1);
  for (auto _ : state) benchmark::DoNotOptimize(farthest_point_sample(in, 2000, 3));
}
BENCHMARK(BM_DownsampleOursFarthestPoint)->Unit(benchmark::kMillisecond);

void BM_DownsamplePclFarthestPoint(benchmark::State& state) {
  const PointCloud in = random_subset(purse_points(), 8000, 1);
  for (auto _ : state) {
    pcl::FarthestPointSampling<pcl::PointXYZ> fps;
    fps.setInputCloud(to_pcl(in));
    fps.setSample(2000);
    fps.setSeed(3);
    pcl::PointCloud<pcl::PointXYZ> out;
    fps.filter(out);
    benchmark::DoNotOptimize(from_pcl(out));
  }
}
BENCHMARK(BM_DownsamplePclFarthestPoint)->Unit(benchmark::kMillisecond);

void BM_DownsamplePclVoxelGrid(benchmark::State& state) {
  const PointCloud in = random_subset(purse_points(), 8000, 1);
  for (auto _ : state) {
    pcl::VoxelGrid<pcl::PointXYZ> grid;
    grid.setInputCloud(to_pcl(in));
    grid.setLeafSize(0.011f, 0.011f, 0.011f);  // about 2000 points on this object
    pcl::PointCloud<pcl::PointXYZ> out;
    grid.filter(out);
    state.counters["points"] = static_cast<double>(out.size());
    benchmark::DoNotOptimize(from_pcl(out));
  }
}
BENCHMARK(BM_DownsamplePclVoxelGrid)->Unit(benchmark::kMillisecond);

// The statistical outlier filter as the pipeline runs it at N = 2,000 (6,000 thinned points, 10
// neighbours, 2 sigma) and on all 40,000 points of the two views, ours against PCL's.
void BM_OutliersOurs(benchmark::State& state) {
  const PointCloud in = random_subset(purse_points(), static_cast<int>(state.range(0)), 1);
  for (auto _ : state) {
    const PointCloud out = remove_statistical_outliers(in, 10, 2.0);
    state.counters["kept"] = static_cast<double>(out.size());
  }
}
BENCHMARK(BM_OutliersOurs)->Arg(6000)->Arg(40000)->Unit(benchmark::kMillisecond);

void BM_OutliersPcl(benchmark::State& state) {
  const PointCloud in = random_subset(purse_points(), static_cast<int>(state.range(0)), 1);
  for (auto _ : state) {
    pcl::StatisticalOutlierRemoval<pcl::PointXYZ> sor;
    sor.setInputCloud(to_pcl(in));
    sor.setMeanK(10);
    sor.setStddevMulThresh(2.0);
    pcl::PointCloud<pcl::PointXYZ> out;
    sor.filter(out);
    state.counters["kept"] = static_cast<double>(out.size());
    benchmark::DoNotOptimize(from_pcl(out));
  }
}
BENCHMARK(BM_OutliersPcl)->Arg(6000)->Arg(40000)->Unit(benchmark::kMillisecond);

}  // namespace
}  // namespace claspplan::perception
