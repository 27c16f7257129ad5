// Rays that stress the traversal's plane logic, each set checked against brute force in double:
// axis-aligned rays with +0/-0 components, origins exactly on split planes, rays lying in split
// planes and rays grazing edges. Every set runs with the kernels' short stack and with a
// one-entry stack (a restart at nearly every node).
#include "brute_force.h"
#include "generated_scenes.h"

#include <kdray/kdtree.h>
#include <kdray/traverse.h>

#include <gtest/gtest.h>

#include <cmath>
#include <cstring>
#include <random>

namespace {

using kdray::Scene;
using kdray::Vec3;

// A box whose faces lie in split planes (small far triangles make the builder cut the empty
// space off at the faces), an icosphere inside it, and coplanar grid triangles in its faces.
struct HardScene {
  Scene scene;
  kdray::KdTree tree;

  HardScene() {
    scene = kdray::test::make_grid_box(-1.0f, 1.0f, 4);
    kdray::test::append_mesh(scene, kdray::test::icosphere_scene(2, {0, 0, 0}, 0.6f));
    for (float corner : {-3.0f, 3.0f}) {
      const float step = corner < 0 ? 0.01f : -0.01f;
      kdray::test::append_mesh(scene, kdray::test::make_scene({{corner, corner, corner},
                                                                {corner + step, corner, corner},
                                                                {corner, corner + step, corner}},
                                                               {0, 1, 2}));
    }
    tree = kdray::build_kdtree(scene, kdray::BuildSettings{});
  }
};

const HardScene& hard_scene() {
  static const HardScene scene;
  return scene;
}

class Rng {
 public:
  explicit Rng(uint32_t seed) : engine_(seed) {}
  float uniform(float lo, float hi) { return lo + (hi - lo) * float(engine_() >> 8) * (1.0f / 16777216.0f); }
  Vec3 direction() {  // not normalised: the traversal must not care
    return {uniform(-1, 1), uniform(-1, 1), uniform(-1, 1)};
  }
  uint32_t below(uint32_t n) { return engine_() % n; }

 private:
  std::mt19937 engine_;
};

void set_axis(RayRecord& ray, int axis, float origin, float direction) {
  (&ray.ox)[axis] = origin;
  (&ray.dx)[axis] = direction;
}

// Traces with the short stack and with a one-entry stack; both must agree with brute force.
void expect_agreement(const std::vector<RayRecord>& rays) {
  for (kdray::TraversalStack stack : {kdray::TraversalStack::Short, kdray::TraversalStack::Depth1}) {
    SCOPED_TRACE(stack == kdray::TraversalStack::Short ? "short stack" : "depth-1 stack");
    kdray::TraceOptions options;
    options.stack = stack;
    kdray::test::trace_checked(hard_scene().scene, hard_scene().tree, rays, options);
  }
}

// 40 rays of random origin (in the box) and direction for each split plane of the hard scene's
// tree, each then placed against its plane by place(ray, axis, split, index of the ray).
template <typename Place>
std::vector<RayRecord> rays_at_split_planes(uint32_t seed, const Place& place) {
  Rng rng(seed);
  std::vector<RayRecord> rays;
  for (int axis = 0; axis < 3; ++axis) {
    for (float split : kdray::test::split_positions(hard_scene().tree, axis)) {
      for (int i = 0; i < 40; ++i) {
        const Vec3 d = rng.direction();
        RayRecord ray{rng.uniform(-1.5f, 1.5f), rng.uniform(-1.5f, 1.5f), rng.uniform(-1.5f, 1.5f), d.x, d.y, d.z, 0,
                      INFINITY};
        place(ray, axis, split, i);
        rays.push_back(ray);
      }
    }
  }
  return rays;
}

}  // namespace

TEST(SplitPlanes, TheBoxFacesAreSplitPlanes) {
  for (int axis = 0; axis < 3; ++axis) {
    const std::vector<float> splits = kdray::test::split_positions(hard_scene().tree, axis);
    EXPECT_TRUE(std::binary_search(splits.begin(), splits.end(), -1.0f)) << "axis " << axis;
    EXPECT_TRUE(std::binary_search(splits.begin(), splits.end(), 1.0f)) << "axis " << axis;
  }
}

