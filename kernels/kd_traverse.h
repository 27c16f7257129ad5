/* k-d tree traversal shared by the CPU reference (libkdtree) and the OpenCL kernels.
 * The contract callers rely on:
 *
 *   typedef struct KdSceneView {
 *     KD_GLOBAL const KdNode* nodes;          root at index 0
 *     KD_GLOBAL const kd_u32* leaf_triangles;  leaves are ranges of this array
 *     KD_GLOBAL const float* leaf_vertices;  KD_TRIANGLE_FLOATS per leaf entry (see below)
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
 * t_split = (split - o_k) / d_k; the near child holds the origin (or, on the plane, the side the
 * ray moves into: below when d_k <= 0). t_split > t_max or t_split <= 0: near only;
 * t_split < t_min: far only; otherwise the far child goes on the stack with [t_split, t_max]
 * and the near one is visited with [t_min, t_split]. A hit found in a leaf is final once no
 * pending segment starts before it (for ordered segments: the seed's "t <= the leaf's t_max").
 * One visit step (kd_visit_inner) decides the children of an inner node for the ordered
 * traversal and for the point visits below.
 *
 * Where this code departs from the letter of the seed, and why:
 * - Ties in t go to the smaller triangle index, so a pending segment that starts at (or within
 *   KD_T_EPSILON of) the best t is still visited: it may hold such a tie.
 * - The comparisons of t_split with t_min and t_max allow KD_T_EPSILON (relative), so a ray
 *   that meets a triangle exactly on a split plane visits the voxels on both sides even when
 *   t_split and the voxel's t interval round differently (a flat voxel's interval is a point).
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

 *
 * All of that is for rare rays, and every inner step paid for it. So a ray none of it can touch
 * takes a fast path (kd_traverse_fast), decided once at setup (kd_ray_takes_fast_path), that
 * makes the very decisions of the robust traversal with fewer instructions, and gives its hits
 * bit for bit:
 * - no direction component is 0, so the ray lies in no split plane and one pass is all the
 *   robust traversal makes;
 * - near and far follow the direction's signs, set once per ray: for t_split > 0 they are the
 *   robust traversal's origin sides, and for t_split <= 0 the robust traversal visits the
 *   origin's side, the one the ray enters second. Both far-only conditions (t_split <= 0 and
 *   t_split < t_min * (1 - KD_T_EPSILON)) are one comparison with the bound raised to the
 *   smallest positive float. That needs t_split = 0 only for an origin on the plane, so every
 *   |direction component| is below 2: (split - o) of two different floats is at least 2^-149,
 *   and times a reciprocal above 1/2 it rounds to no less;
 * - the widened bounds t_min * (1 - KD_T_EPSILON) and t_max * (1 + KD_T_EPSILON) are computed
 *   when the segment changes, not at every node;
 * - a plain stack of KD_SHORT_STACK_SIZE entries: until it overflows, the ring never drops an
 *   entry and the two traversals are step for step the same. A ray that would overflow it is
 *   traced again from the start by the robust traversal (where the ring restarts).
 * KD_TRAVERSAL_ROBUST_ONLY compiles the robust traversal alone (today's code, for comparisons).
 */
#ifndef KD_TRAVERSE_H
#define KD_TRAVERSE_H

#include "kd_compat.h"
#include "kd_geometry.h"
#include "kd_types.h"

#ifndef KD_SHORT_STACK_SIZE
#define KD_SHORT_STACK_SIZE 8
#endif

/* The corners a, b, c of the triangle of leaf entry i (leaf_triangles[i]) are
 * leaf_vertices[KD_TRIANGLE_FLOATS * i + 3 * corner + axis]: copies of the scene's positions
 * gathered once by the host in leaf order, so that the triangles of a leaf are one contiguous
 * read instead of an index load and a 36-byte fetch from elsewhere per triangle. A triangle in
 * several leaves is copied once per leaf: the copy is larger than one per triangle (by the
 * tree's references per triangle), and a ray fetches fewer cache lines. */
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
  KD_GLOBAL const kd_u32* leaf_triangles;
  KD_GLOBAL const float* leaf_vertices;
  float bounds_min[3], bounds_max[3];
#ifdef KD_EMPTY_LEAF_BITS
  KD_GLOBAL const kd_u32* empty_leaves; /* bit n % 32 of word n / 32: node n is an empty leaf */
#endif
#ifdef KD_TRAVERSAL_COUNTERS
  KdTraversalCounters* counters;
#endif
} KdSceneView;

