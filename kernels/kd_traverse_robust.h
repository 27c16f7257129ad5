/* The robust traversal, which every ray may take (kd_traverse.h), and where it departs from the
 * letter of the seed, and why:
 * - Ties in t go to the smaller triangle index, so a pending segment that starts at (or within
 *   KD_T_EPSILON of) the best t is still visited: it may hold such a tie.
 * - The comparisons of t_split with t_min and t_max allow KD_T_EPSILON (relative), so a ray
 *   that meets a triangle exactly on a split plane visits the voxels on both sides even when
 *   t_split and the voxel's t interval round differently (a flat voxel's interval is a point).
 * - Where t_split is 0, the near child is the side the ray moves into, not the origin's: where
 *   (split - o_k) * (1 / d_k) underflows (an origin close to the plane for the size of d_k: a
 *   denormal apart with |d_k| >= 2, 1e-20 apart with |d_k| = 1e30) the plane may lie ahead, and
 *   the origin's side alone would let the ray through the whole tree.
 * - A ray lying in a split plane (d_k = 0, o_k = split) can hit triangles that only touch the
 *   plane from either side, so it is traversed once per side: a first pass goes below at such
 *   nodes and records their axes, then one more pass per combination of sides of the recorded
 *   axes (at most 2 axes, as d != 0). Each pass is an ordinary ordered traversal; the closest
 *   hit carries over and prunes later passes.
 * - The stack is a ring: when full, a push overwrites the oldest (shallowest, farthest) entry
 *   and remembers where that lost segment began. When the stack runs empty, traversal restarts
 *   at the root from the earliest lost start. Pushed segments start at the clamped t_split,
 *   never before the current segment, so the restart point never moves back.
 * - A restart that does not advance (more zero-length voxels meet at the restart point s than
 *   the stack holds, e.g. in a flat voxel) visits every leaf touching s once, in node order,
 *   with one root-to-leaf descent per leaf keyed by node index instead of a stack
 *   (kd_visit_point). The round after it is strict: splits at or before s count as far only,
 *   so every push, and with it the next restart point, lies beyond s.
 */
#ifndef KD_TRAVERSE_ROBUST_H
#define KD_TRAVERSE_ROBUST_H

#include "kd_scene_view.h"

#define KD_VISIT_NEAR 1
#define KD_VISIT_FAR 2

/* The visit step of an inner node, the one used by the ordered traversal and by the point
 * visits: which children the part [t_min, t_max] of the ray touches (KD_VISIT_NEAR,
 * KD_VISIT_FAR or both), whether the near child is the above one (the near child holds the
 * origin, or, where t_split is 0, the side the ray moves into: below when d_k <= 0;
 * kd_node_child gives its index) and t_split. Splits at or before far_from count as far only
 * (-INFINITY: none does). A ray lying in the split plane touches above when its axis is set in
 * plane_sides, below otherwise, as the near child only, and the axis is added to
 * *in_plane_axes. */
KD_HOT_INLINE int kd_visit_inner(const KdRay* ray, KdNode node, float t_min, float t_max, float far_from,
                                 int plane_sides, int* in_plane_axes, kd_u32* near_is_above, float* t_split_out) {
  const kd_u32 axis = kd_node_axis(node);
  const float split = kd_node_split(node);
  const float origin = ray->org[axis];
  if (ray->dir[axis] == 0.0f && origin == split) {
    *in_plane_axes |= 1 << axis;
    *near_is_above = (kd_u32)((plane_sides >> axis) & 1);
    *t_split_out = t_min;
    return KD_VISIT_NEAR;
  }
  const float t_split = (split - origin) * ray->inv_dir[axis];
  /* Where t_split is 0, the side the ray moves into: the origin lies on the plane, or so near it
   * for the size of d that the product rounds to 0 (the header comment), and then the ray is on
   * that side at every t > 0 a hit can have. The origin's side there would drop the whole ray
   * when the plane lies (just) ahead. */
  const int below_first = t_split == 0.0f ? ray->dir[axis] <= 0.0f : origin < split;
  *near_is_above = below_first ? 0u : 1u;
  *t_split_out = t_split;
  if (t_split > t_max * (1.0f + KD_T_EPSILON) || t_split <= 0.0f) return KD_VISIT_NEAR;
  if (t_split < t_min * (1.0f - KD_T_EPSILON) || t_split <= far_from) return KD_VISIT_FAR;
  return KD_VISIT_NEAR | KD_VISIT_FAR;
}

/* Visits, in node order, every leaf whose voxel the ray touches at t = s (the visit step with
 * the interval [s, s]), without a stack: each descent from the root takes the first child, in
 * node order, that touches s, is a node and holds a node >= `next`; `bound` is the first node
 * after the current subtree (0xFFFFFFFF: after the whole tree). Returns 1 when any_hit is set
 * and a hit was found. */
