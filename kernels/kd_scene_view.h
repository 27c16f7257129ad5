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

/* Corner k (0, 1 or 2) of a paged leaf's triangle whose corner numbers are `numbers`, in its
 * page of corners (kd_types.h; the tree reader refuses numbers with bits above the three
 * corners'). */
KD_HOT_INLINE KD_GLOBAL const float* kd_leaf_corner(KD_GLOBAL const float* page, kd_u32 numbers, kd_u32 k) {
  return page + 3u * ((numbers >> (k * KD_LEAF_CORNER_BITS)) & KD_LEAF_CORNER_MASK);
}

/* Where the corners a, b and c of triangle i of a leaf of `count` triangles lie, in either
 * layout; returns the stride between a corner's coordinates (kd_ray_triangle_line). */
KD_HOT_INLINE int kd_leaf_corners(KD_GLOBAL const kd_u32* block, kd_u32 count, int grouped, kd_u32 i,
                                  KD_GLOBAL const float** a, KD_GLOBAL const float** b, KD_GLOBAL const float** c) {
  if (grouped) {
    KD_GLOBAL const float* corners = (KD_GLOBAL const float*)(block + KD_LEAF_GROUP_WORDS * (i / 4u) + 4u) + i % 4u;
    *a = corners;
    *b = corners + 12;
    *c = corners + 24;
    return 4;
  }
  const kd_u32 numbers = block[count + i];
  KD_GLOBAL const float* page =
      (KD_GLOBAL const float*)(block + 2u * count) + 3u * KD_LEAF_PAGE_CORNERS * (i / KD_LEAF_PAGE_TRIANGLES);
  *a = kd_leaf_corner(page, numbers, 0u);
  *b = kd_leaf_corner(page, numbers, 1u);
  *c = kd_leaf_corner(page, numbers, 2u);
  return 1;
}

/* Where leaf tests run in lanes: on CPUs (the C++ builds, and OpenCL CPU devices, which get
 * -DKD_LEAF_TESTS_IN_LANES), a leaf's triangles are tested four at a time in vector lanes. A
 * GPU keeps one triangle at a time: its lanes are work-items. A C++ includer that defines
 * KD_LEAF_TESTS_ONE_AT_A_TIME gets the GPU's test (to compare the two). */
#if (!defined(__OPENCL_VERSION__) && !defined(KD_LEAF_TESTS_ONE_AT_A_TIME)) || defined(KD_LEAF_TESTS_IN_LANES)
#define KD_LEAF_LANES 1
KD_STATIC_ASSERT(KD_LEAF_PAGE_TRIANGLES % 4u == 0u, "four triangles of a leaf in lanes share one page of corners");
#endif

#ifdef KD_LEAF_LANES
/* The lanes of four triangles [first, first + 4) of a leaf, once KD_WATERTIGHT_EDGES has given
 * their edge functions: those that pass, in triangle order, replace `hit` where they precede it
 * (kd_intersect_leaf); returns 1 when any_hit and one did. Written once for both layouts, each
 * loop of kd_intersect_leaf inlining it with its layout fixed. */
KD_HOT_INLINE int kd_leaf_lanes_take(const KdRay* ray, KD_GLOBAL const kd_u32* block, kd_u32 count, int grouped,
                                     kd_u32 first, kd_f4 U, kd_f4 V, kd_f4 W, kd_f4 Az, kd_f4 Bz, kd_f4 Cz,
                                     HitRecord* hit, int any_hit, int* found) {
  const kd_f4 det = U + V + W;
  const kd_i4 any_zero = (U == 0.0f) | (V == 0.0f) | (W == 0.0f);
  const kd_i4 outside = ((U < 0.0f) | (V < 0.0f) | (W < 0.0f)) & ((U > 0.0f) | (V > 0.0f) | (W > 0.0f));
  const kd_u32 in_leaf = count - first < 4u ? (1u << (count - first)) - 1u : 15u;
  const kd_u32 again = kd_i4_bits(any_zero) & in_leaf;
  kd_u32 lanes = (kd_i4_bits(~(outside | (det == 0.0f))) | again) & in_leaf;
  if (lanes == 0u) return 0;
  const kd_f4 inv_det = 1.0f / det;
  float t[4], u[4], v[4];
  kd_f4_store(KD_WATERTIGHT_T(ray, U, V, W, Az, Bz, Cz) * inv_det, t);
  kd_f4_store(V * inv_det, u);
  kd_f4_store(W * inv_det, v);
  do {
    const int lane = kd_lowest_bit(lanes);
    lanes &= lanes - 1u;
    const kd_u32 i = first + (kd_u32)lane;
    if ((again >> lane) & 1u) { /* the one-at-a-time test, which recomputes in double */
      KD_GLOBAL const float *a, *b, *c;
      const int stride = kd_leaf_corners(block, count, grouped, i, &a, &b, &c);
      if (!kd_ray_triangle_line(ray, a, b, c, stride, &t[lane], &u[lane], &v[lane])) continue;
    }
    const kd_u32 index = kd_leaf_index(block, grouped, i);
    if (t[lane] > ray->tmin && kd_hit_precedes(t[lane], index, hit)) {
      hit->t = t[lane];
      hit->triangle = index;
      hit->u = u[lane];
      hit->v = v[lane];
      *found = 1;
      if (any_hit) return 1;
    }
  } while (lanes);
  return 0;
}
#endif

