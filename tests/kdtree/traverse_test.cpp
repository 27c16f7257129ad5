// CPU traversal against brute force (float and double precision), stack variants, any-hit,
// and closed meshes that rays from inside must never leave.
#include "build_common.h"
#include "test_scenes.h"

#include <kdray/kdtree.h>
#include <kdray/ray_sets.h>
#include <kdray/traverse.h>

#include <test_corpus.h>

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <cstring>

namespace kdray {
namespace {

// The traversal must find what testing every triangle with the same float test finds: the
// same triangle and t, or, where the ray meets several triangles at one point (a shared vertex
// or edge), another of them, whose t may differ from the brute force's by rounding. A ray that
// starts on a triangle may or may not report it at a rounding-sized t (the tree skips the side
// of a split plane the ray leaves), so such origin hits are ignored on both sides.
bool same_hit_or_tie(const HitRecord& found, const HitRecord& expected) {
  if (found.triangle == expected.triangle) return found.t == expected.t || found.triangle == KD_NO_HIT;
  if (found.triangle == KD_NO_HIT || expected.triangle == KD_NO_HIT) return false;
  return std::fabs(found.t - expected.t) <= 4e-7f * std::fabs(expected.t);
}

void expect_same_as_float_brute_force(const Scene& scene, const KdTree& tree, const std::vector<RayRecord>& rays,
                                      TraversalStack stack) {
  std::vector<HitRecord> hits;
  trace_closest(tree, rays, hits, {0, stack});
  size_t failures = 0;
  for (size_t i = 0; i < rays.size() && failures < 10; ++i) {
    const HitRecord expected = test::brute_force_float(scene, rays[i]);
    if (same_hit_or_tie(hits[i], expected)) continue;
    if (test::is_origin_hit(scene, rays[i], expected) || test::is_origin_hit(scene, rays[i], hits[i])) {
      if (test::is_origin_hit(scene, rays[i], hits[i])) continue;
      if (same_hit_or_tie(hits[i], test::brute_force_float(scene, rays[i], true))) continue;
    }
    ++failures;
    ADD_FAILURE() << "ray " << i << " (" << rays[i].ox << " " << rays[i].oy << " " << rays[i].oz << " -> "
                  << rays[i].dx << " " << rays[i].dy << " " << rays[i].dz << "): tree t=" << hits[i].t
                  << " triangle " << hits[i].triangle << ", brute force t=" << expected.t << " triangle "
                  << expected.triangle;
  }
}

// Against double precision: hit/miss and t agree, except for rays that graze an edge (the
// closest triangle's smallest barycentric within `kGraze` of 0, or within the float test's
// uncertainty for that ray and triangle where that is larger: a small triangle seen from afar),
// where float and double may fall on different sides. Returns the number of such grazing rays.
size_t expect_close_to_double_brute_force(const Scene& scene, const KdTree& tree, const std::vector<RayRecord>& rays) {
  constexpr double kGraze = 1e-5, kRelativeT = 1e-5;
  std::vector<HitRecord> hits;
  trace_closest(tree, rays, hits);
  size_t grazing = 0, failures = 0;
  for (size_t i = 0; i < rays.size() && failures < 10; ++i) {
    const test::DoubleHit exact = test::brute_force_double(scene, rays[i]);
    const bool exact_grazes = exact.hit && exact.margin < std::max(kGraze, exact.uncertainty);
    const HitRecord& found = hits[i];
    bool ok;
    if (found.triangle == KD_NO_HIT) {
      ok = !exact.hit || exact_grazes;
    } else {
      const test::DoubleHit same = test::intersect_double(scene, found.triangle, rays[i]);
      const bool t_agrees = std::fabs(same.t - found.t) <= kRelativeT * std::max(1.0, std::fabs(same.t));
      const bool nothing_closer = !exact.hit || exact.t >= found.t - kRelativeT * std::max(1.0, static_cast<double>(std::fabs(found.t)));
      const bool closer_one_grazes = exact_grazes;
      ok = same.triangle != KD_NO_HIT && same.margin > -kGraze && t_agrees && (nothing_closer || closer_one_grazes);
    }
    if (exact_grazes) ++grazing;
    if (ok) continue;
    ++failures;
    ADD_FAILURE() << "ray " << i << ": tree t=" << found.t << " triangle " << found.triangle << ", double "
                  << (exact.hit ? "hit" : "miss") << " t=" << exact.t << " triangle " << exact.triangle
                  << " margin " << exact.margin;
  }
  return grazing;
}

std::vector<RayRecord> mixed_rays(const Scene& scene, const KdTree& tree, size_t count, uint64_t seed) {
  std::vector<RayRecord> rays = random_rays(tree.bounds, count / 2, seed);
  const std::vector<RayRecord> hard = hard_case_rays(scene, tree, count - count / 2, seed + 1);
  rays.insert(rays.end(), hard.begin(), hard.end());
  return rays;
}

TEST(KdTraverse, MatchesFloatBruteForceOnGeneratedScenes) {
  for (const Scene& scene : {test::icosphere_scene(3, {0, 0, 0}, 1), test::box_room(), test::triangle_soup(2000, 4),
                             test::coplanar_grid(8)}) {
    const KdTree tree = build_kdtree(scene, BuildSettings{});
    const std::vector<RayRecord> rays = mixed_rays(scene, tree, 6000, 21);
    for (TraversalStack stack : {TraversalStack::Short, TraversalStack::Depth1, TraversalStack::Full})
      expect_same_as_float_brute_force(scene, tree, rays, stack);
  }
}

// A tree of one split has two leaves of about a thousand triangles, whose thousands of distinct
// corners are numbered in pages of their own (kernels/kd_types.h): every corner must be read
// where the block put it.
TEST(KdTraverse, LeavesOfManyPagesGiveTheBruteForceHits) {
  const Scene scene = test::triangle_soup(2000, 9);
  BuildSettings settings;
  settings.max_depth = 1;
  const KdTree tree = build_kdtree(scene, settings);
  ASSERT_EQ(tree.stats.leaves, 2u);
  ASSERT_GT(tree.stats.mean_triangles_per_leaf, 3.0 * KD_LEAF_PAGE_TRIANGLES);
  const std::vector<RayRecord> rays = mixed_rays(scene, tree, 3000, 5);
  for (TraversalStack stack : {TraversalStack::Short, TraversalStack::Full})
    expect_same_as_float_brute_force(scene, tree, rays, stack);
}

TEST(KdTraverse, MatchesFloatBruteForceOnTheDragon) {
  std::string path;
  KDRAY_CORPUS_FILE(path, "dragon/dragon_vcg_23k.ply");
  const Scene scene = test::mesh_file(path);
  const KdTree tree = build_kdtree(scene, BuildSettings{});
  const std::vector<RayRecord> rays = mixed_rays(scene, tree, 3000, 5);
  expect_same_as_float_brute_force(scene, tree, rays, TraversalStack::Short);
  expect_same_as_float_brute_force(scene, tree, rays, TraversalStack::Depth1);
}

TEST(KdTraverse, MatchesDoublePrecisionBruteForce) {
  std::string path;
  KDRAY_CORPUS_FILE(path, "bunny/bun_zipper.ply");
  for (const Scene& scene : {test::mesh_file(path), test::box_room()}) {
    const KdTree tree = build_kdtree(scene, BuildSettings{});
    const std::vector<RayRecord> rays = mixed_rays(scene, tree, 800, 9);
    const size_t grazing = expect_close_to_double_brute_force(scene, tree, rays);
    EXPECT_LT(grazing, rays.size() / 4) << "grazing rays are the exception";
  }
}

// A binned tree finds what brute force and the exact sweep's tree find.
TEST(KdTraverse, BinnedTreesFindTheClosestHits) {
  std::string path;
  KDRAY_CORPUS_FILE(path, "dragon/dragon_vcg_23k.ply");
  for (const Scene& scene : {test::mesh_file(path), test::triangle_soup(5000, 8), test::box_room()}) {
    BuildSettings binned, exact;
    binned.binned_above = 100;
    exact.binned_above = 0;
    const KdTree tree = build_kdtree(scene, binned);
    const std::vector<RayRecord> rays = mixed_rays(scene, tree, 4000, 13);
    expect_same_as_float_brute_force(scene, tree, rays, TraversalStack::Short);
    std::vector<HitRecord> binned_hits, exact_hits;
    trace_closest(tree, rays, binned_hits);
    trace_closest(build_kdtree(scene, exact), rays, exact_hits);
    size_t differ = 0;
    for (size_t i = 0; i < rays.size(); ++i)
      differ += !same_hit_or_tie(binned_hits[i], exact_hits[i]) && !test::is_origin_hit(scene, rays[i], exact_hits[i]);
    EXPECT_EQ(differ, 0u) << scene.triangle_count() << " triangles";
  }
}

TEST(KdTraverse, DepthOneStackGivesTheSameHitsAsTheFullStack) {
  const Scene scene = test::triangle_soup(20000, 8);
  const KdTree tree = build_kdtree(scene, BuildSettings{});
  ASSERT_GT(tree.stats.max_depth, 10u) << "deep enough to force restarts";
  const std::vector<RayRecord> rays = mixed_rays(scene, tree, 40000, 13);
  std::vector<HitRecord> full, depth1, short_stack;
  trace_closest(tree, rays, full, {0, TraversalStack::Full});
  trace_closest(tree, rays, depth1, {0, TraversalStack::Depth1});
  trace_closest(tree, rays, short_stack, {0, TraversalStack::Short});
  EXPECT_EQ(0, std::memcmp(full.data(), depth1.data(), full.size() * sizeof(HitRecord)));
  EXPECT_EQ(0, std::memcmp(full.data(), short_stack.data(), full.size() * sizeof(HitRecord)));
}

TEST(KdTraverse, AnyHitAgreesWithClosestHit) {
  const Scene scene = test::box_room();
  const KdTree tree = build_kdtree(scene, BuildSettings{});
  std::vector<RayRecord> rays = mixed_rays(scene, tree, 8000, 3);
  for (size_t i = 0; i < rays.size(); i += 2) rays[i].tmax = 0.5f;  // shadow rays of finite length
  std::vector<HitRecord> hits;
  std::vector<uint8_t> occluded;
  for (TraversalStack stack : {TraversalStack::Short, TraversalStack::Depth1}) {
    trace_closest(tree, rays, hits, {0, stack});
    trace_any(tree, rays, occluded, {0, stack});
    for (size_t i = 0; i < rays.size(); ++i)
      ASSERT_EQ(occluded[i] != 0, hits[i].triangle != KD_NO_HIT) << "ray " << i;
  }
}

TEST(KdTraverse, RayIntervalIsOpenAtBothEnds) {
  const Scene scene = test::from_triangles({-1, -1, 2, 1, -1, 2, 0, 1, 2});
  const KdTree tree = build_kdtree(scene, BuildSettings{});
  RayRecord ray{0, 0, 0, 0, 0, 1, 0, INFINITY};
  EXPECT_FLOAT_EQ(intersect_closest(tree, ray).t, 2.0f);
  ray.tmax = 2.0f;
  EXPECT_EQ(intersect_closest(tree, ray).triangle, KD_NO_HIT);
  ray.tmax = INFINITY;
  ray.tmin = 2.0f;
  EXPECT_EQ(intersect_closest(tree, ray).triangle, KD_NO_HIT);
  const HitRecord miss = intersect_closest(tree, RayRecord{0, 0, 0, 0, 0, -1, 0, INFINITY});
  EXPECT_TRUE(std::isinf(miss.t));
  EXPECT_EQ(miss.triangle, KD_NO_HIT);
}

TEST(KdTraverse, NonFiniteRaysMiss) {
  const Scene scene = test::box_room();
  const KdTree tree = build_kdtree(scene, BuildSettings{});
  const float nan = std::nanf("");
  for (const RayRecord& ray : {RayRecord{nan, 0.5f, 0, 1, 0, 0, 0, INFINITY}, RayRecord{0, 0.5f, 0, 0, 0, 0, 0, INFINITY},
                               RayRecord{0, 0.5f, 0, nan, 1, 0, 0, INFINITY}, RayRecord{0, 0.5f, 0, 1, 0, 0, 0, nan},
                               RayRecord{-INFINITY, 0.5f, 0.1f, 1, 0.01f, 0.02f, 0, INFINITY},
                               RayRecord{0, 0.5f, 0.1f, 1, INFINITY, 0.02f, 0, INFINITY}})
    EXPECT_EQ(intersect_closest(tree, ray).triangle, KD_NO_HIT);
  // a coordinate far out is finite all the same: this ray comes into the room from 1e20 away
  EXPECT_NE(intersect_closest(tree, RayRecord{-1.0e20f, 0.5f, 0.1f, 1, 0, 0, 0, INFINITY}).triangle, KD_NO_HIT);
}

KdNode inner_node(uint32_t axis, float split, uint32_t far_child) {
  uint32_t bits;
  std::memcpy(&bits, &split, sizeof bits);
  return KdNode{bits, far_child << KD_CHILD_SHIFT | axis};
}

KdNode leaf_node(uint32_t first, uint32_t count) { return kd_leaf_node(first, count, 0); }

// Two copies of one triangle in the plane z = 0 (indices 0 and 1), in trees written by hand so
// that the larger index is met first: the smaller one must win all the same.
TEST(KdTraverse, TiesInTGoToTheSmallerTriangleIndex) {
  const std::vector<float> triangle = {-1, -1, 0, 1, -1, 0, 0, 1, 0};
  std::vector<float> corners = triangle;
  corners.insert(corners.end(), triangle.begin(), triangle.end());
  const Scene scene = test::from_triangles(corners);
  const uint32_t larger_first[] = {1, 0};
  for (LeafLayout layout : {LeafLayout::paged, LeafLayout::grouped}) {
    KdTree one_leaf;
    one_leaf.bounds = Bounds{{-1, -1, -1}, {1, 1, 1}};
    TraversalArray<KdNode> nodes = {leaf_node(0, 2)};
    one_leaf.leaf_blocks = leaf_blocks_of(scene, nodes, larger_first, layout);
    one_leaf.nodes = std::move(nodes);
    // Split at x = 0: triangle 1 only below, triangle 0 only above. The ray meets the triangles
    // on the split plane, so both leaves touch the hit; the below one comes first.
    KdTree two_leaves = one_leaf;
    nodes = {inner_node(0, 0.0f, 2), leaf_node(0, 1), leaf_node(1, 1)};
    two_leaves.leaf_blocks = leaf_blocks_of(scene, nodes, larger_first, layout);
    two_leaves.nodes = std::move(nodes);
    const RayRecord ray{-1, 0, -1, 1, 0, 1, 0, INFINITY};
    for (const KdTree* tree : {&one_leaf, &two_leaves}) {
      for (TraversalStack stack : {TraversalStack::Short, TraversalStack::Depth1, TraversalStack::Full}) {
        const HitRecord hit = intersect_closest(*tree, ray, stack);
        EXPECT_EQ(hit.triangle, 0u);
        EXPECT_EQ(hit.t, 1.0f);
      }
    }
  }
}

// Every triangle of a grid twice, the copies first in reverse order: whatever tree is built
// (its settings change its shape), each hit is exactly the brute force's, which keeps the
// smallest index of the triangles at the closest t.
TEST(KdTraverse, DuplicatedTrianglesGiveTheSameHitsInEveryTree) {
  const Scene grid = test::coplanar_grid(8);
  std::vector<float> corners;
  auto append = [&](uint32_t triangle) {
    for (uint32_t corner = 0; corner < 3; ++corner) {
      const Vec3& p = grid.positions[grid.indices[3 * triangle + corner]];
      corners.insert(corners.end(), {p.x, p.y, p.z});
    }
  };
  for (uint32_t triangle = grid.triangle_count(); triangle-- > 0;) append(triangle);
  for (uint32_t triangle = 0; triangle < grid.triangle_count(); ++triangle) append(triangle);
  const Scene scene = test::from_triangles(corners);
  BuildSettings shallow;
  shallow.max_depth = 2;
  BuildSettings unclipped;
  unclipped.perfect_splits = false;
  unclipped.traversal_cost = 2.0f;
  BuildSettings paged;
  paged.leaf_layout = LeafLayout::paged;
  std::vector<HitRecord> reference;
  for (const BuildSettings& settings : {BuildSettings{}, shallow, unclipped, paged}) {
    const KdTree tree = build_kdtree(scene, settings);
    const std::vector<RayRecord> rays = random_rays(tree.bounds, 4000, 31);
    for (TraversalStack stack : {TraversalStack::Short, TraversalStack::Depth1}) {
      std::vector<HitRecord> hits;
      trace_closest(tree, rays, hits, {0, stack});
      if (reference.empty()) {
        reference = hits;
        size_t hit_count = 0;
        for (size_t i = 0; i < rays.size(); ++i) {
          const HitRecord expected = test::brute_force_float(scene, rays[i]);
          ASSERT_EQ(hits[i].triangle, expected.triangle) << "ray " << i;
          ASSERT_EQ(hits[i].t, expected.t) << "ray " << i;
          hit_count += expected.triangle != KD_NO_HIT ? 1 : 0;
        }
        ASSERT_GT(hit_count, rays.size() / 10) << "enough rays meet the grid";
      }
      EXPECT_EQ(0, std::memcmp(hits.data(), reference.data(), hits.size() * sizeof(HitRecord)));
    }
  }
}

// Rays from a point inside a closed mesh, aimed at its vertices, edges and random surface
// points: every one must hit the mesh.
void expect_no_escape(const Scene& scene, const Vec3& inside, size_t count) {
  const KdTree tree = build_kdtree(scene, BuildSettings{});
  const std::vector<RayRecord> rays = rays_toward_surface(scene, inside, count, 77);
  std::vector<uint8_t> occluded;
  trace_any(tree, rays, occluded);
  size_t escaped = 0;
  for (uint8_t hit : occluded) escaped += hit ? 0 : 1;
  EXPECT_EQ(escaped, 0u) << "of " << rays.size() << " rays from inside";
  std::vector<HitRecord> hits;
  trace_closest(tree, rays, hits, {0, TraversalStack::Depth1});
  escaped = 0;
  for (const HitRecord& hit : hits) escaped += hit.triangle == KD_NO_HIT ? 1 : 0;
  EXPECT_EQ(escaped, 0u) << "closest hit, depth-1 stack";
}

// Scaled down under sanitizers by KDRAY_TEST_RAY_SCALE (e.g. 0.1).
size_t scaled(size_t count) {
  const char* scale = std::getenv("KDRAY_TEST_RAY_SCALE");
  return scale ? static_cast<size_t>(count * std::atof(scale)) : count;
}

TEST(KdTraverse, RaysFromInsideTheIcosphereNeverEscape) {
  expect_no_escape(test::icosphere_scene(3, {0.1f, -0.2f, 0.05f}, 1.0f), {0.1f, -0.2f, 0.05f}, scaled(1000000));
}

// An origin a denormal before a split plane at 0, with a direction of magnitude 2 or more:
// (split - origin) / d rounds to 0 although the plane lies ahead, and the ray is beyond it at
// every t a hit can have. The traversal used to take the origin's side alone there and let rays
// out of the closed sphere; the fast path and the robust traversal must both go beyond. Each ray
// starts in the voxel of a node that splits at 0, at the middle of its other two axes, so it
// meets that node at t = 0 whatever the tree's shape.
TEST(KdTraverse, OriginsADenormalBeforeASplitPlaneGoBeyondIt) {
  const Scene scene = test::icosphere_scene(3, {0, 0, 0}, 1.0f);
  const KdTree tree = build_kdtree(scene, BuildSettings{});
  struct Pending {
    uint32_t node;
    detail::Box3 voxel;
  };
  std::vector<Pending> pending{{0, detail::box_of(tree.bounds)}};
  std::vector<RayRecord> rays;
  std::vector<bool> inside;  // the origin well inside the sphere: the ray must hit it
  while (!pending.empty()) {
    const Pending item = pending.back();
    pending.pop_back();
    const KdNode node = tree.nodes[item.node];
    if (kd_node_is_leaf(node)) continue;
    const int axis = static_cast<int>(kd_node_axis(node));
    const float split = kd_node_split(node);
    if (!kd_node_below_empty(node)) pending.push_back({item.node + 1, detail::below_plane(item.voxel, axis, split)});
    if (!kd_node_above_empty(node))
      pending.push_back({kd_node_far_child(node), detail::above_plane(item.voxel, axis, split)});
    if (split != 0.0f) continue;
    for (const float side : {-1.0f, 1.0f}) {
      for (const float length : {2.0f, 1024.0f, 1e20f}) {
        float origin[3];
        for (int k = 0; k < 3; ++k) origin[k] = 0.5f * (item.voxel.min[k] + item.voxel.max[k]);
        origin[axis] = -side * 1.40129846e-45f;
        // The other components non-zero, for the fast path.
        float direction[3] = {0.01f * length, -0.02f * length, 0.03f * length};
        direction[axis] = side * length;
        rays.push_back(RayRecord{origin[0], origin[1], origin[2], direction[0], direction[1], direction[2], 0, INFINITY});
        inside.push_back(origin[0] * origin[0] + origin[1] * origin[1] + origin[2] * origin[2] < 0.8f);
      }
    }
  }
  ASSERT_NE(std::count(inside.begin(), inside.end(), true), 0) << "the sphere's tree splits at 0 nowhere inside it";
  const TraceOptions ways[] = {{0, TraversalStack::Short, TraversalPath::FastWhereSafe, true},
                               {0, TraversalStack::Short, TraversalPath::FastWhereSafe, false},
                               {0, TraversalStack::Full, TraversalPath::FastWhereSafe, false},
                               {0, TraversalStack::Short, TraversalPath::Robust, false}};
  for (const TraceOptions& way : ways) {
    std::vector<HitRecord> hits;
    trace_closest(tree, rays, hits, way);
    for (size_t i = 0; i < rays.size(); ++i) {
      if (inside[i]) {
        EXPECT_NE(hits[i].triangle, KD_NO_HIT) << "ray " << i << " escaped the sphere";
      }
      EXPECT_TRUE(same_hit_or_tie(hits[i], test::brute_force_float(scene, rays[i]))) << "ray " << i;
    }
  }
}

TEST(KdTraverse, RaysFromInsideTheClosedBunnyNeverEscape) {
  std::string path;
  KDRAY_CORPUS_FILE(path, "bunny/bunny_vn_euclid.ply");
  const Scene scene = test::mesh_file(path);
  // Inside: halfway between where a ray through the middle enters the mesh and leaves it.
  const Bounds bounds = scene_bounds(scene);
  RayRecord probe{bounds.min.x - 1.0f, 0.5f * (bounds.min.y + bounds.max.y), 0.5f * (bounds.min.z + bounds.max.z),
                  1, 0, 0, 0, INFINITY};
  const float enter = test::brute_force_float(scene, probe).t;
  probe.tmin = enter;
  const float leave = test::brute_force_float(scene, probe).t;
  ASSERT_TRUE(std::isfinite(enter) && std::isfinite(leave));
  const Vec3 inside{probe.ox + 0.5f * (enter + leave), probe.oy, probe.oz};
  expect_no_escape(scene, inside, scaled(1000000));
}

}  // namespace
}  // namespace kdray
