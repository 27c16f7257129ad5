// Watertightness: rays from inside a closed mesh aimed exactly at its vertices and along its
// edges, where two or more triangles meet, must never escape.
#include "brute_force.h"
#include "generated_scenes.h"

#include <kdray/kdtree.h>
#include <kdray/traverse.h>

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <random>

namespace {

using kdray::Scene;
using kdray::Vec3;

constexpr size_t kRayCount = 1000000;

float unit_random(std::mt19937& rng) { return float(rng() >> 8) * (1.0f / 16777216.0f); }

// Rays from origins inside [-inner, inner]^3 (and the centre) to every vertex and to points on
// every edge (midpoints and random points), about kRayCount in all. Each target lies on the
// surface, so the convex mesh is hit exactly once, at t = 1.
std::vector<RayRecord> rays_at_vertices_and_edges(const Scene& scene, float inner) {
  std::vector<Vec3> targets = scene.positions;
  std::mt19937 rng(12345);
  for (const auto& [a, b] : kdray::test::mesh_edges(scene)) {
    const Vec3 p = scene.positions[a], q = scene.positions[b];
    for (float s : {0.5f, unit_random(rng)}) {
      targets.push_back({p.x + s * (q.x - p.x), p.y + s * (q.y - p.y), p.z + s * (q.z - p.z)});
    }
  }
  std::vector<RayRecord> rays;
  rays.reserve(kRayCount + targets.size());
  while (rays.size() < kRayCount) {
    for (const Vec3& target : targets) {
      Vec3 origin{0, 0, 0};
      if (rays.size() >= targets.size()) {  // the first round starts at the centre
        origin = {inner * (2 * unit_random(rng) - 1), inner * (2 * unit_random(rng) - 1),
                  inner * (2 * unit_random(rng) - 1)};
      }
      rays.push_back({origin.x, origin.y, origin.z, target.x - origin.x, target.y - origin.y, target.z - origin.z, 0.0f,
                      INFINITY});
    }
  }
  return rays;
}

// Traces rays aimed at the vertices and edges of `surface`, which is part of `scene`.
void expect_no_escapes(const Scene& scene, const Scene& surface, float inner) {
  const kdray::KdTree tree = kdray::build_kdtree(scene, kdray::BuildSettings{});
  const std::vector<RayRecord> rays = rays_at_vertices_and_edges(surface, inner);
  std::vector<HitRecord> hits;
  kdray::trace_closest(tree, rays, hits);

  size_t escapes = 0, off_target = 0;
  std::vector<std::string> examples;  // what brute force in double says about the first failures
  const double magnitude = kdray::test::scene_magnitude(scene);
  for (size_t i = 0; i < rays.size(); ++i) {
    const bool escaped = hits[i].triangle == KD_NO_HIT;
    const bool wrong_t = !escaped && std::abs(hits[i].t - 1.0f) > 1e-4f;
    escapes += escaped ? 1 : 0;
    off_target += wrong_t ? 1 : 0;
    if ((escaped || wrong_t) && examples.size() < 3) {
      const RayRecord& ray = rays[i];
      char hit_text[64];
      std::snprintf(hit_text, sizeof hit_text, "triangle %u t=%.9g", hits[i].triangle, hits[i].t);
      examples.push_back("ray " + std::to_string(i) + " " + kdray::test::describe_ray(ray) + ": " + hit_text +
                         "; brute force: " + kdray::test::disagreement(scene, ray, hits[i], magnitude));
    }
  }
  for (const std::string& example : examples) ADD_FAILURE() << example;
  EXPECT_GE(rays.size(), kRayCount);
  EXPECT_EQ(escapes, 0u) << "of " << rays.size() << " rays";
  EXPECT_EQ(off_target, 0u) << "hits away from the aimed-at surface point (t != 1)";
}

}  // namespace

TEST(ClosedMesh, IcosphereRaysAtVerticesAndEdgesNeverEscape) {
  const Scene sphere = kdray::test::icosphere_scene(3, {0, 0, 0}, 1.0f);
  ASSERT_EQ(sphere.triangle_count(), 1280u);
  expect_no_escapes(sphere, sphere, 0.5f);
}

TEST(ClosedMesh, BoxWithFacesOnSplitPlanesRaysAtVerticesAndEdgesNeverEscape) {
  // Small far-away triangles make the root voxel larger than the box, so the builder cuts the
  // empty space off exactly at the box's faces: the faces lie in split planes.
  const Scene box = kdray::test::make_grid_box(-1.0f, 1.0f, 4);
  Scene scene = box;
  for (float corner : {-4.0f, 4.0f}) {
    kdray::test::append_mesh(scene, kdray::test::make_scene({{corner, corner, corner},
                                                              {corner + 0.01f * (corner < 0 ? 1 : -1), corner, corner},
                                                              {corner, corner + 0.01f * (corner < 0 ? 1 : -1), corner}},
                                                             {0, 1, 2}));
  }
  const kdray::KdTree tree = kdray::build_kdtree(scene, kdray::BuildSettings{});
  for (int axis = 0; axis < 3; ++axis) {
    const std::vector<float> splits = kdray::test::split_positions(tree, axis);
    EXPECT_TRUE(std::binary_search(splits.begin(), splits.end(), -1.0f)) << "no split at -1 on axis " << axis;
    EXPECT_TRUE(std::binary_search(splits.begin(), splits.end(), 1.0f)) << "no split at +1 on axis " << axis;
  }
  expect_no_escapes(scene, box, 0.9f);
}
