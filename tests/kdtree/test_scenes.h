// Small scenes built in memory for the k-d tree tests, and brute-force intersection.
#pragma once

#include <kdray/scene.h>

#include <kernels/kd_types.h>

#include <cstdint>
#include <string>
#include <vector>

namespace kdray::test {

// Builders of triangle meshes (material 0 everywhere, content hash computed).
Scene icosphere(int subdivisions, Vec3 centre, float radius);  // closed, shared vertices
Scene box_room();           // Cornell-like: axis-aligned walls and two boxes standing on the floor
Scene triangle_soup(size_t count, uint64_t seed);  // random small triangles in the unit cube
Scene coplanar_grid(int cells);  // a grid of triangles all in the plane z = 0.25
Scene from_triangles(const std::vector<float>& corners);  // 9 floats per triangle
Scene mesh_file(const std::string& path);  // through import_scene

// Closest hit over all triangles with the float test the kernels use. With skip_origin_hits,
// triangles the ray starts on (exact t ~ 0, found at a rounding-sized t > 0 in float) are
// ignored.
HitRecord brute_force_float(const Scene& scene, const RayRecord& ray, bool skip_origin_hits = false);
// True when the hit's triangle contains the ray origin (its exact t is ~0).
bool is_origin_hit(const Scene& scene, const RayRecord& ray, const HitRecord& hit);

// The same watertight test computed entirely in double precision (from the same float inputs).
// margin is the smallest barycentric of the hit (>= 0; near 0 when the ray grazes an edge).
// Hits at t ~ 0 (the triangle the ray starts on) are ignored.
struct DoubleHit {
  bool hit = false;
  double t = 0;
  uint32_t triangle = KD_NO_HIT;
  double margin = 0;
};
DoubleHit brute_force_double(const Scene& scene, const RayRecord& ray);
// The double-precision test for one triangle; margin and t are filled (hit or not) unless the
// ray is parallel to it.
DoubleHit double_test(const Scene& scene, const RayRecord& ray, uint32_t triangle);

}  // namespace kdray::test
