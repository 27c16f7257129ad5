// What the tests of the host's other traversals (lanes, packets) share: the comparison of their
// hits with one ray at a time's, and the bunny's rays from outside and from inside it.
#pragma once

#include <kdray/kdtree.h>
#include <kdray/scene.h>
#include <kdray/traverse.h>

#include <kernels/kd_types.h>

#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

namespace kdray::test {

// A closest-hit traversal of the host (libkdtree/src/traversal_variant.h's form).
using ClosestTrace = void (*)(const TraversalArrays& arrays, const RayRecord* rays, HitRecord* hits, size_t count);

// Traces `rays` one at a time (the short stack) and with `trace`, and expects the same hit records
// byte for byte; a failure names the first ray that differs, with `name` (the scene) and `what`
// (the traversal `trace` is).
void expect_closest_matches_one_ray_at_a_time(const KdTree& tree, const std::vector<RayRecord>& rays,
                                              ClosestTrace trace, const std::string& name, const std::string& what);

// A tessellated sphere's tree, deeper than the short stack, and random rays of which some
// overflow it (expected).
struct DeepTree {
  KdTree tree;
  std::vector<RayRecord> rays;
};
DeepTree deep_tree_and_rays();

// The ray mix (test_scenes.h) of a closed mesh, and as many rays from its bounds' centre toward
// its surface.
std::vector<RayRecord> rays_outside_and_inside(const Scene& scene, const KdTree& tree, size_t count, uint64_t seed);

}  // namespace kdray::test