/* The one way a KdSceneView is made, by the CPU builds and by every kernel, so a field added to
 * it is set everywhere. The root voxel comes as six floats because the callers hold it in
 * different forms and address spaces (float4 kernel arguments, __global parameter blocks, host
 * arrays). empty_leaves is kept only where KD_EMPTY_LEAF_BITS is defined (pass 0 elsewhere);
 * counters start null: a counting build points them at its own totals. */
KD_INLINE KdSceneView kd_scene_view(KD_GLOBAL const KdNode* nodes, KD_GLOBAL const kd_u32* empty_leaves,
                                    KD_GLOBAL const kd_u32* leaf_triangles, KD_GLOBAL const float* leaf_vertices,
                                    float min_x, float min_y, float min_z, float max_x, float max_y, float max_z) {
  KdSceneView view;
  view.nodes = nodes;
  view.leaf_triangles = leaf_triangles;
  view.leaf_vertices = leaf_vertices;
  view.bounds_min[0] = min_x;
  view.bounds_min[1] = min_y;
  view.bounds_min[2] = min_z;
  view.bounds_max[0] = max_x;
  view.bounds_max[1] = max_y;
  view.bounds_max[2] = max_z;
#ifdef KD_EMPTY_LEAF_BITS
  view.empty_leaves = empty_leaves;
#else
  (void)empty_leaves;
#endif
#ifdef KD_TRAVERSAL_COUNTERS
  view.counters = 0;
#endif
  return view;
}

/* Empty leaves are most of the leaves a ray meets. Where the host derives a bit per node at
 * load (KD_EMPTY_LEAF_BITS: 1/64 of the node array, so it stays in cache), the traversal skips
 * them without fetching their nodes, which for a far child is usually a cache miss. */
#ifdef KD_EMPTY_LEAF_BITS
#define KD_IS_EMPTY_LEAF(scene, index) (((scene)->empty_leaves[(index) >> 5] >> ((index) & 31u)) & 1u)
#elif defined(KD_EMPTY_LEAF_NODES)
/* Without the bits, the node itself says it (a leaf of no triangles): one load, which for the
 * near child is the one the descent makes next anyway. */
#define KD_IS_EMPTY_LEAF(scene, index) ((scene)->nodes[(index)].header == KD_LEAF_TAG)
#else
#define KD_IS_EMPTY_LEAF(scene, index) 0
#endif

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

