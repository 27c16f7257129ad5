// The host's packets of eight rays (libkdtree/src/traversal_packets.cpp) give one ray at a time's
// closest hits byte for byte, and its occlusion answers: on random, hard-case and camera rays,
// rays from inside a closed mesh, trees of both leaf layouts and trees deeper than the short stack.
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

// Traces `rays` one at a time and as packets, closest and any, and reports the first ray whose
// answer differs.
void expect_packets_match_one_ray_at_a_time(const KdTree& tree, const std::vector<RayRecord>& rays,
                                            const std::string& name) {
  test::expect_closest_matches_one_ray_at_a_time(tree, rays, &detail::closest_in_packets, name, "packets");
  const TraversalArrays arrays = traversal_arrays(tree);
  std::vector<uint8_t> one_any(rays.size()), packets_any(rays.size());
  detail::traversal_short_stack().any(arrays, rays.data(), one_any.data(), rays.size());
  detail::any_in_packets(arrays, rays.data(), packets_any.data(), rays.size());
  size_t occluded = 0, any_differing = 0;
  for (size_t i = 0; i < rays.size(); ++i) {
    occluded += one_any[i];
    any_differing += one_any[i] != packets_any[i];
  }
  EXPECT_EQ(any_differing, 0u) << name << ": occlusion differs for " << any_differing << " rays";
  EXPECT_GT(occluded, rays.size() / 10) << name;
}

class TraversalPackets : public ::testing::Test {
 protected:
  void SetUp() override {
    if (!packets_supported()) GTEST_SKIP() << "this CPU has no AVX2";
  }
};

TEST_F(TraversalPackets, SameHitsAsOneRayAtATimeOnGeneratedScenesInBothLayouts) {
  for (const auto& [name, scene] : {std::pair<std::string, Scene>{"box room", test::box_room()},
                                    {"triangle soup", test::triangle_soup(4000, 5)},
                                    {"coplanar grid", test::coplanar_grid(24)}}) {
    for (const LeafLayout layout : {LeafLayout::grouped, LeafLayout::paged}) {
      BuildSettings settings;
      settings.leaf_layout = layout;
      const KdTree tree = build_kdtree(scene, settings);
      expect_packets_match_one_ray_at_a_time(tree, test::ray_mix(scene, tree, 6000, 11),
                                             name + (layout == LeafLayout::grouped ? ", grouped" : ", paged"));
    }
  }
}

TEST_F(TraversalPackets, SameHitsOnTheBunnyAndFromInsideIt) {
  std::string path;
  KDRAY_CORPUS_FILE(path, "bunny/bun_zipper.ply");
  const Scene scene = test::mesh_file(path);
  for (const LeafLayout layout : {LeafLayout::grouped, LeafLayout::paged}) {
    BuildSettings settings;
    settings.leaf_layout = layout;
    const KdTree tree = build_kdtree(scene, settings);
    const std::vector<RayRecord> rays = test::rays_outside_and_inside(scene, tree, 6000, 21);
    expect_packets_match_one_ray_at_a_time(tree, rays, layout == LeafLayout::grouped ? "bunny, grouped" : "bunny, paged");

    // trace_closest and trace_any choose the packets when asked, and only then.
    TraceOptions packets;
    packets.packets = true;
    ASSERT_TRUE(traces_in_packets(packets));
    ASSERT_FALSE(traces_in_packets(TraceOptions{}));
    std::vector<HitRecord> chosen, one;
    trace_closest(tree, rays, chosen, packets);
    trace_closest(tree, rays, one, TraceOptions{});
    EXPECT_EQ(std::memcmp(chosen.data(), one.data(), rays.size() * sizeof(HitRecord)), 0) << "trace_closest";
    std::vector<uint8_t> chosen_any, one_any;
    trace_any(tree, rays, chosen_any, packets);
    trace_any(tree, rays, one_any, TraceOptions{});
    EXPECT_EQ(chosen_any, one_any) << "trace_any";
  }
}

// A tessellated sphere's tree is deeper than the short stack: the packets' stack holds a level
// each, so no ray is traced again.
TEST_F(TraversalPackets, SameHitsWhereTheShortStackOverflows) {
  const test::DeepTree deep = test::deep_tree_and_rays();
  expect_packets_match_one_ray_at_a_time(deep.tree, deep.rays, "icosphere");
}

// A lane left alone in a subtree goes on alone on the one-ray fast path; where its short stack
// overflows there, the packet leaves it to be traced again. A packet of one ray is alone from the
// root, so on a tree deeper than the short stack some of them overflow.
TEST_F(TraversalPackets, ALoneLaneWhoseShortStackOverflowsIsTracedAgain) {
  const test::DeepTree deep = test::deep_tree_and_rays();
  std::vector<HitRecord> one;
  const TraversalWork work = count_traversal_work(deep.tree, deep.rays, one);
  ASSERT_GT(work.fast_path_restarts, 0u) << "no ray overflows the short stack: the test tests nothing";
  const TraversalArrays arrays = traversal_arrays(deep.tree);
  size_t differing = 0;
  uint8_t occluded = 0;
  for (size_t i = 0; i < deep.rays.size(); ++i) {
    HitRecord hit;
    trace_packet(arrays, &deep.rays[i], 1, &hit);
    differing += std::memcmp(&hit, &one[i], sizeof hit) != 0;
    trace_packet_any(arrays, &deep.rays[i], 1, &occluded);
    differing += occluded != (one[i].triangle != KD_NO_HIT && one[i].t < deep.rays[i].tmax);
  }
  EXPECT_EQ(differing, 0u) << "of " << deep.rays.size() << " rays, " << work.fast_path_restarts
                           << " of which overflow the short stack";
}

// A packet of fewer rays than lanes, and one whose rays mostly miss, from the public entry points.
TEST_F(TraversalPackets, PartialPacketsAndMisses) {
  const Scene scene = test::box_room();
  const KdTree tree = build_kdtree(scene, BuildSettings{});
  std::vector<RayRecord> rays = test::ray_mix(scene, tree, 64, 5);
  rays.resize(13);
  rays[2].dx = rays[2].dy = rays[2].dz = 0.0f;  // no direction: a miss
  rays[5].tmin = rays[5].tmax;                   // an empty interval: a miss
  rays[6].ox = NAN;                              // not finite: a miss
  const TraversalArrays arrays = traversal_arrays(tree);
  for (int count = 1; count <= kPacketRays; ++count) {
    std::vector<HitRecord> one(count), packet(count);
    detail::traversal_short_stack().closest(arrays, rays.data() + 5, one.data(), count);
    trace_packet(arrays, rays.data() + 5, count, packet.data());
    EXPECT_EQ(std::memcmp(one.data(), packet.data(), count * sizeof(HitRecord)), 0) << count << " rays";
    std::vector<uint8_t> one_any(count), packet_any(count);
    detail::traversal_short_stack().any(arrays, rays.data() + 5, one_any.data(), count);
    trace_packet_any(arrays, rays.data() + 5, count, packet_any.data());
    EXPECT_EQ(one_any, packet_any) << count << " rays";
  }
}

}  // namespace
}  // namespace kdray
