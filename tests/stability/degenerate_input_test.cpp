// Bad triangles in the input: zero-area, collinear, duplicate-vertex, NaN and Inf ones are
// dropped and counted by kdconvert; needle and tiny triangles are kept; what remains builds,
// traces (agreeing with brute force) and renders without NaN.
#include "brute_force.h"
#include "generated_scenes.h"
#include "tool_pipeline.h"

#include <kdray/image_compare.h>
#include <kdray/kdtree.h>
#include <kdray/ray_sets.h>
#include <kdray/scene_file.h>
#include <kdray/traverse.h>

#include <gtest/gtest.h>

#include <cmath>

namespace {

// Vertex numbers are 1-based, as in OBJ. The good part is a floor and a light facing it.
constexpr const char* kBadTrianglesObj = R"(usemtl white
v -100 0 -100
v -100 0 100
v 100 0 100
v 100 0 -100
f 1 2 3
f 1 3 4
usemtl light
v -20 100 -20
v 20 100 -20
v 20 100 20
v -20 100 20
f 5 6 7
f 5 7 8
usemtl white
# zero area: a repeated index
f 1 1 2
# collinear: three distinct points on a line
v 0 5 0
v 1 5 1
v 2 5 2
f 9 10 11
# duplicate vertex: two entries with the same coordinates
v 10 20 10
v 10 20 10
v 30 20 10
f 12 13 14
# NaN and Inf coordinates
v nan 10 0
v 1 10 0
v 0 10 1
f 15 16 17
v 0 10 inf
v 1 11 0
v 0 11 1
f 18 19 20
# a needle: 100 long, 1e-3 wide
v -50 30 0
v 50 30 0
v -50 30.001 0.001
f 21 22 23
# a tiny triangle: 1e-5 across
v 5 1 5
v 5.00001 1 5
v 5 1.00001 5.00001
f 24 25 26
)";

constexpr uint32_t kGoodTriangles = 6;  // floor 2, light 2, needle, tiny

// Writes the OBJ and its MTL, converts it (keeping kdconvert's report) and builds its tree.
class DegenerateInput : public ::testing::Test {
 protected:
  void SetUp() override {
    const std::string obj = tools_.path("bad.obj");
    kdray::test::write_obj(obj, kBadTrianglesObj, kdray::test::white_and_light_mtl(10.0f));
    converted_ = tools_.convert_and_build(obj, "bad");
  }

  kdray::test::ToolPipeline tools_;
  nlohmann::json converted_;
};

}  // namespace

TEST_F(DegenerateInput, ConversionDropsAndCountsTheBadTriangles) {
  EXPECT_EQ(converted_["dropped_degenerate"], 3) << converted_.dump();
  EXPECT_EQ(converted_["dropped_non_finite"], 2) << converted_.dump();
  EXPECT_EQ(converted_["triangles"], kGoodTriangles) << converted_.dump();
}

TEST_F(DegenerateInput, WhatRemainsTracesLikeBruteForce) {
  const kdray::Scene scene = kdray::read_scene(tools_.scene("bad"));
  const kdray::KdTree tree = kdray::read_tree(tools_.tree("bad"));
  for (const kdray::Vec3& p : scene.positions) {
    ASSERT_TRUE(std::isfinite(p.x) && std::isfinite(p.y) && std::isfinite(p.z));
  }
  // Rays at every surface, the needle and the tiny triangle included, and from outside.
  std::vector<RayRecord> rays = kdray::rays_toward_surface(scene, {0, 50, 0}, 6000, 21);
  const std::vector<RayRecord> outside = kdray::random_rays(kdray::scene_bounds(scene), 6000, 22);
  rays.insert(rays.end(), outside.begin(), outside.end());
  const std::vector<HitRecord> hits = kdray::test::trace_checked(scene, tree, rays);
  for (const HitRecord& hit : hits) {
    ASSERT_FALSE(std::isnan(hit.t) || std::isnan(hit.u) || std::isnan(hit.v));
  }
}

TEST_F(DegenerateInput, WhatRemainsRendersWithoutNaN) {
  const std::string image = tools_.path("bad.exr");
  const nlohmann::json report =
      tools_.render("bad", image,
                   "--cam-pos 0,60,200 --cam-target 0,10,0 --cam-up 0,1,0 --fov 60 --width 32 --height 32 --spp 8");
  EXPECT_EQ(report["nonfinite_values"], 0);
  const kdray::FloatImage pixels = kdray::read_float_image(image);
  size_t nonfinite = 0;
  for (float value : pixels.pixels) nonfinite += std::isfinite(value) ? 0 : 1;
  EXPECT_EQ(nonfinite, 0u);
  EXPECT_GT(report["mean_radiance"].get<double>(), 0.0);
}