/* Tests the leaf's triangles against the ray and `hit`; returns 1 if hit changed. */
KD_HOT_INLINE int kd_intersect_leaf(const KdSceneView* scene, const KdRay* ray, KdNode leaf, HitRecord* hit,
                                    int any_hit) {
  int found = 0;
  const kd_u32 first = kd_leaf_first(leaf);
  const kd_u32 count = kd_leaf_count(leaf);
  KD_COUNT(scene, leaves, 1);
  KD_COUNT(scene, triangle_tests, count);
  for (kd_u32 i = 0; i < count; ++i) {
    const kd_u32 triangle = scene->leaf_triangles[first + i];
    KD_GLOBAL const float* corners = scene->leaf_vertices + KD_TRIANGLE_FLOATS * (first + i);
    float t, u, v;
    if (kd_ray_triangle_line(ray, corners, corners + 3, corners + 6, &t, &u, &v) && t > ray->tmin &&
        kd_hit_precedes(t, triangle, hit)) {
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

/* Relative slack of the t comparisons in the descent (about 8 ulps). */
#define KD_T_EPSILON 9.5367431640625e-07f

/* Whether a pending segment starting at t_start may hold a hit that precedes `best`: one that
 * starts at best->t may hold a tie of a smaller index, and the slack covers a triangle hit on
 * the boundary of two voxels whose t and t_split round apart. t_start = +inf stands for no
 * segment (best->t is +inf until a hit when the ray is unbounded). */
KD_INLINE int kd_segment_may_precede(float t_start, const HitRecord* best) {
  return t_start <= best->t * (1.0f + KD_T_EPSILON) && t_start < INFINITY;
}

#define KD_VISIT_NEAR 1
#define KD_VISIT_FAR 2

/* The visit step of an inner node, the one used by the ordered traversal and by the point
 * visits: which children the part [t_min, t_max] of the ray touches (KD_VISIT_NEAR,
 * KD_VISIT_FAR or both), the near child (it holds the origin, or, with the origin on the
 * plane, the side the ray moves into: below when d_k <= 0), the far child and t_split.
 * Splits at or before far_from count as far only (-INFINITY: none does). A ray lying in the
 * split plane touches above when its axis is set in plane_sides, below otherwise, as the near
 * child only, and the axis is added to *in_plane_axes. */
KD_HOT_INLINE int kd_visit_inner(const KdRay* ray, KdNode node, kd_u32 node_index, float t_min, float t_max,
                                 float far_from, int plane_sides, int* in_plane_axes, kd_u32* near_child,
                                 kd_u32* far_child, float* t_split_out) {
  const kd_u32 axis = kd_node_axis(node);
  const float split = kd_node_split(node);
  const float origin = ray->org[axis];
  const kd_u32 below = node_index + 1u;
  const kd_u32 above = kd_node_far_child(node);
  if (ray->dir[axis] == 0.0f && origin == split) {
    *in_plane_axes |= 1 << axis;
    const int go_above = (plane_sides >> axis) & 1;
    *near_child = go_above ? above : below;
    *far_child = go_above ? below : above;
    *t_split_out = t_min;
    return KD_VISIT_NEAR;
  }
  const float t_split = (split - origin) * ray->inv_dir[axis];
  const int below_first = origin < split || (origin == split && ray->dir[axis] <= 0.0f);
  *near_child = below_first ? below : above;
  *far_child = below_first ? above : below;
  *t_split_out = t_split;
  if (t_split > t_max * (1.0f + KD_T_EPSILON) || t_split <= 0.0f) return KD_VISIT_NEAR;
  if (t_split < t_min * (1.0f - KD_T_EPSILON) || t_split <= far_from) return KD_VISIT_FAR;
  return KD_VISIT_NEAR | KD_VISIT_FAR;
}

/* Visits, in node order, every leaf whose voxel the ray touches at t = s (the visit step with
 * the interval [s, s]), without a stack: each descent from the root takes the first child, in
 * node order, that touches s and holds a node >= `next`; `bound` is the first node after the
 * current subtree (0xFFFFFFFF: after the whole tree). Returns 1 when any_hit is set and a hit
 * was found. */
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
      kd_u32 near_child, far_child;
      float t_split;
      const int visit = kd_visit_inner(ray, node, node_index, s, s, -INFINITY, plane_sides, in_plane_axes,
                                       &near_child, &far_child, &t_split);
      const kd_u32 below = node_index + 1u;
      const kd_u32 above = kd_node_far_child(node);
      const int touches_below = (visit & (near_child == below ? KD_VISIT_NEAR : KD_VISIT_FAR)) != 0;
      const int touches_above = (visit & (near_child == below ? KD_VISIT_FAR : KD_VISIT_NEAR)) != 0;
      if (touches_below && next < above) {
        bound = above;
        node_index = below;
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

/* Hint that a node will be read soon: the far child of a split, read when the near side is
 * done, and on the fast path the above child of every inner node visited (it lies after the
 * whole below subtree, so usually in another cache line; its fetch then starts while the step
 * still decides which child comes next, which a mispredicted branch otherwise waits for).
 * PoCL's CPU devices compile __builtin_prefetch (OpenCL's prefetch() is a no-op there); the
 * host defines KD_PREFETCH_NODES only for them. */
#if !defined(__OPENCL_VERSION__) || defined(KD_PREFETCH_NODES)
#define KD_PREFETCH_NODE(address) __builtin_prefetch(address)
#else
#define KD_PREFETCH_NODE(address) ((void)0)
#endif

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
    int empty_leaf = 0; /* reached a leaf known to be empty, without fetching it */
    while (!kd_node_is_leaf(node)) {
      KD_COUNT(scene, inner_steps, 1);
      kd_u32 near_child, far_child;
      float t_split;
      const int visit = kd_visit_inner(ray, node, node_index, t_min, t_max, far_from, plane_sides, in_plane_axes,
                                       &near_child, &far_child, &t_split);
      if (visit == KD_VISIT_NEAR) {
        node_index = near_child;
      } else if (visit == KD_VISIT_FAR) {
        node_index = far_child;
      } else {
        const float t_boundary = kd_minf(kd_maxf(t_split, t_min), t_max);
        if (KD_IS_EMPTY_LEAF(scene, near_child)) {
          /* Nothing near: the far segment comes next, as if popped at once. */
          if (!kd_segment_may_precede(t_boundary, best)) {
            empty_leaf = 1;
            break;
          }
          node_index = far_child;
          t_min = t_boundary;
        } else {
          if (!KD_IS_EMPTY_LEAF(scene, far_child)) {
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
      if (KD_IS_EMPTY_LEAF(scene, node_index)) {
        empty_leaf = 1;
        break;
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

#ifndef KD_TRAVERSAL_ROBUST_ONLY
/* Whether the fast path gives this ray the robust traversal's hits (the header comment): no zero
 * direction component, none of magnitude 2 or more. */
KD_INLINE int kd_ray_takes_fast_path(const KdRay* ray) {
  const float x = kd_absf(ray->dir[0]), y = kd_absf(ray->dir[1]), z = kd_absf(ray->dir[2]);
  return x > 0.0f && y > 0.0f && z > 0.0f && x < 2.0f && y < 2.0f && z < 2.0f;
}

/* t_split below this bound, with t_min's slack, is far only; raised to the smallest positive
 * float, the bound also sends t_split <= 0 to the origin's side. */
KD_INLINE float kd_fast_far_bound(float t_min) { return kd_maxf(t_min * (1.0f - KD_T_EPSILON), 1.40129846e-45f); }

#define KD_FAST_OVERFLOW 2

/* kd_traverse_pass for a ray that kd_ray_takes_fast_path, with a plain stack: returns 1 when
 * any_hit is set and a hit was found, 0 when done, KD_FAST_OVERFLOW when the stack overflowed
 * (best is then partial, and the ray must be traced robustly). */
KD_INLINE int kd_traverse_fast(const KdSceneView* scene, const KdRay* ray, float scene_t_min, float scene_t_max,
                               HitRecord* best, int any_hit) {
  KdStackEntry stack[KD_SHORT_STACK_SIZE];
  int stack_count = 0;
  /* Bit k: the ray runs down axis k, so it meets the node above a split before the one below. */
  const kd_u32 descending = (ray->dir[0] < 0.0f ? 1u : 0u) | (ray->dir[1] < 0.0f ? 2u : 0u) |
                            (ray->dir[2] < 0.0f ? 4u : 0u);
  kd_u32 node_index = 0;
  float t_min = scene_t_min;
  float t_max = scene_t_max;
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
      const int down = (descending >> axis) & 1u;
      const kd_u32 first = down ? above : below;
      const kd_u32 second = down ? below : above;
      if (t_split < far_below) {
        node_index = second;
      } else if (t_split > near_above) {
        node_index = first;
      } else {
        const float t_boundary = kd_minf(kd_maxf(t_split, t_min), t_max);
        if (KD_IS_EMPTY_LEAF(scene, first)) {
          if (!kd_segment_may_precede(t_boundary, best)) {
            empty_leaf = 1;
            break;
          }
          node_index = second;
          t_min = t_boundary;
          far_below = kd_fast_far_bound(t_min);
        } else {
          if (!KD_IS_EMPTY_LEAF(scene, second)) {
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
      if (KD_IS_EMPTY_LEAF(scene, node_index)) {
        empty_leaf = 1;
        break;
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
#endif

/* Both entry points: setup, clipping to the root voxel, the fast path where it applies, else one
 * pass per side combination of split planes the ray lies in. best.t starts at ray.tmax so
 * triangle tests only accept closer hits. */
KD_INLINE HitRecord kd_traverse(const KdSceneView* scene, RayRecord record, int any_hit) {
  HitRecord best;
  best.t = INFINITY;
  best.triangle = KD_NO_HIT;
  best.u = 0.0f;
  best.v = 0.0f;
  KdRay ray;
  if (!kd_ray_setup(&ray, record.ox, record.oy, record.oz, record.dx, record.dy, record.dz,
                    record.tmin, record.tmax))
    return best;
#ifndef KD_TRAVERSAL_ROBUST_ONLY
  const int fast = kd_ray_takes_fast_path(&ray);
  KD_COUNT(scene, fast_path_rays, fast);
#endif
  float scene_t_min = record.tmin > 0.0f ? record.tmin : 0.0f;
  float scene_t_max = record.tmax;
  if (!kd_ray_box(&ray, scene->bounds_min, scene->bounds_max, &scene_t_min, &scene_t_max)) return best;
  best.t = record.tmax;
#ifndef KD_TRAVERSAL_ROBUST_ONLY
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
  /* Side choices in increasing order, each a subset of the axes met so far (which passes may
   * add to): the next one after s is ((s | ~met) + 1) & met, and 0 once all are done. */
  int in_plane_axes = 0;
  int plane_sides = 0;
  do {
    if (kd_traverse_pass(scene, &ray, scene_t_min, scene_t_max, plane_sides, &in_plane_axes, &best, any_hit))
      break;
    plane_sides = ((plane_sides | ~in_plane_axes) + 1) & in_plane_axes;
  } while (plane_sides != 0);
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
