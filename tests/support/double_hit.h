// The test suites' one exact triangle test: a ray against a triangle computed in double
// precision from the same float inputs the kernels read, the oracle that traversal and
// stability tests judge float hits by.
#pragma once

#include <kdray/scene.h>

#include <kernels/kd_types.h>

#include <cstdint>

namespace kdray::test {

// `margin` is the smallest barycentric coordinate (negative outside, near 0 where the ray grazes
// an edge). `uncertainty` is how far off a float test's margin may be for this ray and
// triangle: it grows with the origin's distance relative to the triangle's size and as the ray
// turns parallel to the triangle. A ray in the triangle's plane is `parallel` and never hits.
struct DoubleHit {
  bool parallel = true;
  bool hit = false;               // not parallel, margin >= 0 and tmin < t < tmax
  uint32_t triangle = KD_NO_HIT;  // the triangle tested, unless parallel
  double t = 0;
  double margin = -1;
  double uncertainty = 0;
  double inverse_cosine = 1;  // 1 / |cos(angle between ray and normal)|: how ill-conditioned t is

  bool clearly_inside() const { return !parallel && margin > uncertainty; }
  bool possibly_inside() const { return !parallel && margin >= -uncertainty; }
};

// One triangle against one ray; t and margin are filled, hit or not, unless the ray is parallel.
DoubleHit intersect_double(const Scene& scene, uint32_t triangle, const RayRecord& ray);

}  // namespace kdray::test
