// The host's closest hits in AVX2 lanes (libkdtree/src/traversal_lanes.cpp) are those of one ray
// at a time, byte for byte: on random, hard-case and camera rays, rays from inside a closed mesh,
// trees deeper than the short stack (rays that overflow it and are traced again) and trees of
// every size, the ones too small for trace_closest to choose the lanes included.
#include "test_scenes.h"
#include "traversal_comparison.h"
#include "traversal_variant.h"

#include <kdray/kdtree.h>
#include <kdray/ray_sets.h>
#include <kdray/traverse.h>

#include <test_corpus.h>

#include <gtest/gtest.h>

#include <cstring>
#include <string>
#include <vector>

namespace kdray {
namespace {

void expect_lanes_match_one_ray_at_a_time(const KdTree& tree, const std::vector<RayRecord>& rays,
                                          const std::string& name) {
  test::expect_closest_matches_one_ray_at_a_time(tree, rays, &detail::closest_in_lanes, name, "lanes");
}

class TraversalLanes : public ::testing::Test {
 protected:
  void SetUp() override {
    if (!detail::closest_in_lanes_supported()) GTEST_SKIP() << "this CPU has no AVX2";
  }
};

TEST_F(TraversalLanes, SameHitsAsOneRayAtATimeOnGeneratedScenes) {
  for (const auto& [name, scene] : {std::pair<std::string, Scene>{"box room", test::box_room()},
                                    {"triangle soup", test::triangle_soup(4000, 5)},
                                    {"coplanar grid", test::coplanar_grid(24)}}) {
    const KdTree tree = build_kdtree(scene, BuildSettings{});
    expect_lanes_match_one_ray_at_a_time(tree, test::ray_mix(scene, tree, 6000, 11), name);
  }
}

TEST_F(TraversalLanes, SameHitsOnTheBunnyAndFromInsideIt) {
  std::string path;
  KDRAY_CORPUS_FILE(path, "bunny/bun_zipper.ply");
  const Scene scene = test::mesh_file(path);
  const KdTree tree = build_kdtree(scene, BuildSettings{});
  ASSERT_GT(tree.nodes.size(), kLanesMinNodes) << "trace_closest must choose the lanes for this tree";
  const std::vector<RayRecord> rays = test::rays_outside_and_inside(scene, tree, 6000, 21);
  expect_lanes_match_one_ray_at_a_time(tree, rays, "bunny");

  std::vector<HitRecord> chosen, one;
  TraceOptions one_at_a_time;
  one_at_a_time.lanes = false;
  ASSERT_TRUE(traces_in_lanes(tree, TraceOptions{}));
  ASSERT_FALSE(traces_in_lanes(tree, one_at_a_time));
  trace_closest(tree, rays, chosen, TraceOptions{});
  trace_closest(tree, rays, one, one_at_a_time);
  EXPECT_EQ(std::memcmp(chosen.data(), one.data(), rays.size() * sizeof(HitRecord)), 0) << "trace_closest";
}

// A tessellated sphere's tree is deeper than the short stack: some rays overflow it, and those
// are traced again from the start, as the scalar fast path does.
TEST_F(TraversalLanes, SameHitsWhereTheShortStackOverflows) {
  const test::DeepTree deep = test::deep_tree_and_rays();
  expect_lanes_match_one_ray_at_a_time(deep.tree, deep.rays, "icosphere");
}

}  // namespace
}  // namespace kdray
