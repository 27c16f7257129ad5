// Secondary rays leave their surface for good: shadow rays from a wall in the plane x = 0 of a
// Cornell-sized room towards its ceiling light never meet the wall again. Their origin is moved off
// the wall by pt_offset_origin (kernels/pt_sampling.h, compiled here as C++ with the kernels'
// arithmetic) and they are traced by the traversal the kernels run. With a step of 1.5e-5 off a
// plane at 0, about 0.4% of them met the wall at t ~ +3e-8 whenever a leaf held the wall and the
// ray's origin together, so the image depended on the tree.
#include "test_scenes.h"

#include <kdray/kdtree.h>
#include <kdray/traverse.h>

#include <kernels/kd_types.h>
#include <kernels/kd_vector.h>

#include <gtest/gtest.h>

#include <random>
#include <vector>

namespace {
#include <kernels/pt_sampling.h>
}  // namespace

namespace kdray {
namespace {

TEST(OffsetOrigin, ShadowRaysFromAWallAtZeroDoNotMeetItAgain) {
  // The wall and the light of the Cornell box (millimetres): a wall facing +x in the plane x = 0,
  // and the light facing down just below the ceiling.
  Scene scene;
  scene.materials.push_back(Material{});
  test::add_quad(scene, {{{0, 0, 559.2f}, {0, 0, 0}, {0, 548.8f, 0}, {0, 548.8f, 559.2f}}}, 0);
  test::add_quad(scene, {{{343, 548.7f, 227}, {343, 548.7f, 332}, {213, 548.7f, 332}, {213, 548.7f, 227}}}, 0);
  // The tree with the default costs, and one leaf holding everything (splits cost too much).
  BuildSettings one_leaf;
  one_leaf.traversal_cost = 1000;
  const KdTree trees[] = {build_kdtree(scene, BuildSettings{}), build_kdtree(scene, one_leaf)};
  ASSERT_EQ(trees[1].stats.leaves, 1u);

  std::mt19937 random(7);
  std::uniform_real_distribution<float> unit(0.0f, 1.0f);
  std::vector<RayRecord> rays;
  for (int i = 0; i < 200000; ++i) {
    float3 on_wall = KD_FLOAT3(0.0f, 1.0f + 546.0f * unit(random), 1.0f + 557.0f * unit(random));
    float3 on_light = KD_FLOAT3(213.0f + 130.0f * unit(random), 548.7f, 227.0f + 105.0f * unit(random));
    float3 origin = pt_offset_origin(on_wall, KD_FLOAT3(1.0f, 0.0f, 0.0f));
    float3 target = pt_offset_origin(on_light, KD_FLOAT3(0.0f, -1.0f, 0.0f));
    float3 span = target - origin;
    rays.push_back({origin.x, origin.y, origin.z, span.x, span.y, span.z, 0.0f, 1.0f});
  }
  for (const KdTree& tree : trees) {
    std::vector<uint8_t> occluded;
    trace_any(tree, rays, occluded);
    size_t blocked = 0;
    for (uint8_t o : occluded) blocked += o;
    EXPECT_EQ(blocked, 0u) << "of " << rays.size() << " shadow rays, tree of " << tree.stats.leaves << " leaves";
  }
}

}  // namespace
}  // namespace kdray