/* Tests the leaf's triangles against the ray and `hit`; returns 1 if hit changed. The block's
 * words are read as float where they are corners (the file's and the device buffer's bytes
 * have no other type).
 *
 * In lanes (KD_LEAF_LANES), four triangles go through KD_WATERTIGHT_EDGES side by side, each
 * lane with the one-triangle test's operations; a lane where an edge function is 0 is tested
 * again alone by kd_ray_triangle_line (which then recomputes in double), and the lanes that
 * pass are taken in triangle order, so the hits are the one-at-a-time test's bit for bit. One
 * vector pass and one branch on its outcome replace a branch per triangle, which random rays
 * mispredict (bench/LOG.md, "A leaf's triangles four at a time"). A grouped block gives each
 * of the nine coordinate vectors in one load; a paged block's are put together lane by lane. */
KD_HOT_INLINE int kd_intersect_leaf(const KdSceneView* scene, const KdRay* ray, KdNode leaf, HitRecord* hit,
                                    int any_hit) {
  int found = 0;
  const kd_u32 count = kd_leaf_count(leaf);
  const int grouped = kd_leaf_grouped(leaf);
  KD_GLOBAL const kd_u32* block = scene->leaf_blocks + kd_leaf_first(leaf);
  KD_COUNT(scene, leaves, 1);
  KD_COUNT(scene, triangle_tests, count);
#ifdef KD_LEAF_LANES
  const int kx = ray->kx, ky = ray->ky, kz = ray->kz;
  /* One loop per layout, the branch outside it: with the paged layout's dozen pointers in the
   * same loop as the grouped one's nine loads, a grouped tree's in-cache traces were 15% slower
   * (bench/LOG.md, "`.kdtree` version 6"). */
  if (grouped) {
    for (kd_u32 first = 0; first < count; first += 4u) {
      KD_GLOBAL const float* corners = (KD_GLOBAL const float*)(block + KD_LEAF_GROUP_WORDS * (first / 4u) + 4u);
      KD_WATERTIGHT_EDGES(kd_f4, ray, kd_f4_load(corners + 4 * kx), kd_f4_load(corners + 4 * ky),
                          kd_f4_load(corners + 4 * kz), kd_f4_load(corners + 12 + 4 * kx),
                          kd_f4_load(corners + 12 + 4 * ky), kd_f4_load(corners + 12 + 4 * kz),
                          kd_f4_load(corners + 24 + 4 * kx), kd_f4_load(corners + 24 + 4 * ky),
                          kd_f4_load(corners + 24 + 4 * kz));
      if (kd_leaf_lanes_take(ray, block, count, 1, first, U, V, W, Az, Bz, Cz, hit, any_hit, &found)) return 1;
    }
    return found;
  }
  for (kd_u32 first = 0; first < count; first += 4u) {
    /* Lanes past the leaf's end test its first triangle of the four again, and are dropped. */
#define KD_LEAF_LANE_CORNERS(lane)                                                                         \
  const kd_u32 numbers##lane = block[count + (first + lane##u < count ? first + lane##u : first)];           \
  KD_GLOBAL const float* a##lane = kd_leaf_corner(page, numbers##lane, 0u);                                \
  KD_GLOBAL const float* b##lane = kd_leaf_corner(page, numbers##lane, 1u);                                \
  KD_GLOBAL const float* c##lane = kd_leaf_corner(page, numbers##lane, 2u)
    /* The page of the four: a run of four starting at a multiple of 4 never crosses a page. */
    KD_GLOBAL const float* page =
        (KD_GLOBAL const float*)(block + 2u * count) + 3u * KD_LEAF_PAGE_CORNERS * (first / KD_LEAF_PAGE_TRIANGLES);
    KD_LEAF_LANE_CORNERS(0);
    KD_LEAF_LANE_CORNERS(1);
    KD_LEAF_LANE_CORNERS(2);
    KD_LEAF_LANE_CORNERS(3);
#undef KD_LEAF_LANE_CORNERS
    KD_WATERTIGHT_EDGES(kd_f4, ray, KD_F4(a0[kx], a1[kx], a2[kx], a3[kx]), KD_F4(a0[ky], a1[ky], a2[ky], a3[ky]),
                        KD_F4(a0[kz], a1[kz], a2[kz], a3[kz]), KD_F4(b0[kx], b1[kx], b2[kx], b3[kx]),
                        KD_F4(b0[ky], b1[ky], b2[ky], b3[ky]), KD_F4(b0[kz], b1[kz], b2[kz], b3[kz]),
                        KD_F4(c0[kx], c1[kx], c2[kx], c3[kx]), KD_F4(c0[ky], c1[ky], c2[ky], c3[ky]),
                        KD_F4(c0[kz], c1[kz], c2[kz], c3[kz]));
    if (kd_leaf_lanes_take(ray, block, count, 0, first, U, V, W, Az, Bz, Cz, hit, any_hit, &found)) return 1;
  }
#else
  for (kd_u32 i = 0; i < count; ++i) {
    KD_GLOBAL const float *a, *b, *c;
    const int stride = kd_leaf_corners(block, count, grouped, i, &a, &b, &c);
    float t, u, v;
    if (!kd_ray_triangle_line(ray, a, b, c, stride, &t, &u, &v) || !(t > ray->tmin)) continue;
    const kd_u32 index = kd_leaf_index(block, grouped, i);
    if (kd_hit_precedes(t, index, hit)) {
      hit->t = t;
      hit->triangle = index;
      hit->u = u;
      hit->v = v;
      found = 1;
      if (any_hit) return 1;
    }
  }
#endif
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
