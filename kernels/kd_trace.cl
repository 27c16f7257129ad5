/* Closest hits for a buffer of rays (kdtrace --device opencl, and the kernel-vs-CPU test).
 * Persistent threads: each work-item fetches its own batch of rays from a global atomic counter
 * until none are left. One ray per work-item, or with KD_TRACE_LANES (CPU devices) 24 per
 * work-item in float8 lanes (kd_traverse_lanes.h). */
#include "kd_trace_args.h"
#include "kd_traverse.h"

/* Rays a work-item takes from the counter at a time: few on a GPU, so that its thousands of
 * work-items share the rays evenly; a CPU's build names more (trace_opencl.cpp), since each of its
 * few work-items' fetches contends for the counter's cache line with the other cores. */
#ifndef KD_TRACE_BATCH
#define KD_TRACE_BATCH 32u
#endif

#define KD_TRACE_BUFFER_ARG(type, name) __global type* name,
#define KD_TRACE_VALUE_ARG(type, name) type name,
__kernel void kd_trace_closest(KD_TRACE_ARGS(KD_TRACE_BUFFER_ARG, KD_TRACE_BUFFER_ARG, KD_TRACE_VALUE_ARG)
                                   __global uint* next_ray) {
  const KdSceneView scene = kd_scene_view(nodes, leaf_blocks, bounds_min.x, bounds_min.y, bounds_min.z,
                                          bounds_max.x, bounds_max.y, bounds_max.z);
  for (;;) {
    uint first = atomic_add(next_ray, KD_TRACE_BATCH);
    if (first >= ray_count) break;
    uint end = min(first + KD_TRACE_BATCH, ray_count);
    for (uint i = first; i < end; ++i) hits[i] = kd_intersect_closest(&scene, rays[i]);
  }
}

#ifdef KD_TRACE_LANES
#include "kd_traverse_lanes.h"

__kernel void kd_trace_closest_lanes(KD_TRACE_ARGS(KD_TRACE_BUFFER_ARG, KD_TRACE_BUFFER_ARG, KD_TRACE_VALUE_ARG)
                                         __global uint* next_ray) {
  const KdSceneView scene = kd_scene_view(nodes, leaf_blocks, bounds_min.x, bounds_min.y, bounds_min.z,
                                          bounds_max.x, bounds_max.y, bounds_max.z);
  KdLaneRays source;
  source.rays = rays;
  source.hits = hits;
  source.next = 0;
  source.end = 0;
  source.counter = next_ray;
  source.count = ray_count;
  source.batch = KD_TRACE_BATCH;
  kd_trace_closest_in_lanes(&scene, &source);
}
#endif
