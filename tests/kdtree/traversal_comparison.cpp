#include "traversal_comparison.h"

#include "test_scenes.h"
#include "traversal_variant.h"

#include <kdray/ray_sets.h>

#include <icosphere.h>

#include <gtest/gtest.h>

#include <cstring>

namespace kdray::test {

void expect_closest_matches_one_ray_at_a_time(const KdTree& tree, const std::vector<RayRecord>& rays,
                                              ClosestTrace trace, const std::string& name, const std::string& what) {
  const TraversalArrays arrays = traversal_arrays(tree);
  std::vector<HitRecord> expected(rays.size()), actual(rays.size());
  detail::traversal_short_stack().closest(arrays, rays.data(), expected.data(), rays.size());
  trace(arrays, rays.data(), actual.data(), rays.size());
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

DeepTree deep_tree_and_rays() {
  const Scene scene = icosphere_scene(5, {0, 0, 0}, 1.0f);
  DeepTree deep{build_kdtree(scene, BuildSettings{}), random_rays(scene_bounds(scene), 20000, 41)};
  std::vector<HitRecord> counted;
  const TraversalWork work = count_traversal_work(deep.tree, deep.rays, counted);
  EXPECT_GT(work.fast_path_restarts, 0u) << "some rays must overflow the short stack";
  return deep;
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
