/* The fast path. The robust traversal's care is for rare rays, and every inner step paid for
 * it. So a ray none of it can touch takes a fast path (kd_traverse_fast), decided once at setup
 * (kd_ray_takes_fast_path), that makes the very decisions of the robust traversal with fewer
 * instructions, and gives its hits bit for bit:
 * - no direction component is 0, so the ray lies in no split plane and one pass is all the
 *   robust traversal makes;
 * - near and far follow the direction's signs, set once per ray: for t_split > 0 they are the
 *   robust traversal's origin sides, and for t_split <= 0 the robust traversal visits the side
 *   the ray moves into (the origin's side, or where t_split is 0, the side the direction points
 *   to), the one it enters second. Both far-only conditions (t_split <= 0 and
 *   t_split < t_min * (1 - KD_T_EPSILON)) are one comparison with the bound raised to the
 *   smallest positive float;
 * - the widened bounds t_min * (1 - KD_T_EPSILON) and t_max * (1 + KD_T_EPSILON) are computed
 *   when the segment changes, not at every node;
 * - a plain stack of KD_SHORT_STACK_SIZE entries: until it overflows, the ring never drops an
 *   entry and the two traversals are step for step the same. A ray that would overflow it is
 *   traced again from the start by the robust traversal (where the ring restarts).
 */
#ifndef KD_TRAVERSE_FAST_H
#define KD_TRAVERSE_FAST_H

#include "kd_scene_view.h"

#ifndef KD_TRAVERSAL_ROBUST_ONLY
/* Whether the fast path gives this ray the robust traversal's hits (the header comment): no zero
 * direction component. */
KD_INLINE int kd_ray_takes_fast_path(const KdRay* ray) {
  return ray->dir[0] != 0.0f && ray->dir[1] != 0.0f && ray->dir[2] != 0.0f;
}

/* t_split below this bound, with t_min's slack, is far only; raised to the smallest positive
 * float, the bound also sends t_split <= 0 to the side the ray moves into. */
KD_INLINE float kd_fast_far_bound(float t_min) { return kd_maxf(t_min * (1.0f - KD_T_EPSILON), 1.40129846e-45f); }

/* Bit k: the ray runs down axis k, so it meets the node above a split before the one below. */
KD_INLINE kd_u32 kd_ray_descending_axes(const KdRay* ray) {
  return (ray->dir[0] < 0.0f ? 1u : 0u) | (ray->dir[1] < 0.0f ? 2u : 0u) | (ray->dir[2] < 0.0f ? 4u : 0u);
}

#define KD_FAST_OVERFLOW 2

/* kd_traverse_pass for a ray that kd_ray_takes_fast_path, with a plain stack, through the subtree
 * at node_index over the ray's segment [t_min, t_max] there (the root and the segment in the root
 * voxel for a whole trace; the host's packets hand a lane over at any node, with best its hit so
 * far): returns 1 when any_hit is set and a hit was found, 0 when done, KD_FAST_OVERFLOW when the
 * stack overflowed (best is then partial, and the ray must be traced robustly). */
KD_INLINE int kd_traverse_fast_from(const KdSceneView* scene, const KdRay* ray, kd_u32 node_index, float t_min,
                                    float t_max, HitRecord* best, int any_hit) {
  KdStackEntry stack[KD_SHORT_STACK_SIZE];
  int stack_count = 0;
  const kd_u32 descending = kd_ray_descending_axes(ray);
  for (;;) {
    float far_below = kd_fast_far_bound(t_min);
    float near_above = t_max * (1.0f + KD_T_EPSILON);
    KdNode node = scene->nodes[node_index];
    int empty_leaf = 0;
    while (!kd_node_is_leaf(node)) {
      KD_COUNT(scene, inner_steps, 1);
      const kd_u32 axis = kd_node_axis(node);
      const float t_split = (kd_node_split(node) - ray->org[axis]) * ray->inv_dir[axis];
      const kd_u32 below = node_index + 1u;
      const kd_u32 above = kd_node_far_child(node);
      KD_PREFETCH_NODE(scene->nodes + above);
      const kd_u32 down = (descending >> axis) & 1u;
      const kd_u32 first = down ? above : below;
      const kd_u32 second = down ? below : above;
      /* The header's empty bit of the first child, and of the second. Picked here by selects
       * rather than through kd_node_child and kd_node_child_empty: GCC makes of those a longer
       * step (bench/LOG.md, ".kdtree version 5"), and this loop is most of a trace. */
      const kd_u32 first_bit = down ? KD_ABOVE_EMPTY : KD_BELOW_EMPTY;
      const kd_u32 first_empty = node.header & first_bit;
      const kd_u32 second_empty = node.header & (first_bit ^ (KD_BELOW_EMPTY | KD_ABOVE_EMPTY));
      if (t_split < far_below) {
        if (second_empty) {
          empty_leaf = 1;
          break;
        }
        node_index = second;
      } else if (t_split > near_above) {
        if (first_empty) {
          empty_leaf = 1;
          break;
        }
        node_index = first;
      } else {
        const float t_boundary = kd_minf(kd_maxf(t_split, t_min), t_max);
        if (first_empty) {
          /* Nothing near: the far segment comes next, as if popped at once (it is a node: a
           * node has at most one empty child). */
          if (!kd_segment_may_precede(t_boundary, best)) {
            empty_leaf = 1;
            break;
          }
          node_index = second;
          t_min = t_boundary;
          far_below = kd_fast_far_bound(t_min);
        } else {
          if (!second_empty) {
            if (stack_count == KD_SHORT_STACK_SIZE) return KD_FAST_OVERFLOW;
            KD_PREFETCH_NODE(scene->nodes + second);
            stack[stack_count].node = second;
            stack[stack_count].t_min = t_boundary;
            stack[stack_count].t_max = t_max;
            ++stack_count;
          }
          node_index = first;
          t_max = t_boundary;
          near_above = t_max * (1.0f + KD_T_EPSILON);
        }
      }
      node = scene->nodes[node_index];
    }
    if (!empty_leaf && kd_intersect_leaf(scene, ray, node, best, any_hit) && any_hit) return 1;
    for (;;) {
      if (stack_count == 0) return 0;
      --stack_count;
      if (kd_segment_may_precede(stack[stack_count].t_min, best)) break;
    }
    node_index = stack[stack_count].node;
    t_min = stack[stack_count].t_min;
    t_max = stack[stack_count].t_max;
  }
}

/* The whole trace: from the root over the segment in the root voxel. */
KD_INLINE int kd_traverse_fast(const KdSceneView* scene, const KdRay* ray, float scene_t_min, float scene_t_max,
                               HitRecord* best, int any_hit) {
  return kd_traverse_fast_from(scene, ray, 0u, scene_t_min, scene_t_max, best, any_hit);
}
#endif

#endif /* KD_TRAVERSE_FAST_H */
