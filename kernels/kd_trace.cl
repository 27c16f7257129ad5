/* Closest hits for a buffer of rays (kdtrace --device opencl, and the kernel-vs-CPU test).
 * Persistent threads: each work-item fetches its own batch of rays from a global atomic counter
 * until none are left (GUIDE section 4). */
#define KD_EMPTY_LEAF_BITS
#include "kd_traverse.h"

#define KD_TRACE_BATCH 32u

__kernel void kd_trace_closest(__global const KdNode* nodes, __global const kd_u32* empty_leaves,
                               __global const kd_u32* leaf_triangles,
                               __global const float* triangle_vertices, float4 bounds_min, float4 bounds_max, __global const RayRecord* rays,
                               uint ray_count, __global HitRecord* hits, __global uint* next_ray) {
  const KdSceneView scene = kd_scene_view(nodes, empty_leaves, leaf_triangles, triangle_vertices, bounds_min.x,
                                          bounds_min.y, bounds_min.z, bounds_max.x, bounds_max.y, bounds_max.z);
  for (;;) {
    uint first = atomic_add(next_ray, KD_TRACE_BATCH);
    if (first >= ray_count) break;
    uint end = min(first + KD_TRACE_BATCH, ray_count);
    for (uint i = first; i < end; ++i) hits[i] = kd_intersect_closest(&scene, rays[i]);
  }
}