TEST(SplitPlanes, AxisAlignedRaysWithSignedZerosAgreeWithBruteForce) {
  Rng rng(1);
  std::vector<RayRecord> rays;
  for (int i = 0; i < 2000; ++i) {
    const int axis = int(rng.below(3));
    const float sign = rng.below(2) ? 1.0f : -1.0f;
    RayRecord base{rng.uniform(-1.5f, 1.5f), rng.uniform(-1.5f, 1.5f), rng.uniform(-1.5f, 1.5f), 0, 0, 0, 0, INFINITY};
    if (i % 4 == 0) {  // some origins on the grid lines of the faces
      (&base.ox)[(axis + 1) % 3] = 0.5f * float(int(rng.below(5)) - 2);
    }
    (&base.dx)[axis] = sign;
    for (float zero_a : {0.0f, -0.0f}) {
      for (float zero_b : {0.0f, -0.0f}) {
        RayRecord ray = base;
        (&ray.dx)[(axis + 1) % 3] = zero_a;
        (&ray.dx)[(axis + 2) % 3] = zero_b;
        rays.push_back(ray);
      }
    }
  }
  expect_agreement(rays);

  // The sign of a zero component must not change the answer at all.
  std::vector<HitRecord> hits;
  kdray::trace_closest(hard_scene().tree, rays, hits);
  size_t sign_dependent = 0;
  for (size_t i = 0; i < rays.size(); i += 4) {
    for (size_t k = 1; k < 4; ++k) {
      sign_dependent += (hits[i + k].triangle != hits[i].triangle ||
                         std::memcmp(&hits[i + k].t, &hits[i].t, sizeof(float)) != 0) ? 1 : 0;
    }
  }
  EXPECT_EQ(sign_dependent, 0u);
}

TEST(SplitPlanes, OriginsExactlyOnSplitPlanesAgreeWithBruteForce) {
  const std::vector<RayRecord> rays =
      rays_at_split_planes(2, [](RayRecord& ray, int axis, float split, int) { (&ray.ox)[axis] = split; });
  ASSERT_GT(rays.size(), 1000u);
  expect_agreement(rays);
}

TEST(SplitPlanes, RaysLyingInSplitPlanesAgreeWithBruteForce) {
  const std::vector<RayRecord> rays = rays_at_split_planes(3, [](RayRecord& ray, int axis, float split, int i) {
    set_axis(ray, axis, split, i % 2 ? 0.0f : -0.0f);
  });
  ASSERT_GT(rays.size(), 1000u);
  expect_agreement(rays);
}

TEST(SplitPlanes, RaysGrazingEdgesAgreeWithBruteForce) {
  // Each ray passes through a point of an edge of the sphere (or the box), tangent to the
  // surface there: the hardest case for deciding hit or miss.
  const Scene& scene = hard_scene().scene;
  const auto edges = kdray::test::mesh_edges(scene);
  Rng rng(4);
  std::vector<RayRecord> rays;
  for (int i = 0; i < 4000; ++i) {
    const auto [a, b] = edges[rng.below(uint32_t(edges.size()))];
    const Vec3 p = scene.positions[a], q = scene.positions[b];
    const float s = rng.uniform(0, 1);
    const Vec3 point{p.x + s * (q.x - p.x), p.y + s * (q.y - p.y), p.z + s * (q.z - p.z)};
    // Tangent: perpendicular to the position (a sphere normal; for the box, within a face or along an edge).
    const Vec3 r = rng.direction();
    const Vec3 tangent{point.y * r.z - point.z * r.y, point.z * r.x - point.x * r.z, point.x * r.y - point.y * r.x};
    rays.push_back({point.x - 2 * tangent.x, point.y - 2 * tangent.y, point.z - 2 * tangent.z, tangent.x, tangent.y,
                    tangent.z, 0, INFINITY});
  }
  expect_agreement(rays);
}
