// A leaf's triangles tested four at a time in vector lanes, as every CPU build and PoCL test them
// (kernels/kd_scene_view.h), give the hits of the one-at-a-time test that a GPU runs, byte for
// byte: on random, hard-case and camera rays (rays through vertices and along edges, where an
// edge function is 0 and a lane is tested again in double), on closest-hit and any-hit
// traversals, and on trees whose leaves hold from one to thousands of triangles (several pages
// of corners, lengths that are not multiples of four), in both leaf layouts, which give the
// same hits.
#include "test_scenes.h"

#include <kdray/kdtree.h>
#include <kdray/traverse.h>

#include <icosphere.h>

#include <gtest/gtest.h>

#include <cstring>
#include <string>
#include <vector>

// The device headers the traversal shares, at global scope (as libkdtree's traversal_variant.inc
// includes them), then the traversal itself compiled again below with the one-at-a-time test.
#include <kernels/kd_compat.h>
#include <kernels/kd_geometry.h>
#include <kernels/kd_types.h>

#define KD_LEAF_TESTS_ONE_AT_A_TIME
namespace kdray::one_at_a_time {
#include <kernels/kd_traverse.h>
#ifdef KD_LEAF_LANES
#error "kd_scene_view.h was included before this file asked for the one-at-a-time leaf test"
#endif
}  // namespace kdray::one_at_a_time

namespace kdray {
namespace {

// Traces `rays` through `tree` with the library's traversal (leaf tests in lanes) and with the
// one-at-a-time build above, closest and any hit, and reports the first ray that differs.
void expect_same_hits(const KdTree& tree, const std::vector<RayRecord>& rays, const std::string& name) {
  const one_at_a_time::KdSceneView view = one_at_a_time::kd_scene_view(
      tree.nodes.data(), tree.leaf_blocks.data(), tree.bounds.min.x, tree.bounds.min.y, tree.bounds.min.z,
      tree.bounds.max.x, tree.bounds.max.y, tree.bounds.max.z);
  TraceOptions one_ray;
  one_ray.lanes = false;
  std::vector<HitRecord> lanes;
  std::vector<uint8_t> lanes_occluded;
  trace_closest(tree, rays, lanes, one_ray);
  trace_any(tree, rays, lanes_occluded, one_ray);
  size_t differing = 0, first = rays.size(), occluded_differing = 0, hits = 0;
  for (size_t i = 0; i < rays.size(); ++i) {
    const HitRecord one = one_at_a_time::kd_intersect_closest(&view, rays[i]);
    hits += one.triangle != KD_NO_HIT;
    if (std::memcmp(&one, &lanes[i], sizeof(HitRecord)) != 0 && differing++ == 0) first = i;
    occluded_differing += one_at_a_time::kd_intersect_any(&view, rays[i]) != lanes_occluded[i];
  }
  EXPECT_EQ(differing, 0u) << name << ": " << differing << " of " << rays.size() << " closest hits differ; first ray "
                           << first;
  EXPECT_EQ(occluded_differing, 0u) << name << ": any-hit results differ";
  EXPECT_GT(hits, rays.size() / 10) << name << ": the rays must hit something to compare";
}

TEST(LeafLanes, GiveTheOneAtATimeHitsOnEveryLeafSize) {
  const Scene sphere = test::icosphere_scene(5, {0, 0, 0}, 1.0f);  // 20,480 triangles
  const Scene room = test::box_room();
  const Scene soup = test::triangle_soup(3000, 7);
  const Scene grid = test::coplanar_grid(24);
  struct Case {
    const char* name;
    const Scene* scene;
    uint32_t max_depth;  // 0: the default
  };
  for (const Case& c : {Case{"icosphere", &sphere, 0}, Case{"icosphere, depth 3 (leaves of thousands)", &sphere, 3},
                        Case{"icosphere, depth 9", &sphere, 9}, Case{"box room", &room, 0},
                        Case{"box room, depth 1", &room, 1}, Case{"soup", &soup, 0}, Case{"soup, depth 5", &soup, 5},
                        Case{"coplanar grid", &grid, 0}, Case{"coplanar grid, depth 2", &grid, 2}}) {
    BuildSettings settings;
    settings.max_depth = c.max_depth;
    std::vector<HitRecord> hits_of_layout[2];
    for (LeafLayout layout : {LeafLayout::paged, LeafLayout::grouped}) {
      settings.leaf_layout = layout;
      const KdTree tree = build_kdtree(*c.scene, settings);
      const std::string name = std::string(c.name) + (layout == LeafLayout::paged ? ", paged" : ", grouped");
      const std::vector<RayRecord> rays = test::ray_mix(*c.scene, tree, 8000, 41);
      expect_same_hits(tree, rays, name);
      trace_closest(tree, rays, hits_of_layout[layout == LeafLayout::grouped]);
    }
    ASSERT_EQ(hits_of_layout[0].size(), hits_of_layout[1].size());
    EXPECT_EQ(0, std::memcmp(hits_of_layout[0].data(), hits_of_layout[1].data(),
                             hits_of_layout[0].size() * sizeof(HitRecord)))
        << c.name << ": the two layouts give different hits";
  }
}

}  // namespace
}  // namespace kdray
