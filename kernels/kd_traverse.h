/* k-d tree traversal shared by the CPU reference (libkdtree) and the OpenCL kernels.
 * CONTRACT (implemented by the libkdtree work; callers rely on these names):
 *
 *   typedef struct KdSceneView {
 *     KD_GLOBAL const KdNode* nodes;          root at index 0
 *     KD_GLOBAL const kd_u32* leaf_triangles;  leaves are ranges of this array
 *     KD_GLOBAL const float* triangle_vertices; KD_TRIANGLE_FLOATS per triangle (see below)
 *     float bounds_min[3], bounds_max[3];      root voxel
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
 * ray moves into: below when d_k <= 0). t_split > t_max or t_split <= 0: near only;
 * t_split < t_min: far only; otherwise the far child goes on the stack with [t_split, t_max]
 * and the near one is visited with [t_min, t_split]. A hit found in a leaf is final once no
 * pending segment starts before it (for ordered segments: the seed's "t <= the leaf's t_max").
 *
 * Where this code departs from the letter of the seed, and why:
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

/* Triangle t's corners a, b, c are triangle_vertices[KD_TRIANGLE_FLOATS * t + 3 * corner + axis]:
 * copies of the scene's positions gathered once by the host, so that a triangle test is one
 * contiguous 36-byte fetch instead of a chain of leaf entry -> index -> vertex cache misses.
 * Indexed by triangle id, not by leaf entry: one copy of the vertices however many leaves
 * reference a triangle (a leaf-ordered copy would be ~5x larger, and measured slower). */
#define KD_TRIANGLE_FLOATS 9u

typedef struct KdSceneView {
  KD_GLOBAL const KdNode* nodes;
  KD_GLOBAL const kd_u32* leaf_triangles;
  KD_GLOBAL const float* triangle_vertices;
  float bounds_min[3], bounds_max[3];
} KdSceneView;

typedef struct KdStackEntry {
  kd_u32 node;
  float t_min, t_max;
} KdStackEntry;

KD_INLINE void kd_load_corner(KD_GLOBAL const float* triangle, kd_u32 corner, float out[3]) {
  out[0] = triangle[3u * corner + 0u];
  out[1] = triangle[3u * corner + 1u];
  out[2] = triangle[3u * corner + 2u];
}

