// Reproducible ray sets for tests and benchmarks (fixed seeds give the same rays on every
// machine: the generator is our own splitmix64, not a standard-library distribution).
#pragma once

#include <kdray/kdtree.h>
#include <kdray/scene.h>

#include <kernels/kd_types.h>

#include <cstddef>
#include <cstdint>
#include <vector>

namespace kdray {

// One ray through the centre of each pixel of the scene's first camera (a camera framing the
// bounds from +z when it has none), row by row from the top; tmin 0, tmax +inf.
std::vector<RayRecord> camera_rays(const Scene& scene, uint32_t width, uint32_t height);

// Origins uniform on the bounding sphere of `bounds`, each aimed at a uniform random point in
// the box (the benchmark's "random rays").
std::vector<RayRecord> random_rays(const Bounds& bounds, size_t count, uint64_t seed);

// The numerically hard cases, in equal shares: axis-aligned rays with +0/-0 components,
// origins exactly on split planes of `tree`, rays lying in split planes, rays aimed at
// vertices, rays aimed at points on edges, axis-aligned rays through vertices, segments from
// a triangle to a point in the box as shadow rays are (the direction unnormalised and scaled,
// tmax 1 over the scale), and directions of magnitude 2 to 2^40 from origins one float off a
// split plane, or at or near 0, on one axis.
std::vector<RayRecord> hard_case_rays(const Scene& scene, const KdTree& tree, size_t count, uint64_t seed);

// Rays from `origin` aimed, in turn, at a vertex, at a point on an edge and at a random
// point inside a triangle of the scene (for "rays from inside a closed mesh never escape").
std::vector<RayRecord> rays_toward_surface(const Scene& scene, const Vec3& origin, size_t count, uint64_t seed);

}  // namespace kdray