KD_INLINE int kd_visit_point(const KdSceneView* scene, const KdRay* ray, float s, int plane_sides,
                             int* in_plane_axes, HitRecord* best, int any_hit) {
  const kd_u32 after_tree = 0xFFFFFFFFu;
  kd_u32 next = 0;
  while (next != after_tree) {
    kd_u32 node_index = 0;
    kd_u32 bound = after_tree;
    KdNode node = scene->nodes[0];
    int dead_end = 0;
    while (!kd_node_is_leaf(node)) {
      KD_COUNT(scene, inner_steps, 1);
      kd_u32 near_is_above;
      float t_split;
      const int visit =
          kd_visit_inner(ray, node, s, s, -INFINITY, plane_sides, in_plane_axes, &near_is_above, &t_split);
      const int touches_below =
          (visit & (near_is_above ? KD_VISIT_FAR : KD_VISIT_NEAR)) != 0 && !kd_node_below_empty(node);
      const int touches_above =
          (visit & (near_is_above ? KD_VISIT_NEAR : KD_VISIT_FAR)) != 0 && !kd_node_above_empty(node);
      const kd_u32 above = kd_node_far_child(node);
      /* The first node after the below subtree: the above child, or the subtree's bound. */
      const kd_u32 below_end = kd_node_above_empty(node) ? bound : above;
      if (touches_below && next < below_end) {
        bound = below_end;
        node_index = node_index + 1u;
      } else if (touches_above && next < bound) {
        node_index = above;
      } else {
        dead_end = 1;
        break;
      }
      node = scene->nodes[node_index];
    }
    /* The last leaf of the tree has bound 0xFFFFFFFF and is found again once visited. */
    if (dead_end || node_index < next) {
      next = bound;
      continue;
    }
    if (kd_intersect_leaf(scene, ray, node, best, any_hit) && any_hit) return 1;
    next = node_index + 1u;
  }
  return 0;
}
/* One ordered traversal of [scene_t_min, scene_t_max]. At nodes whose split plane holds the
 * ray, it goes above on the axes set in plane_sides, below on the others, and adds the axis to
 * *in_plane_axes. Returns 1 when any_hit is set and a hit was found. */
KD_INLINE int kd_traverse_pass(const KdSceneView* scene, const KdRay* ray, float scene_t_min, float scene_t_max,
                               int plane_sides, int* in_plane_axes, HitRecord* best, int any_hit) {
  KdStackEntry stack[KD_SHORT_STACK_SIZE];
#ifndef __OPENCL_VERSION__
  /* Only slots already pushed are ever read; initialising them lets C++ compilers see that. The
   * kernel skips it: eight stores per ray were 2% of a render's instructions. */
  for (int i = 0; i < KD_SHORT_STACK_SIZE; ++i) stack[i].t_min = INFINITY;
#endif
  int stack_top = 0;   /* next free slot, modulo the size */
  int stack_count = 0; /* valid entries below stack_top */
  float lost_t_min = INFINITY; /* earliest start of an overwritten entry in this round */
  float round_start = scene_t_min;
  float far_from = -INFINITY; /* a strict round: round_start */
  kd_u32 node_index = 0;
  float t_min = scene_t_min;
  float t_max = scene_t_max;

  for (;;) {
    KdNode node = scene->nodes[node_index];
    int empty_leaf = 0; /* reached a child its parent marks empty */
    while (!kd_node_is_leaf(node)) {
      KD_COUNT(scene, inner_steps, 1);
      kd_u32 near_is_above;
      float t_split;
      const int visit =
          kd_visit_inner(ray, node, t_min, t_max, far_from, plane_sides, in_plane_axes, &near_is_above, &t_split);
      const kd_u32 near_child = kd_node_child(node, node_index, near_is_above);
      const kd_u32 far_child = kd_node_child(node, node_index, near_is_above ^ 1u);
      const kd_u32 near_empty = kd_node_child_empty(node, near_is_above);
      const kd_u32 far_empty = kd_node_child_empty(node, near_is_above ^ 1u);
      if (visit == KD_VISIT_NEAR) {
        if (near_empty) {
          empty_leaf = 1;
          break;
        }
        node_index = near_child;
      } else if (visit == KD_VISIT_FAR) {
        if (far_empty) {
          empty_leaf = 1;
          break;
        }
        node_index = far_child;
      } else {
        const float t_boundary = kd_minf(kd_maxf(t_split, t_min), t_max);
        if (near_empty) {
          /* Nothing near: the far segment comes next, as if popped at once (it is a node: a
           * node has at most one empty child). */
          if (!kd_segment_may_precede(t_boundary, best)) {
            empty_leaf = 1;
            break;
          }
          node_index = far_child;
          t_min = t_boundary;
        } else {
          if (!far_empty) {
            KD_PREFETCH_NODE(scene->nodes + far_child);
            if (stack_count == KD_SHORT_STACK_SIZE)
              lost_t_min = kd_minf(lost_t_min, stack[stack_top].t_min);
            else
              ++stack_count;
            stack[stack_top].node = far_child;
            stack[stack_top].t_min = t_boundary;
            stack[stack_top].t_max = t_max;
            stack_top = (stack_top + 1) % KD_SHORT_STACK_SIZE;
          }
          node_index = near_child;
          t_max = t_boundary;
        }
      }
      node = scene->nodes[node_index];
    }
    if (!empty_leaf && kd_intersect_leaf(scene, ray, node, best, any_hit) && any_hit) return 1;

    /* Next segment: the newest pending one that could still hold a preceding hit. */
    int popped = 0;
    while (stack_count > 0) {
      stack_top = (stack_top + KD_SHORT_STACK_SIZE - 1) % KD_SHORT_STACK_SIZE;
      --stack_count;
      if (kd_segment_may_precede(stack[stack_top].t_min, best)) {
        node_index = stack[stack_top].node;
        t_min = stack[stack_top].t_min;
        t_max = stack[stack_top].t_max;
        popped = 1;
        break;
      }
    }
    if (popped) continue;
    /* Stack empty: done unless a lost segment could still hold a preceding hit. */
    if (!kd_segment_may_precede(lost_t_min, best)) return 0;
    const int strict = !(lost_t_min > round_start);
    if (strict &&
        kd_visit_point(scene, ray, round_start, plane_sides, in_plane_axes, best, any_hit))
      return 1;
    far_from = strict ? round_start : -INFINITY;
    const float restart = kd_maxf(lost_t_min, round_start);
    round_start = restart;
    lost_t_min = INFINITY;
    node_index = 0;
    t_min = restart;
    t_max = scene_t_max;
  }
}

#endif /* KD_TRAVERSE_ROBUST_H */
