// What the tests of the host's other traversals (lanes, packets) share: the comparison of their
// hits with one ray at a time's, and the bunny's rays from outside and from inside it.
#pragma once

#include <kdray/kdtree.h>
#include <kdray/scene.h>

#include <kernels/kd_types.h>

#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

namespace kdray::test {

// Expects `actual` to be `expected` byte for byte, hit by hit; a failure names the first ray that
// differs, with `name` (the scene) and `what` (the traversal traced as `actual`).
void expect_same_hits(const std::vector<HitRecord>& expected, const std::vector<HitRecord>& actual,
                      const std::string& name, const std::string& what);

// The ray mix (test_scenes.h) of a closed mesh, and as many rays from its bounds' centre toward
// its surface.
std::vector<RayRecord> rays_outside_and_inside(const Scene& scene, const KdTree& tree, size_t count, uint64_t seed);

}  // namespace kdray::test
