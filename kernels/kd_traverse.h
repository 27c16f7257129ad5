/* k-d tree traversal shared by the CPU reference (libkdtree) and the OpenCL kernels.
 * CONTRACT (implemented by the libkdtree work; callers rely on these names):
 *
 *   typedef struct KdSceneView {
 *     KD_GLOBAL const KdNode* nodes;          root at index 0
 *     KD_GLOBAL const kd_u32* leaf_triangles; leaves are ranges of this array
 *     KD_GLOBAL const kd_u32* indices;        3 per triangle
 *     KD_GLOBAL const float* positions;       3 floats per vertex
 *     float bounds_min[3], bounds_max[3];     root voxel
 *   } KdSceneView;
 *
 *   HitRecord kd_intersect_closest(const KdSceneView* scene, RayRecord ray);
 *       closest hit with tmin < t < tmax (t=+inf, triangle=KD_NO_HIT on a miss)
 *   int kd_intersect_any(const KdSceneView* scene, RayRecord ray);
 *       1 if any triangle is hit with tmin < t < tmax (shadow rays)
 *
 * Short stack with restart; KD_SHORT_STACK_SIZE (default below) is a compile-time constant.
 *
 * The algorithm (GUIDE section 4): the ray is clipped to the root voxel; at each inner node
 * t_split = (split - o_k) / d_k; the near child holds the origin (or, on the plane, the side the
 * ray does not move into: below when d_k <= 0). t_split > t_max or t_split <= 0: near only;
 * t_split < t_min: far only; otherwise the far child goes on the stack with [t_split, t_max]
 * and the near one is visited with [t_min, t_split]. The stack is a ring: when full, a push
 * overwrites the oldest (shallowest) entry. When it runs empty before the ray's segment is
 * done, traversal restarts at the root with t_min = the last leaf's t_max. A hit found in a
 * leaf is final once no pending segment starts before it, which for ordered segments is the
 * seed's rule "t <= the leaf's t_max".
 *
 * Rays lying in a split plane (d_k = 0, o_k = split) give t_split = 0 and go below only; the
 * builder (libkdtree/src/build_common.h) puts triangles that start on a split plane on both
 * sides, so every non-planar triangle touching the plane is found below. Triangles lying in the
 * plane are parallel to such a ray and cannot be hit by it.
 *
 * Restart from the same t twice (possible with a depth-1 stack when several split planes meet
 * exactly at the restart point) switches the next descent to t_split <= t_min => far only, so
 * traversal always advances.
 */
#ifndef KD_TRAVERSE_H
#define KD_TRAVERSE_H

#include "kd_compat.h"
#include "kd_geometry.h"
#include "kd_types.h"

/* The deepest tree any builder writes and read_tree accepts; a stack of this size never
 * overflows, which is the "full stack" variant. */
#define KD_MAX_TREE_DEPTH 64

#ifndef KD_SHORT_STACK_SIZE
#define KD_SHORT_STACK_SIZE 8
#endif

typedef struct KdSceneView {
  KD_GLOBAL const KdNode* nodes;
  KD_GLOBAL const kd_u32* leaf_triangles;
  KD_GLOBAL const kd_u32* indices;
  KD_GLOBAL const float* positions;
  float bounds_min[3], bounds_max[3];
} KdSceneView;

typedef struct KdStackEntry {
  kd_u32 node;
  float t_min, t_max;
} KdStackEntry;

KD_INLINE void kd_load_vertex(const KdSceneView* scene, kd_u32 vertex, float out[3]) {
  out[0] = scene->positions[3u * vertex + 0u];
  out[1] = scene->positions[3u * vertex + 1u];
  out[2] = scene->positions[3u * vertex + 2u];
}

/* Tests the leaf's triangles against (ray.tmin, hit->t); returns 1 if hit->t got smaller. */
KD_INLINE int kd_intersect_leaf(const KdSceneView* scene, const KdRay* ray, KdNode leaf, HitRecord* hit,
                                int any_hit) {
  int found = 0;
  const kd_u32 first = kd_leaf_first(leaf);
  const kd_u32 count = kd_leaf_count(leaf);
  for (kd_u32 i = 0; i < count; ++i) {
    const kd_u32 triangle = scene->leaf_triangles[first + i];
    float a[3], b[3], c[3];
    kd_load_vertex(scene, scene->indices[3u * triangle + 0u], a);
    kd_load_vertex(scene, scene->indices[3u * triangle + 1u], b);
    kd_load_vertex(scene, scene->indices[3u * triangle + 2u], c);
    float t, u, v;
    if (kd_ray_triangle(ray, a, b, c, hit->t, &t, &u, &v)) {
      hit->t = t;
      hit->triangle = triangle;
      hit->u = u;
      hit->v = v;
      found = 1;
      if (any_hit) return 1;
    }
  }
  return found;
}

