/* The scene as the traversal reads it (KdSceneView), its leaf test and the pieces that both
 * traversals (kd_traverse_robust.h, kd_traverse_fast.h) share; kernels/kd_traverse.h is the
 * entry point and says what the traversal promises. */
#ifndef KD_SCENE_VIEW_H
#define KD_SCENE_VIEW_H

#include "kd_compat.h"
#include "kd_geometry.h"
#include "kd_types.h"

#ifndef KD_SHORT_STACK_SIZE
#define KD_SHORT_STACK_SIZE 8
#endif

/* Floats of one triangle's three corners (the shading copy of the corners, one triangle after
 * another in scene order). */
#define KD_TRIANGLE_FLOATS 9u

/* Work counters of one traversal (kdtrace --json, bench/): compiled in only where
 * KD_TRAVERSAL_COUNTERS is defined (a CPU build of its own), so the timed code has none. */
#ifdef KD_TRAVERSAL_COUNTERS
typedef struct KdTraversalCounters {
  unsigned long long inner_steps, leaves, triangle_tests;
  unsigned long long fast_path_rays, fast_path_restarts; /* restarts: traced again, robustly */
} KdTraversalCounters;
#define KD_COUNT(scene, field, n) ((scene)->counters->field += (n))
#else
#define KD_COUNT(scene, field, n) ((void)0)
#endif

typedef struct KdSceneView {
  KD_GLOBAL const KdNode* nodes;
  KD_GLOBAL const kd_u32* leaf_blocks; /* kd_types.h */
  float bounds_min[3], bounds_max[3];
#ifdef KD_TRAVERSAL_COUNTERS
  KdTraversalCounters* counters;
#endif
} KdSceneView;

/* The one way a KdSceneView is made, by the CPU builds and by every kernel, so a field added to
 * it is set everywhere. The root voxel comes as six floats because the callers hold it in
 * different forms and address spaces (float4 kernel arguments, __global parameter blocks, host
 * arrays). Counters start null: a counting build points them at its own totals. */
KD_INLINE KdSceneView kd_scene_view(KD_GLOBAL const KdNode* nodes, KD_GLOBAL const kd_u32* leaf_blocks, float min_x,
                                    float min_y, float min_z, float max_x, float max_y, float max_z) {
  KdSceneView view;
  view.nodes = nodes;
  view.leaf_blocks = leaf_blocks;
  view.bounds_min[0] = min_x;
  view.bounds_min[1] = min_y;
  view.bounds_min[2] = min_z;
  view.bounds_max[0] = max_x;
  view.bounds_max[1] = max_y;
  view.bounds_max[2] = max_z;
#ifdef KD_TRAVERSAL_COUNTERS
  view.counters = 0;
#endif
  return view;
}

typedef struct KdStackEntry {
  kd_u32 node;
  float t_min, t_max;
} KdStackEntry;

/* A hit at t by `triangle` replaces `best` when it is closer, or as close and of a smaller
 * triangle index: the closest hit is then the smallest (t, triangle) pair, whatever order the
 * leaves are visited in and whichever leaf holds which triangle. best->t starts as the ray's
 * tmax with no triangle, and that end of the interval stays open. */
KD_INLINE int kd_hit_precedes(float t, kd_u32 triangle, const HitRecord* best) {
  return t < best->t || (t == best->t && triangle < best->triangle && best->triangle != KD_NO_HIT);
}

/* Tests the leaf's triangles against the ray and `hit`; returns 1 if hit changed. The block's
 * words are read as float where they are corners (the file's and the device buffer's bytes
 * have no other type). */
KD_HOT_INLINE int kd_intersect_leaf(const KdSceneView* scene, const KdRay* ray, KdNode leaf, HitRecord* hit,
                                    int any_hit) {
  int found = 0;
  const kd_u32 count = kd_leaf_count(leaf);
  KD_GLOBAL const kd_u32* block = scene->leaf_blocks + kd_leaf_first(leaf);
  KD_GLOBAL const float* corners = (KD_GLOBAL const float*)(block + 2u * count);
  KD_COUNT(scene, leaves, 1);
  KD_COUNT(scene, triangle_tests, count);
  for (kd_u32 i = 0; i < count; ++i) {
    const kd_u32 numbers = block[count + i];
    KD_GLOBAL const float* page = corners + 3u * KD_LEAF_PAGE_CORNERS * (i / KD_LEAF_PAGE_TRIANGLES);
    float t, u, v;
    if (kd_ray_triangle_line(ray, page + 3u * (numbers & KD_LEAF_CORNER_MASK),
                             page + 3u * ((numbers >> KD_LEAF_CORNER_BITS) & KD_LEAF_CORNER_MASK),
                             page + 3u * (numbers >> (2u * KD_LEAF_CORNER_BITS)), &t, &u, &v) &&
        t > ray->tmin && kd_hit_precedes(t, block[i], hit)) {
      hit->t = t;
      hit->triangle = block[i];
      hit->u = u;
      hit->v = v;
      found = 1;
      if (any_hit) return 1;
    }
  }
  return found;
}

/* Relative slack of the t comparisons in the descent (about 8 ulps). */
#define KD_T_EPSILON 9.5367431640625e-07f

/* Whether a pending segment starting at t_start may hold a hit that precedes `best`: one that
 * starts at best->t may hold a tie of a smaller index, and the slack covers a triangle hit on
 * the boundary of two voxels whose t and t_split round apart. t_start = +inf stands for no
 * segment (best->t is +inf until a hit when the ray is unbounded). */
KD_INLINE int kd_segment_may_precede(float t_start, const HitRecord* best) {
  return t_start <= best->t * (1.0f + KD_T_EPSILON) && t_start < INFINITY;
}
/* Hint that a node will be read soon: the far child of a split, read when the near side is
 * done, and on the fast path the above child of every inner node visited (it lies after the
 * whole below subtree, so usually in another cache line; its fetch then starts while the step
 * still decides which child comes next, which a mispredicted branch otherwise waits for).
 * PoCL's CPU devices compile __builtin_prefetch (OpenCL's prefetch() is a no-op there); the
 * host defines KD_PREFETCH_NODES only for them. */
#if !defined(__OPENCL_VERSION__) || defined(KD_PREFETCH_NODES)
#define KD_PREFETCH(address) __builtin_prefetch(address)
#define KD_PREFETCH_NODE(address) KD_PREFETCH(address)
#else
#define KD_PREFETCH(address) ((void)0)
#define KD_PREFETCH_NODE(address) ((void)0)
#endif

#endif /* KD_SCENE_VIEW_H */
