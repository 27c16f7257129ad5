// The OpenCL traversal kernel returns exactly the CPU traversal's hits (same shared code).
#include "render_fixture.h"

#include <icosphere.h>

#include <kdray/import.h>
#include <kdray/ray_sets.h>
#include <kdray/trace_opencl.h>
#include <kdray/traverse.h>

#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <cstring>
#include <tuple>

namespace kdray {
namespace {

// Counts records that differ in any bit, and prints the first few.
size_t count_differences(const std::vector<HitRecord>& a, const std::vector<HitRecord>& b) {
  size_t differences = 0;
  for (size_t i = 0; i < a.size(); ++i) {
    if (std::memcmp(&a[i], &b[i], sizeof(HitRecord)) == 0) continue;
    if (++differences <= 5) {
      std::printf("ray %zu: cpu t=%a tri=%u u=%a v=%a, device t=%a tri=%u u=%a v=%a\n", i, a[i].t, a[i].triangle,
                  a[i].u, a[i].v, b[i].t, b[i].triangle, b[i].u, b[i].v);
    }
  }
  return differences;
}

// Traces `rays` on the CPU and on the default OpenCL device and expects the same records bit
// for bit, with more than a quarter of the rays hitting (so that misses are not all compared).
void expect_device_gives_cpu_hits(const KdTree& tree, const std::vector<RayRecord>& rays) {
  std::vector<HitRecord> cpu;
  trace_closest(tree, rays, cpu);
  std::vector<HitRecord> device = trace_rays_opencl(tree, rays, DeviceSelection{});
  ASSERT_EQ(device.size(), rays.size());
  size_t hits = 0;
  for (const HitRecord& hit : cpu) hits += hit.triangle != KD_NO_HIT;
  EXPECT_GT(hits, rays.size() / 4);
  EXPECT_EQ(count_differences(cpu, device), 0u);
}

class TraceKernel : public ::testing::Test {
 protected:
  static void SetUpTestSuite() {
    std::string path = std::string(KDRAY_CORPUS_DIR) + "/misc/fandisk.obj";
    if (!std::filesystem::exists(path)) return;
    scene_ = new Scene(import_scene(path, ImportOptions{}));
    tree_ = new KdTree(test::tree_for(*scene_));
  }
  static void TearDownTestSuite() {
    delete tree_;
    delete scene_;
    tree_ = nullptr;
    scene_ = nullptr;
  }
  void SetUp() override {
    std::string path;
    KDRAY_CORPUS_FILE(path, "misc/fandisk.obj");
  }
  static Scene* scene_;
  static KdTree* tree_;
};
Scene* TraceKernel::scene_ = nullptr;
KdTree* TraceKernel::tree_ = nullptr;

TEST_F(TraceKernel, HitsEqualTheCpuTraversalOnTheFandisk) {
  std::vector<RayRecord> rays = camera_rays(*scene_, 256, 256);                  // 65,536
  std::vector<RayRecord> random = random_rays(tree_->bounds, 40000, 11);
  std::vector<RayRecord> hard = hard_case_rays(*scene_, *tree_, 40000, 12);
  rays.insert(rays.end(), random.begin(), random.end());
  rays.insert(rays.end(), hard.begin(), hard.end());
  ASSERT_GE(rays.size(), 100000u);
  expect_device_gives_cpu_hits(*tree_, rays);
}

// Directions whose largest components tie in magnitude, with either sign or none: the C++ builds
// choose the watertight test's axes by arithmetic, OpenCL by selects (kd_ray_axes), and both must
// pick the same axes, or the hits' last bits differ.
TEST_F(TraceKernel, DirectionsWithTiedComponentsGiveTheCpuHits) {
  // Origins on a 4 x 4 x 4 grid inside the box, so that most rays meet the part.
  const Bounds& box = tree_->bounds;
  std::vector<Vec3> origins;
  for (int i = 0; i < 64; ++i) {
    const float f[3] = {(1 + 2 * (i & 3)) / 8.0f, (1 + 2 * ((i >> 2) & 3)) / 8.0f, (1 + 2 * (i >> 4)) / 8.0f};
    origins.push_back(Vec3{box.min.x + f[0] * (box.max.x - box.min.x), box.min.y + f[1] * (box.max.y - box.min.y),
                           box.min.z + f[2] * (box.max.z - box.min.z)});
  }
  const float values[] = {-1.0f, -0.5f, -0.0f, 0.0f, 0.5f, 1.0f};
  std::vector<RayRecord> rays;
  for (const Vec3& origin : origins)
    for (float dx : values)
      for (float dy : values)
        for (float dz : values)
          if (dx != 0.0f || dy != 0.0f || dz != 0.0f)
            rays.push_back(RayRecord{origin.x, origin.y, origin.z, dx, dy, dz, 0.0f, INFINITY});
  expect_device_gives_cpu_hits(*tree_, rays);
}

TEST_F(TraceKernel, ShortStackOfOneGivesTheSameHits) {
  std::vector<RayRecord> rays = random_rays(tree_->bounds, 20000, 21);
  std::vector<RayRecord> hard = hard_case_rays(*scene_, *tree_, 10000, 22);
  rays.insert(rays.end(), hard.begin(), hard.end());
  std::vector<HitRecord> cpu;
  trace_closest(*tree_, rays, cpu, TraceOptions{0, TraversalStack::Depth1});
  DeviceSelection depth_one;
  depth_one.short_stack_size = 1;
  EXPECT_EQ(count_differences(cpu, trace_rays_opencl(*tree_, rays, depth_one)), 0u);
}

// A tree's leaves grouped (the fandisk's by default) or paged: the device reads either, in lanes
// and one ray per work-item, with the CPU's hits, and both layouts give the same hits.
TEST_F(TraceKernel, BothLeafLayoutsGiveTheCpuHits) {
  BuildSettings paged_settings;
  paged_settings.leaf_layout = LeafLayout::paged;
  const KdTree paged = build_kdtree(*scene_, paged_settings);
  ASSERT_EQ(tree_->settings.leaf_layout, LeafLayout::grouped);
  std::vector<RayRecord> rays = random_rays(tree_->bounds, 30000, 41);
  std::vector<RayRecord> hard = hard_case_rays(*scene_, *tree_, 30000, 42);
  rays.insert(rays.end(), hard.begin(), hard.end());
  std::vector<HitRecord> grouped_cpu, paged_cpu;
  trace_closest(*tree_, rays, grouped_cpu);
  trace_closest(paged, rays, paged_cpu);
  EXPECT_EQ(count_differences(grouped_cpu, paged_cpu), 0u) << "grouped against paged, on the CPU";
  DeviceSelection one_ray;
  one_ray.lanes = false;
  for (const DeviceSelection& selection : {DeviceSelection{}, one_ray}) {
    EXPECT_EQ(count_differences(paged_cpu, trace_rays_opencl(paged, rays, selection)), 0u) << "paged";
    EXPECT_EQ(count_differences(paged_cpu, trace_rays_opencl(*tree_, rays, selection)), 0u) << "grouped";
  }
}

// A device compiles its own traversal unless one is named: the robust code alone on a GPU, where
// it traced faster, the fast path on a CPU; the program's options and its reported path agree.
// On a CPU device a tree of more than kLanesMinNodes nodes is traced 24 rays per work-item in
// float8 lanes (kernels/kd_traverse_lanes.h): the same hits as one ray per work-item and as the
// CPU, on camera, random and hard-case rays and on a tree whose short stack some rays overflow.
TEST_F(TraceKernel, LanesGiveTheSameHitsAsOneRayPerWorkItem) {
  DeviceSelection one_ray;
  one_ray.lanes = false;
  const Scene sphere = test::icosphere_scene(5, {0, 0, 0}, 1.0f);
  const KdTree sphere_tree = build_kdtree(sphere, BuildSettings{});
  using Case = std::tuple<const char*, const Scene*, const KdTree*>;
  for (const auto& [name, scene, tree] : {Case{"fandisk", scene_, tree_}, Case{"icosphere", &sphere, &sphere_tree}}) {
    ASSERT_TRUE(opencl_traces_in_lanes(*tree, DeviceSelection{}, false)) << name;
    ASSERT_FALSE(opencl_traces_in_lanes(*tree, DeviceSelection{}, true)) << name << ": a GPU: one ray per work-item";
    ASSERT_FALSE(opencl_traces_in_lanes(*tree, one_ray, false)) << name;
    std::vector<RayRecord> rays = camera_rays(*scene, 128, 128);
    for (const std::vector<RayRecord>& more :
         {random_rays(tree->bounds, 30000, 31), hard_case_rays(*scene, *tree, 30000, 32)})
      rays.insert(rays.end(), more.begin(), more.end());
    std::vector<HitRecord> cpu;
    TraceOptions cpu_one_ray;
    cpu_one_ray.lanes = false;
    trace_closest(*tree, rays, cpu, cpu_one_ray);
    TraceOpenClStats lanes_stats, one_ray_stats;
    const std::vector<HitRecord> lanes = trace_rays_opencl(*tree, rays, DeviceSelection{}, &lanes_stats);
    const std::vector<HitRecord> single = trace_rays_opencl(*tree, rays, one_ray, &one_ray_stats);
    EXPECT_EQ(lanes_stats.kernel_variant, "24-rays-per-work-item-in-float8-lanes+prefetch") << name;
    EXPECT_EQ(one_ray_stats.kernel_variant, "one-ray-per-work-item+prefetch") << name;
    size_t hits = 0;
    for (const HitRecord& hit : cpu) hits += hit.triangle != KD_NO_HIT;
    EXPECT_GT(hits, rays.size() / 4) << name;
    EXPECT_EQ(count_differences(cpu, lanes), 0u) << name << ", lanes";
    EXPECT_EQ(count_differences(cpu, single), 0u) << name << ", one ray per work-item";
  }
  std::vector<HitRecord> counted;
  const TraversalWork work = count_traversal_work(sphere_tree, random_rays(sphere_tree.bounds, 30000, 31), counted);
  EXPECT_GT(work.fast_path_restarts, 0u) << "some rays must overflow the short stack";
}

TEST(TraceKernelBuilds, EachDeviceKindGetsItsOwnTraversalUnlessOneIsNamed) {
  const std::string robust_only = "-DKD_TRAVERSAL_ROBUST_ONLY";
  const TraceKernelBuild gpu = trace_kernel_build(DeviceSelection{}, true);
  const TraceKernelBuild cpu = trace_kernel_build(DeviceSelection{}, false);
  EXPECT_EQ(gpu.traversal, TraversalPath::Robust);
  EXPECT_NE(gpu.options.find(robust_only), std::string::npos) << gpu.options;
  EXPECT_EQ(cpu.traversal, TraversalPath::FastWhereSafe);
  EXPECT_EQ(cpu.options.find(robust_only), std::string::npos) << cpu.options;
  DeviceSelection named;
  named.traversal = TraversalPath::FastWhereSafe;
  EXPECT_EQ(trace_kernel_build(named, true).options.find(robust_only), std::string::npos);
  named.traversal = TraversalPath::Robust;
  EXPECT_NE(trace_kernel_build(named, false).options.find(robust_only), std::string::npos);
  // A CPU tests a leaf's triangles four at a time in lanes, a GPU one at a time (its lanes are
  // work-items); the render kernels take the same traversal options (traversal_build_options).
  const std::string leaf_lanes = "-DKD_LEAF_TESTS_IN_LANES";
  EXPECT_NE(cpu.options.find(leaf_lanes), std::string::npos) << cpu.options;
  EXPECT_EQ(gpu.options.find(leaf_lanes), std::string::npos) << gpu.options;
  EXPECT_STREQ(traversal_path_name(TraversalPath::Robust), "robust");
  EXPECT_STREQ(traversal_path_name(TraversalPath::FastWhereSafe), "fast");
}

TEST_F(TraceKernel, RobustTraversalOnPoclGivesTheSameHits) {
  std::vector<RayRecord> rays = random_rays(tree_->bounds, 20000, 31);
  std::vector<RayRecord> hard = hard_case_rays(*scene_, *tree_, 20000, 32);
  rays.insert(rays.end(), hard.begin(), hard.end());
  DeviceSelection fast{"cpu"}, robust{"cpu"};
  robust.traversal = TraversalPath::Robust;
  TraceOpenClStats fast_stats, robust_stats;
  const std::vector<HitRecord> fast_hits = trace_rays_opencl(*tree_, rays, fast, &fast_stats);
  EXPECT_EQ(count_differences(fast_hits, trace_rays_opencl(*tree_, rays, robust, &robust_stats)), 0u);
  EXPECT_EQ(fast_stats.traversal, TraversalPath::FastWhereSafe);
  EXPECT_EQ(robust_stats.traversal, TraversalPath::Robust);
}

TEST(TraceKernelEdges, NoRaysGiveNoHits) {
  Scene scene;
  scene.positions = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}};
  scene.indices = {0, 1, 2};
  scene.material_ids = {0};
  scene.materials.resize(1);
  KdTree tree = test::tree_for(scene);
  EXPECT_TRUE(trace_rays_opencl(tree, {}, DeviceSelection{}).empty());
  RayRecord ray{0.25f, 0.25f, 1, 0, 0, -1, 0, 1e30f};
  std::vector<HitRecord> hits = trace_rays_opencl(tree, {ray}, DeviceSelection{});
  ASSERT_EQ(hits.size(), 1u);
  EXPECT_EQ(hits[0].triangle, 0u);
  EXPECT_FLOAT_EQ(hits[0].t, 1.0f);
}

}  // namespace
}  // namespace kdray