/* The one traversal loop behind both entry points. hit.t starts at ray.tmax so every
 * triangle test only accepts closer hits. */
KD_INLINE HitRecord kd_traverse(const KdSceneView* scene, RayRecord record, int any_hit) {
  HitRecord hit;
  hit.t = INFINITY;
  hit.triangle = KD_NO_HIT;
  hit.u = 0.0f;
  hit.v = 0.0f;
  KdRay ray;
  if (!kd_ray_setup(&ray, record.ox, record.oy, record.oz, record.dx, record.dy, record.dz,
                    record.tmin, record.tmax))
    return hit;
  float scene_t_min = record.tmin > 0.0f ? record.tmin : 0.0f;
  float scene_t_max = record.tmax;
  if (!kd_ray_box(&ray, scene->bounds_min, scene->bounds_max, &scene_t_min, &scene_t_max)) return hit;

  HitRecord best = hit;
  best.t = record.tmax;
  KdStackEntry stack[KD_SHORT_STACK_SIZE];
  int stack_top = 0;   /* next free slot, modulo the size */
  int stack_count = 0; /* valid entries below stack_top */
  kd_u32 node_index = 0;
  float t_min = scene_t_min;
  float t_max = scene_t_max;
  float last_restart = -INFINITY;
  int strict_descent = 0;

  for (;;) {
    KdNode node = scene->nodes[node_index];
    while (!kd_node_is_leaf(node)) {
      const kd_u32 axis = kd_node_axis(node);
      const float split = kd_node_split(node);
      const float origin = ray.org[axis];
      const float t_split = (split - origin) * ray.inv_dir[axis];
      const int below_first = origin < split || (origin == split && ray.dir[axis] <= 0.0f);
      const kd_u32 below = node_index + 1u;
      const kd_u32 above = kd_node_far_child(node);
      const kd_u32 near_child = below_first ? below : above;
      const kd_u32 far_child = below_first ? above : below;
      if (t_split > t_max || t_split <= 0.0f) {
        node_index = near_child;
      } else if (t_split < t_min || (strict_descent && t_split == t_min)) {
        node_index = far_child;
      } else {
        stack[stack_top].node = far_child;
        stack[stack_top].t_min = t_split;
        stack[stack_top].t_max = t_max;
        stack_top = (stack_top + 1) % KD_SHORT_STACK_SIZE;
        if (stack_count < KD_SHORT_STACK_SIZE) ++stack_count;
        node_index = near_child;
        t_max = t_split;
      }
      node = scene->nodes[node_index];
    }
    strict_descent = 0;
    if (kd_intersect_leaf(scene, &ray, node, &best, any_hit) && any_hit) return best;

    /* Next segment: the newest pending one that could still hold a closer hit. */
    int popped = 0;
    while (stack_count > 0) {
      stack_top = (stack_top + KD_SHORT_STACK_SIZE - 1) % KD_SHORT_STACK_SIZE;
      --stack_count;
      if (stack[stack_top].t_min < best.t) {
        node_index = stack[stack_top].node;
        t_min = stack[stack_top].t_min;
        t_max = stack[stack_top].t_max;
        popped = 1;
        break;
      }
    }
    if (popped) continue;
    /* Stack empty: done unless entries were lost to overflow and the segment goes on. */
    if (t_max >= scene_t_max || t_max >= best.t || !(t_max == t_max)) break;
    strict_descent = t_max == last_restart;
    last_restart = t_max;
    node_index = 0;
    t_min = t_max;
    t_max = scene_t_max;
  }
  if (best.triangle == KD_NO_HIT) best.t = INFINITY;
  return best;
}

KD_INLINE HitRecord kd_intersect_closest(const KdSceneView* scene, RayRecord ray) {
  return kd_traverse(scene, ray, 0);
}

KD_INLINE int kd_intersect_any(const KdSceneView* scene, RayRecord ray) {
  return kd_traverse(scene, ray, 1).triangle != KD_NO_HIT;
}

#endif /* KD_TRAVERSE_H */
