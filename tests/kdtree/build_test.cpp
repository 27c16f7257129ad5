// The SAH builder: degenerate scenes, structure, quality, the reference builder and threads.
#include "build_common.h"
#include "radix_sort.h"
#include "reference_builder.h"
#include "test_scenes.h"

#include <kdray/error.h>
#include <kdray/kdtree.h>
#include <kdray/traverse.h>

#include <test_corpus.h>

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <random>
#include <vector>

namespace kdray {
namespace {

bool same_tree(const KdTree& a, const KdTree& b) { return test::same_tree_bytes(a, b); }

// FNV-1a 64 over the nodes and the leaves' triangle indices: the tree's shape in one number (the
// corners in the leaf blocks are the scene's). Each leaf is fed with its first index in the
// concatenated triangle lists, as the builder numbers them, not with where its block lies, and
// the nodes as version 4 laid them out (every empty child a node, a leaf's header count << 2 | 3):
// the fingerprint is the builder's, whatever the file's leaf layout and encoding of empty
// children.
uint64_t tree_fingerprint(const KdTree& tree) {
  uint64_t hash = 0xcbf29ce484222325ull;
  auto feed = [&](const void* data, size_t size) {
    for (size_t i = 0; i < size; ++i) hash = (hash ^ static_cast<const unsigned char*>(data)[i]) * 0x100000001b3ull;
  };
  uint32_t references = 0;
  for (KdNode node : test::nodes_with_empty_leaves(tree)) {
    if (kd_node_is_leaf(node)) {
      const uint32_t count = kd_leaf_count(node);
      node = KdNode{references, count << 2 | KD_LEAF_TAG};  // version 5's leaf header
      references += count;
    }
    feed(&node, sizeof node);
  }
  const std::vector<uint32_t> indices = test::leaf_triangle_indices(tree);
  feed(indices.data(), indices.size() * sizeof(uint32_t));
  return hash;
}

// Every triangle with finite corners is in some leaf.
void expect_all_triangles_referenced(const Scene& scene, const KdTree& tree) {
  std::vector<bool> seen(scene.triangle_count(), false);
  for (uint32_t triangle : test::leaf_triangle_indices(tree)) seen.at(triangle) = true;
  for (size_t t = 0; t < seen.size(); ++t) EXPECT_TRUE(seen[t]) << "triangle " << t << " is in no leaf";
}

TEST(KdBuild, EmptySceneIsOneEmptyLeaf) {
  const KdTree tree = build_kdtree(test::from_triangles({}), BuildSettings{});
  ASSERT_EQ(tree.nodes.size(), 1u);
  EXPECT_TRUE(kd_node_is_leaf(tree.nodes[0]));
  EXPECT_EQ(kd_leaf_count(tree.nodes[0]), 0u);
  EXPECT_EQ(tree.stats.empty_leaves, 1u);
}

TEST(KdBuild, SingleTriangleIsOneLeaf) {
  const KdTree tree = build_kdtree(test::from_triangles({0, 0, 0, 1, 0, 0, 0, 1, 0}), BuildSettings{});
  ASSERT_EQ(tree.nodes.size(), 1u);
  EXPECT_EQ(test::leaf_triangle_indices(tree), std::vector<uint32_t>{0});
  EXPECT_EQ(tree.bounds.max.x, 1.0f);
  EXPECT_EQ(tree.bounds.min.z, 0.0f);
  EXPECT_EQ(tree.bounds.max.z, 0.0f);
}

TEST(KdBuild, CoplanarSceneWithZeroThicknessBoundsIsValid) {
  const Scene scene = test::coplanar_grid(32);
  const KdTree tree = build_kdtree(scene, BuildSettings{});
  EXPECT_EQ(tree.bounds.min.z, tree.bounds.max.z);
  EXPECT_GT(tree.stats.inner_nodes, 0u) << "a flat scene still splits along its two extents";
  for (const KdNode& node : tree.nodes)
    if (!kd_node_is_leaf(node)) {
      EXPECT_NE(kd_node_axis(node), 2u) << "no split across the zero thickness";
    }
  expect_all_triangles_referenced(scene, tree);
}

TEST(KdBuild, LineOfDegenerateTrianglesIsALeaf) {
  // Zero-area triangles along the x axis: the root box has no area, so no split can pay.
  const KdTree tree = build_kdtree(test::from_triangles({0, 0, 0, 1, 0, 0, 2, 0, 0, 2, 0, 0, 3, 0, 0, 4, 0, 0}),
                                   BuildSettings{});
  ASSERT_EQ(tree.nodes.size(), 1u);
  EXPECT_EQ(kd_leaf_count(tree.nodes[0]), 2u);
}

TEST(KdBuild, TrianglesWithNonFiniteCornersAreLeftOut) {
  const float nan = std::nanf("");
  const Scene scene = test::from_triangles({0, 0, 0, 1, 0, 0, 0, 1, 0, nan, 0, 0, 1, 1, 1, 0, 1, 1,
                                            0, 0, 1, INFINITY, 0, 1, 0, 1, 1});
  const KdTree tree = build_kdtree(scene, BuildSettings{});
  EXPECT_EQ(test::leaf_triangle_indices(tree), std::vector<uint32_t>{0});
  EXPECT_EQ(tree.bounds.max.z, 0.0f) << "the bounds ignore the dropped triangles";
  EXPECT_EQ(tree.stats.triangles, 3u);
}

TEST(KdBuild, StatisticsDescribeTheTree) {
  const Scene scene = test::icosphere_scene(4, {0, 0, 0}, 1);
  const KdTree tree = build_kdtree(scene, BuildSettings{});
  const TreeStats& stats = tree.stats;
  EXPECT_EQ(stats.inner_nodes + stats.leaves - stats.empty_leaves, tree.nodes.size()) << "empty leaves are no nodes";
  EXPECT_EQ(stats.inner_nodes + stats.leaves, test::nodes_with_empty_leaves(tree).size());
  EXPECT_EQ(stats.leaves, stats.inner_nodes + 1);
  EXPECT_EQ(stats.leaf_references, test::leaf_triangle_indices(tree).size());
  EXPECT_GE(stats.references_per_triangle, 1.0);
  EXPECT_LE(stats.max_depth, BuildSettings{}.resolved(scene.triangle_count()).max_depth);
  EXPECT_GT(stats.empty_leaves, 0u) << "empty space around a sphere is cut off";
  EXPECT_GT(stats.sah_cost, 0.0);
  EXPECT_LT(stats.sah_cost, 20.0 * scene.triangle_count()) << "much cheaper than one leaf";
  expect_all_triangles_referenced(scene, tree);
}

TEST(KdBuild, MaxDepthIsRespected) {
  const Scene scene = test::triangle_soup(2000, 3);
  BuildSettings settings;
  settings.max_depth = 3;
  const KdTree tree = build_kdtree(scene, settings);
  EXPECT_EQ(tree.stats.max_depth, 3u);
  EXPECT_EQ(BuildSettings{}.resolved(1u << 20).max_depth, 28u);
  EXPECT_EQ(BuildSettings{}.resolved(uint64_t{1} << 40).max_depth, BuildSettings::kAutoMaxDepthCap);
  EXPECT_EQ(settings.resolved(1u << 20).max_depth, 3u) << "an explicit limit stays";
}

// The automatic limit depends on the scene, so a tree records the limit it was built with, and
// its key names that limit: the same tree asked for by its explicit limit has the same key.
TEST(KdBuild, AutomaticDepthLimitIsRecordedInTheTree) {
  const Scene scene = test::triangle_soup(2000, 5);
  const KdTree automatic = build_kdtree(scene, BuildSettings{});
  const uint32_t limit = BuildSettings{}.resolved(scene.triangle_count()).max_depth;
  EXPECT_EQ(automatic.settings.max_depth, limit);
  EXPECT_LE(automatic.stats.max_depth, limit);
  BuildSettings explicit_settings;
  explicit_settings.max_depth = limit;
  const KdTree explicit_tree = build_kdtree(scene, explicit_settings);
  EXPECT_EQ(explicit_tree.key, automatic.key);
  EXPECT_EQ(explicit_tree.nodes.size(), automatic.nodes.size());
  BuildSettings deeper;
  deeper.max_depth = limit + 1;
  EXPECT_NE(build_kdtree(scene, deeper).key, automatic.key);
}

TEST(KdBuild, RejectsSettingsOutOfRange) {
  const Scene scene = test::triangle_soup(10, 1);
  BuildSettings settings;
  settings.max_depth = BuildSettings::kMaxDepthLimit + 1;
  EXPECT_THROW(build_kdtree(scene, settings), Error);
  settings = BuildSettings{};
  settings.empty_bonus = 0.0f;
  EXPECT_THROW(build_kdtree(scene, settings), Error);
  settings = BuildSettings{};
  settings.intersection_cost = -1.0f;
  EXPECT_THROW(build_kdtree(scene, settings), Error);
}

TEST(KdBuild, HigherTraversalCostGivesShallowerTree) {
  const Scene scene = test::triangle_soup(3000, 5);
  BuildSettings expensive;
  expensive.traversal_cost = 200.0f;
  EXPECT_LT(build_kdtree(scene, expensive).stats.inner_nodes, build_kdtree(scene, BuildSettings{}).stats.inner_nodes);
}

TEST(KdBuild, PerfectSplitsLowerTheCostOfTheCornellRoom) {
  const Scene scene = test::box_room();
  BuildSettings bounding_boxes;
  bounding_boxes.perfect_splits = false;
  EXPECT_LE(build_kdtree(scene, BuildSettings{}).stats.sah_cost, build_kdtree(scene, bounding_boxes).stats.sah_cost);
}

TEST(KdBuild, ReferenceBuilderAgreesOnGeneratedScenes) {
  BuildSettings no_clipping;
  no_clipping.perfect_splits = false;
  for (const Scene& scene : {test::icosphere_scene(3, {0.5f, 0, 0}, 2), test::box_room(), test::triangle_soup(3000, 11),
                             test::coplanar_grid(16)}) {
    for (const BuildSettings& settings : {BuildSettings{}, no_clipping}) {
      const KdTree fast = build_kdtree(scene, settings);
      const KdTree reference = test::build_kdtree_by_resorting(scene, settings);
      EXPECT_TRUE(same_tree(fast, reference)) << scene.triangle_count() << " triangles, nodes " << fast.nodes.size()
                                              << " vs " << reference.nodes.size();
      EXPECT_EQ(fast.stats.sah_cost, reference.stats.sah_cost);
    }
  }
}

TEST(KdBuild, ReferenceBuilderAgreesAroundTheSmallNodeThreshold) {
  // Roots just below, at and above the size the builder switches to its fixed-size small-node
  // path (kSmallNodeTriangles, 256), with and without clipping: the same tree as re-sorting
  // every node.
  BuildSettings no_clipping;
  no_clipping.perfect_splits = false;
  for (size_t triangles : {size_t{1}, size_t{33}, size_t{128}, size_t{255}, size_t{256}, size_t{257}, size_t{600}})
    for (const BuildSettings& settings : {BuildSettings{}, no_clipping}) {
      const Scene scene = test::triangle_soup(triangles, static_cast<uint32_t>(triangles));
      EXPECT_TRUE(same_tree(build_kdtree(scene, settings), test::build_kdtree_by_resorting(scene, settings)))
          << triangles << " triangles";
    }
}

TEST(KdBuild, ReferenceBuilderAgreesOnTheDragon) {
  std::string path;
  KDRAY_CORPUS_FILE(path, "dragon/dragon_vcg_23k.ply");
  const Scene scene = test::mesh_file(path);
  BuildSettings exact;
  exact.binned_above = 0;
  EXPECT_TRUE(same_tree(build_kdtree(scene, exact), test::build_kdtree_by_resorting(scene, exact)));
}

// More threads than cores (they are taken since kdray/threads.h) let a waiting thread pick up other
// nodes' work: under AddressSanitizer this caught divide()'s scratch arrays reused under a
// parallel loop still reading them (3 of 12 runs failed before the fix, 0 of 18 after).
TEST(KdBuild, ThreadCountDoesNotChangeTheTree) {
  const Scene scene = test::triangle_soup(25000, 17);
  const KdTree one = build_kdtree(scene, BuildSettings{}, BuildControl{1, {}});
  for (unsigned threads : {2u, 5u, 8u, 8u}) {
    const KdTree many = build_kdtree(scene, BuildSettings{}, BuildControl{threads, {}});
    EXPECT_TRUE(same_tree(one, many)) << threads << " threads";
  }
}

// Settings that bin nodes of more than `above` triangles, so that small test scenes have
// binned levels.
BuildSettings binned_above(uint32_t above, uint32_t bins = BuildSettings::kDefaultBins) {
  BuildSettings settings;
  settings.binned_above = above;
  settings.bins = bins;
  return settings;
}

// The builder's cost, C = lambda (K_T + P_L C_L + P_R C_R) and K_I N, by recursion (an empty
// child costs 0).
double recursive_cost(const KdTree& tree, uint32_t index, const detail::Box3& voxel, double root_area) {
  const KdNode node = tree.nodes[index];
  const double area = detail::surface_area(voxel) / root_area;
  if (kd_node_is_leaf(node)) return tree.settings.intersection_cost * static_cast<double>(kd_leaf_count(node)) * area;
  const int axis = static_cast<int>(kd_node_axis(node));
  const float split = kd_node_split(node);
  const bool bonus = (kd_node_below_empty(node) || kd_node_above_empty(node)) && split != voxel.min[axis] &&
                     split != voxel.max[axis];
  const double below = kd_node_below_empty(node)
                           ? 0.0
                           : recursive_cost(tree, index + 1, detail::below_plane(voxel, axis, split), root_area);
  const double above = kd_node_above_empty(node) ? 0.0
                                                 : recursive_cost(tree, kd_node_far_child(node),
                                                                  detail::above_plane(voxel, axis, split), root_area);
  return (bonus ? tree.settings.empty_bonus : 1.0) * (tree.settings.traversal_cost * area + below + above);
}

TEST(KdBuild, SahCostIsTheBuildersCostWithTheEmptyBonus) {
  const Scene scene = test::icosphere_scene(4, {0, 0, 0}, 1);
  for (float bonus : {1.0f, 0.8f, 0.5f}) {
    BuildSettings settings;
    settings.empty_bonus = bonus;
    const KdTree tree = build_kdtree(scene, settings);
    const detail::Box3 root = detail::box_of(tree.bounds);
    EXPECT_NEAR(tree.stats.sah_cost, recursive_cost(tree, 0, root, detail::surface_area(root)),
                1e-9 * tree.stats.sah_cost)
        << "empty bonus " << bonus;
  }
  // With a bonus, the empty cuts around the sphere cost less than their full traversal.
  BuildSettings full;
  full.empty_bonus = 1.0f;
  const KdTree tree = build_kdtree(scene, BuildSettings{});
  KdTree unbonused = tree;
  unbonused.settings = full;
  EXPECT_LT(tree.stats.sah_cost, compute_tree_stats(unbonused, scene.triangle_count()).sah_cost);
}

TEST(KdBuild, BinnedTreeIsTheSameForAnyThreadCount) {
  for (const BuildSettings& settings : {binned_above(1000), binned_above(300, 16)}) {
    const Scene scene = test::triangle_soup(25000, 17);
    const KdTree one = build_kdtree(scene, settings, BuildControl{1, {}});
    EXPECT_NE(tree_fingerprint(one), tree_fingerprint(build_kdtree(scene, binned_above(0))))
        << "the binned levels chose other planes than the exact sweep";
    for (unsigned threads : {2u, 8u, 8u}) {
      const KdTree many = build_kdtree(scene, settings, BuildControl{threads, {}});
      EXPECT_TRUE(same_tree(one, many)) << threads << " threads, " << settings.bins << " bins";
      EXPECT_EQ(one.stats.sah_cost, many.stats.sah_cost);
    }
  }
}

TEST(KdBuild, BinnedTreeIsValidAndCloseToTheExactOne) {
  std::string path;
  KDRAY_CORPUS_FILE(path, "dragon/dragon_vcg_23k.ply");
  const Scene dragon = test::mesh_file(path);
  BuildSettings no_clipping = binned_above(500);
  no_clipping.perfect_splits = false;
  for (const Scene& scene : {dragon, test::coplanar_grid(64), test::box_room()})
    for (const BuildSettings& settings : {binned_above(500), binned_above(20, 4), no_clipping}) {
      const KdTree binned = build_kdtree(scene, settings);
      BuildSettings exact_settings = settings;
      exact_settings.binned_above = 0;
      const KdTree exact = build_kdtree(scene, exact_settings);
      const TreeStats& stats = binned.stats;
      EXPECT_EQ(stats.inner_nodes + stats.leaves - stats.empty_leaves, binned.nodes.size());
      EXPECT_EQ(stats.leaves, stats.inner_nodes + 1);
      EXPECT_LE(stats.max_depth, settings.resolved(scene.triangle_count()).max_depth);
      expect_all_triangles_referenced(scene, binned);
      for (const KdNode& node : binned.nodes) {
        if (!kd_node_is_leaf(node)) continue;
        const uint32_t* block = binned.leaf_blocks.data() + kd_leaf_first(node);
        for (uint32_t i = 1; i < kd_leaf_count(node); ++i)
          EXPECT_LT(kd_leaf_index(block, kd_leaf_grouped(node), i - 1), kd_leaf_index(block, kd_leaf_grouped(node), i));
      }
      // Binning costs little at the top of a tree; 4 bins above 20 triangles may cost more.
      EXPECT_LT(stats.sah_cost, (settings.bins == 4 ? 1.25 : 1.03) * exact.stats.sah_cost)
          << scene.triangle_count() << " triangles, " << settings.bins << " bins above " << settings.binned_above;
    }
}

TEST(KdBuild, BinningIsTheDefaultAboveTheThresholdOnly) {
  EXPECT_GT(BuildSettings{}.binned_above, 0u);
  const Scene small = test::triangle_soup(3000, 11);
  EXPECT_TRUE(same_tree(build_kdtree(small, binned_above(3000)), build_kdtree(small, binned_above(0))))
      << "a root at the threshold is built by the exact sweep";
  EXPECT_FALSE(same_tree(build_kdtree(small, binned_above(2999)), build_kdtree(small, binned_above(0))));
}

TEST(KdBuild, RejectsBinCountsOutOfRange) {
  const Scene scene = test::triangle_soup(100, 1);
  EXPECT_THROW(build_kdtree(scene, binned_above(10, 1)), Error);
  EXPECT_THROW(build_kdtree(scene, binned_above(10, BuildSettings::kMaxBins + 1)), Error);
  EXPECT_NO_THROW(build_kdtree(scene, binned_above(0, 1))) << "bins do not matter to the exact sweep";
}

// The exact sweep's trees, pinned at the automatic depth limit these scenes had before the
// binned builder existed (8 + 1.3 log2 N: 26 for all three); re-pinned when splits had to pay
// for the references they add (CostModel::reference_price), and for the dragon when straddlers
// came to be clipped by the parent voxel's planes first (the same planes in another order, so
// clipped bounds may differ in their last bit).
TEST(KdBuild, ExactBuilderKeepsItsTrees) {
  BuildSettings exact;
  exact.binned_above = 0;
  exact.max_depth = 26;
  EXPECT_EQ(tree_fingerprint(build_kdtree(test::triangle_soup(25000, 17), exact)), 0x0d84db78e89cf25full);
  EXPECT_EQ(tree_fingerprint(build_kdtree(test::icosphere_scene(5, {0.25f, 0, 0}, 1), exact)), 0xaec9fc864dc9a34bull);
  std::string path;
  KDRAY_CORPUS_FILE(path, "dragon/dragon_vcg_23k.ply");
  EXPECT_EQ(tree_fingerprint(build_kdtree(test::mesh_file(path), exact)), 0x8af96ac400020f8eull);
}

// Keys that differ in all bytes (eight passes), in only some (the others take no pass; an odd
// number of passes ends in the scratch buffer) and keys that repeat.
TEST(KdBuild, RadixSortSortsAsAComparisonSortDoes) {
  std::mt19937_64 random(7);
  for (uint64_t varying : {~uint64_t{0}, uint64_t{0x00ff00ff}, uint64_t{0xff0000ff00ff0000}, uint64_t{0x3}})
    for (size_t count : {size_t{1}, size_t{2}, size_t{1000}, size_t{5000}}) {
      std::vector<uint64_t> keys(count), scratch(count);
      for (uint64_t& key : keys) key = (random() & varying) | (uint64_t{0x1234567890abcdef} & ~varying);
      std::vector<uint64_t> expected = keys;
      std::sort(expected.begin(), expected.end());
      detail::radix_sort(keys.data(), scratch.data(), count);
      EXPECT_EQ(keys, expected) << count << " keys varying in " << std::hex << varying;
    }
}

// From byte 3 up only: keys whose three low bytes increase along the array (as a node's events
// do, made triangle by triangle) still come out sorted; keys whose low bytes do not, do not.
TEST(KdBuild, RadixSortFromAByteKeepsTheOrderOfTheBytesBelow) {
  std::mt19937_64 random(11);
  const size_t count = 5000;
  std::vector<uint64_t> keys(count), scratch(count);
  // Few distinct high parts: most keys tie above byte 3, and the low bytes decide.
  for (size_t i = 0; i < count; ++i) keys[i] = (random() % 16) << 40 | (random() % 4) << 24 | i;
  std::vector<uint64_t> expected = keys;
  std::sort(expected.begin(), expected.end());
  detail::radix_sort(keys.data(), scratch.data(), count, 3);
  EXPECT_EQ(keys, expected);
  std::reverse(keys.begin(), keys.end());
  detail::radix_sort(keys.data(), scratch.data(), count, 3);
  EXPECT_NE(keys, expected);  // the low bytes were not sorted on
}

TEST(KdBuild, ReportsItsPhaseTimes) {
  const Scene scene = test::triangle_soup(5000, 4);
  BuildTimings timings{-1, -1, -1, -1, -1};
  build_kdtree(scene, BuildSettings{}, BuildControl{2, {}, &timings});
  for (double seconds : {timings.prepare, timings.events, timings.subdivide, timings.assemble, timings.statistics})
    EXPECT_GE(seconds, 0.0);
  EXPECT_GT(timings.subdivide, 0.0);
}

// The builder's own count of finished subtrees reaches 1 before the build's closing report of 1,
// binned at the top and exact from the root (below the default threshold). Two clusters of
// triangles at opposite corners: the root's split parts them, and each child's first splits cut
// off the empty rest of its voxel (nodes that become their own child, as a subtree's root too).
TEST(KdBuild, ProgressEndsAtOne) {
  std::vector<float> corners;
  for (float offset : {0.0f, 9.0f}) {
    const Scene cluster = test::triangle_soup(3000, offset == 0.0f ? 2 : 3);
    for (uint32_t index : cluster.indices) {
      const Vec3& p = cluster.positions[index];
      corners.insert(corners.end(), {p.x + offset, p.y + offset, p.z + offset});
    }
  }
  const Scene scene = test::from_triangles(corners);
  for (const BuildSettings& settings : {binned_above(4096), BuildSettings{}}) {
    std::vector<double> fractions;
    build_kdtree(scene, settings, BuildControl{2, [&](double fraction) { fractions.push_back(fraction); }});
    ASSERT_GE(fractions.size(), 2u);
    EXPECT_TRUE(std::is_sorted(fractions.begin(), fractions.end()));
    EXPECT_DOUBLE_EQ(fractions[fractions.size() - 2], 1.0);
    EXPECT_DOUBLE_EQ(fractions.back(), 1.0);
  }
}

}  // namespace
}  // namespace kdray
