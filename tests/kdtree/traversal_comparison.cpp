#include "traversal_comparison.h"

#include "test_scenes.h"

#include <kdray/ray_sets.h>

#include <gtest/gtest.h>

#include <cstring>

namespace kdray::test {

void expect_same_hits(const std::vector<HitRecord>& expected, const std::vector<HitRecord>& actual,
                      const std::string& name, const std::string& what) {
  ASSERT_EQ(expected.size(), actual.size()) << name;
  size_t differing = 0, first = 0, hits = 0;
  for (size_t i = 0; i < expected.size(); ++i) {
    hits += expected[i].triangle != KD_NO_HIT;
    if (std::memcmp(&expected[i], &actual[i], sizeof(HitRecord)) != 0 && differing++ == 0) first = i;
  }
  EXPECT_EQ(differing, 0u) << name << ": " << differing << " of " << expected.size() << " rays differ; first ray "
                           << first << ": one at a time triangle " << expected[first].triangle << " t "
                           << expected[first].t << ", " << what << " triangle " << actual[first].triangle << " t "
                           << actual[first].t;
  EXPECT_GT(hits, expected.size() / 10) << name << ": the rays must hit something to compare";
}

std::vector<RayRecord> rays_outside_and_inside(const Scene& scene, const KdTree& tree, size_t count, uint64_t seed) {
  std::vector<RayRecord> rays = ray_mix(scene, tree, count, seed);
  const Bounds bounds = scene_bounds(scene);
  const Vec3 centre{(bounds.min.x + bounds.max.x) / 2, (bounds.min.y + bounds.max.y) / 2,
                    (bounds.min.z + bounds.max.z) / 2};
  const std::vector<RayRecord> inside = rays_toward_surface(scene, centre, count, seed + 2);
  rays.insert(rays.end(), inside.begin(), inside.end());
  return rays;
}

}  // namespace kdray::test
