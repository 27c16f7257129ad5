/* k-d tree traversal shared by the CPU reference (libkdtree) and the OpenCL kernels.
 * The contract callers rely on:
 *
 *   typedef struct KdSceneView {
 *     KD_GLOBAL const KdNode* nodes;          root at index 0
 *     KD_GLOBAL const kd_u32* leaf_blocks;    each non-empty leaf's block (kd_types.h)
 *     float bounds_min[3], bounds_max[3];      root voxel
 *   } KdSceneView;
 *
 *   HitRecord kd_intersect_closest(const KdSceneView* scene, RayRecord ray);
 *       closest hit with tmin < t < tmax (t=+inf, triangle=KD_NO_HIT on a miss); of two
 *       triangles hit at the same t, the smaller index, so the hit does not depend on the
 *       tree's shape or the order of its nodes
 *   int kd_intersect_any(const KdSceneView* scene, RayRecord ray);
 *       1 if any triangle is hit with tmin < t < tmax (shadow rays)
 *
 * Short stack with restart; KD_SHORT_STACK_SIZE (default below) is a compile-time constant.
 *
 * The algorithm: the ray is clipped to the root voxel; at each inner node
 * t_split = (split - o_k) / d_k; the near child holds the origin (or, where t_split is 0, the
 * side the ray moves into: below when d_k <= 0). t_split > t_max or t_split <= 0: near only;
 * t_split < t_min: far only; otherwise the far child goes on the stack with [t_split, t_max]
 * and the near one is visited with [t_min, t_split]. A hit found in a leaf is final once no
 * pending segment starts before it (for ordered segments: the seed's "t <= the leaf's t_max").
 * One visit step (kd_visit_inner) decides the children of an inner node for the ordered
 * traversal and for the point visits below.
 *
 * The robust traversal (kd_traverse_robust.h) handles every ray, the rare cases included; a
 * ray none of them can touch takes the fast path (kd_traverse_fast.h), decided once at setup,
 * which gives the same hits bit for bit. KD_TRAVERSAL_ROBUST_ONLY compiles the robust
 * traversal alone (for comparisons).
 */
#ifndef KD_TRAVERSE_H
#define KD_TRAVERSE_H

#include "kd_scene_view.h"
#include "kd_traverse_fast.h"
#include "kd_traverse_robust.h"

/* A ray's start, shared by kd_traverse and the lanes (kd_traverse_lanes.h): best is the miss,
 * the ray set up and its segment clipped to the root voxel. Returns 0 when the ray meets no voxel
 * (best is then what to return); else best.t is ray.tmax, so triangle tests only accept closer
 * hits. */
KD_INLINE int kd_traverse_begin(const KdSceneView* scene, RayRecord record, KdRay* ray, float* scene_t_min,
                                float* scene_t_max, HitRecord* best) {
  best->t = INFINITY;
  best->triangle = KD_NO_HIT;
  best->u = 0.0f;
  best->v = 0.0f;
  if (!kd_ray_setup(ray, record.ox, record.oy, record.oz, record.dx, record.dy, record.dz, record.tmin,
                    record.tmax))
    return 0;
  *scene_t_min = record.tmin > 0.0f ? record.tmin : 0.0f;
  *scene_t_max = record.tmax;
  if (!kd_ray_box(ray, scene->bounds_min, scene->bounds_max, scene_t_min, scene_t_max)) return 0;
  best->t = record.tmax;
  return 1;
}

/* The robust traversal of a started ray: one pass per side combination of the split planes it
 * lies in. Side choices in increasing order, each a subset of the axes met so far (which passes
 * may add to): the next one after s is ((s | ~met) + 1) & met, and 0 once all are done. */
KD_INLINE void kd_traverse_robust(const KdSceneView* scene, const KdRay* ray, float scene_t_min, float scene_t_max,
                                  HitRecord* best, int any_hit) {
  int in_plane_axes = 0;
  int plane_sides = 0;
  do {
    if (kd_traverse_pass(scene, ray, scene_t_min, scene_t_max, plane_sides, &in_plane_axes, best, any_hit)) break;
    plane_sides = ((plane_sides | ~in_plane_axes) + 1) & in_plane_axes;
  } while (plane_sides != 0);
  if (best->triangle == KD_NO_HIT) best->t = INFINITY;
}

/* Both entry points: the start, the fast path where it applies, else the robust traversal. */
KD_INLINE HitRecord kd_traverse(const KdSceneView* scene, RayRecord record, int any_hit) {
  HitRecord best;
  KdRay ray;
  float scene_t_min, scene_t_max;
  if (!kd_traverse_begin(scene, record, &ray, &scene_t_min, &scene_t_max, &best)) return best;
#ifndef KD_TRAVERSAL_ROBUST_ONLY
  const int fast = kd_ray_takes_fast_path(&ray);
  KD_COUNT(scene, fast_path_rays, fast);
  if (fast) {
    if (kd_traverse_fast(scene, &ray, scene_t_min, scene_t_max, &best, any_hit) != KD_FAST_OVERFLOW) {
      if (best.triangle == KD_NO_HIT) best.t = INFINITY;
      return best;
    }
    KD_COUNT(scene, fast_path_restarts, 1);
    best.t = record.tmax;
    best.triangle = KD_NO_HIT;
    best.u = 0.0f;
    best.v = 0.0f;
  }
#endif
  kd_traverse_robust(scene, &ray, scene_t_min, scene_t_max, &best, any_hit);
  return best;
}

KD_INLINE HitRecord kd_intersect_closest(const KdSceneView* scene, RayRecord ray) {
  return kd_traverse(scene, ray, 0);
}

KD_INLINE int kd_intersect_any(const KdSceneView* scene, RayRecord ray) {
  return kd_traverse(scene, ray, 1).triangle != KD_NO_HIT;
}

#endif /* KD_TRAVERSE_H */