/* Tests the leaf's triangles against (ray.tmin, hit->t); returns 1 if hit->t got smaller. */
KD_INLINE int kd_intersect_leaf(const KdSceneView* scene, const KdRay* ray, KdNode leaf, HitRecord* hit,
                                int any_hit) {
  int found = 0;
  const kd_u32 first = kd_leaf_first(leaf);
  const kd_u32 count = kd_leaf_count(leaf);
  for (kd_u32 i = 0; i < count; ++i) {
    const kd_u32 triangle = scene->leaf_triangles[first + i];
    KD_GLOBAL const float* corners = scene->triangle_vertices + KD_TRIANGLE_FLOATS * triangle;
    float a[3], b[3], c[3];
    kd_load_corner(corners, 0u, a);
    kd_load_corner(corners, 1u, b);
    kd_load_corner(corners, 2u, c);
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

/* Relative slack of the t comparisons in the descent (about 8 ulps). */
#define KD_T_EPSILON 9.5367431640625e-07f

/* Visits, in node order, every leaf whose voxel the ray touches at t = s (with the same
 * tolerance as the descent), without a stack: each descent from the root takes the first
 * child, in node order, that touches s and holds a node >= `next`; `bound` is the first node
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
      const kd_u32 axis = kd_node_axis(node);
      const float split = kd_node_split(node);
      const float origin = ray->org[axis];
      const kd_u32 below = node_index + 1u;
      const kd_u32 above = kd_node_far_child(node);
      int touches_below, touches_above;
      if (ray->dir[axis] == 0.0f && origin == split) {
        *in_plane_axes |= 1 << axis;
        touches_above = (plane_sides >> axis) & 1;
        touches_below = !touches_above;
      } else {
        const float t_split = (split - origin) * ray->inv_dir[axis];
        const int below_first = origin < split || (origin == split && ray->dir[axis] <= 0.0f);
        const int near_only = t_split > s * (1.0f + KD_T_EPSILON) || t_split <= 0.0f;
        const int far_only = !near_only && t_split < s * (1.0f - KD_T_EPSILON);
        touches_below = below_first ? !far_only : !near_only;
        touches_above = below_first ? !near_only : !far_only;
      }
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

/* One ordered traversal of [scene_t_min, scene_t_max]. At nodes whose split plane holds the
 * ray, it goes above on the axes set in plane_sides, below on the others, and adds the axis to
 * *in_plane_axes. Returns 1 when any_hit is set and a hit was found. */
KD_INLINE int kd_traverse_pass(const KdSceneView* scene, const KdRay* ray, float scene_t_min, float scene_t_max,
                               int plane_sides, int* in_plane_axes, HitRecord* best, int any_hit) {
  KdStackEntry stack[KD_SHORT_STACK_SIZE];
  /* Only slots already pushed are ever read; initialising them lets compilers see that. */
  for (int i = 0; i < KD_SHORT_STACK_SIZE; ++i) stack[i].t_min = INFINITY;
  int stack_top = 0;   /* next free slot, modulo the size */
  int stack_count = 0; /* valid entries below stack_top */
  float lost_t_min = INFINITY; /* earliest start of an overwritten entry in this round */
  float round_start = scene_t_min;
  int strict = 0;
  kd_u32 node_index = 0;
  float t_min = scene_t_min;
  float t_max = scene_t_max;

  for (;;) {
    KdNode node = scene->nodes[node_index];
    while (!kd_node_is_leaf(node)) {
      const kd_u32 axis = kd_node_axis(node);
      const float split = kd_node_split(node);
      const float origin = ray->org[axis];
      const kd_u32 below = node_index + 1u;
      const kd_u32 above = kd_node_far_child(node);
      if (ray->dir[axis] == 0.0f && origin == split) {
        *in_plane_axes |= 1 << axis;
        node_index = (plane_sides >> axis) & 1 ? above : below;
        node = scene->nodes[node_index];
        continue;
      }
      const float t_split = (split - origin) * ray->inv_dir[axis];
      const int below_first = origin < split || (origin == split && ray->dir[axis] <= 0.0f);
      const kd_u32 near_child = below_first ? below : above;
      const kd_u32 far_child = below_first ? above : below;
      if (t_split > t_max * (1.0f + KD_T_EPSILON) || t_split <= 0.0f) {
        node_index = near_child;
      } else if (t_split < t_min * (1.0f - KD_T_EPSILON) || (strict && t_split <= round_start)) {
        node_index = far_child;
      } else {
        if (stack_count == KD_SHORT_STACK_SIZE)
          lost_t_min = kd_minf(lost_t_min, stack[stack_top].t_min);
        else
          ++stack_count;
        const float t_boundary = kd_minf(kd_maxf(t_split, t_min), t_max);
        stack[stack_top].node = far_child;
        stack[stack_top].t_min = t_boundary;
        stack[stack_top].t_max = t_max;
        stack_top = (stack_top + 1) % KD_SHORT_STACK_SIZE;
        node_index = near_child;
        t_max = t_boundary;
      }
      node = scene->nodes[node_index];
    }
    if (kd_intersect_leaf(scene, ray, node, best, any_hit) && any_hit) return 1;

    /* Next segment: the newest pending one that could still hold a closer hit. */
    int popped = 0;
    while (stack_count > 0) {
      stack_top = (stack_top + KD_SHORT_STACK_SIZE - 1) % KD_SHORT_STACK_SIZE;
      --stack_count;
      if (stack[stack_top].t_min < best->t) {
        node_index = stack[stack_top].node;
        t_min = stack[stack_top].t_min;
        t_max = stack[stack_top].t_max;
        popped = 1;
        break;
      }
    }
    if (popped) continue;
    /* Stack empty: done unless a lost segment could still hold a closer hit. */
    if (!(lost_t_min < best->t)) return 0;
    strict = !(lost_t_min > round_start);
    if (strict &&
        kd_visit_point(scene, ray, round_start, plane_sides, in_plane_axes, best, any_hit))
      return 1;
    const float restart = kd_maxf(lost_t_min, round_start);
    round_start = restart;
    lost_t_min = INFINITY;
    node_index = 0;
    t_min = restart;
    t_max = scene_t_max;
  }
}

/* Both entry points: setup, clipping to the root voxel, and one pass per side combination of
 * split planes the ray lies in. best.t starts at ray.tmax so triangle tests only accept closer
 * hits. */
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
  float scene_t_min = record.tmin > 0.0f ? record.tmin : 0.0f;
  float scene_t_max = record.tmax;
  if (!kd_ray_box(&ray, scene->bounds_min, scene->bounds_max, &scene_t_min, &scene_t_max)) return best;
  best.t = record.tmax;
  int in_plane_axes = 0;
  for (int plane_sides = 0; plane_sides < 8; ++plane_sides) {
    if (plane_sides & ~in_plane_axes) continue; /* a side choice on an axis never met */
    if (kd_traverse_pass(scene, &ray, scene_t_min, scene_t_max, plane_sides, &in_plane_axes, &best, any_hit))
      break;
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
