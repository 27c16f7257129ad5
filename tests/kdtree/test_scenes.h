// Small scenes built in memory for the k-d tree tests, and brute-force intersection.
#pragma once

#include <kdray/kdtree.h>
#include <kdray/scene.h>

#include <kernels/kd_types.h>

#include <double_hit.h>
#include <icosphere.h>

#include <cstdint>
#include <string>
#include <vector>

namespace kdray::test {

// Builders of triangle meshes (material 0 everywhere, content hash computed); the icosphere is
// the support library's icosphere_scene.
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

// Random rays (`count`), as many hard-case rays (kdray/ray_sets.h) and 64x48 camera rays of the
// scene, in that order: the mix the traversal variants are compared on.
std::vector<RayRecord> ray_mix(const Scene& scene, const KdTree& tree, size_t count, uint64_t seed);

// The scene triangles of the tree's leaves, leaf after leaf in node order.
std::vector<uint32_t> leaf_triangle_indices(const KdTree& tree);
// The tree's nodes as version 4 of the format laid them out: each empty child an empty leaf node
// of its own (header count 0, payload 0), far children renumbered. The shape the builder's
// tests pinned, whatever the file's encoding of empty children.
std::vector<KdNode> nodes_with_empty_leaves(const KdTree& tree);
// Whether two trees have the same node and leaf-block bytes.
bool same_tree_bytes(const KdTree& a, const KdTree& b);

// The closest double-precision hit over all triangles (double_hit.h), ignoring hits at t ~ 0
// (the triangle the ray starts on).
DoubleHit brute_force_double(const Scene& scene, const RayRecord& ray);

}  // namespace kdray::test
