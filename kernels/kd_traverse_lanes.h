/* The fast path (kd_traverse_fast.h) for several rays at once, in groups of 8 lanes: closest hits
 * on CPUs, both for the host (C++, AVX2: 16 rays) and for PoCL's CPU devices (OpenCL C, float8:
 * 24 rays).
 *
 * Why: one ray's descent is a chain of dependent node loads and hard-to-predict branches, so a
 * core mostly waits (on a random ray the scalar step runs at under one instruction a cycle). Here
 * an inner step is taken for 8 rays with the same vector instructions and no branch on the data:
 * the 8 node loads are one gather, and the nodes each lane goes to next are prefetched, as is the
 * block of a leaf a lane has just reached (its triangles are tested one step later). Groups take
 * turns, so one group's loads are in flight while another computes. The rare events (a
 * leaf, an empty child, a push onto the stack, a finished ray) are handled lane by lane in scalar
 * code. A GPU keeps one ray per work-item: it is the GPU's own lanes that run rays side by side.
 *
 * The same hits bit for bit: every lane makes the scalar fast path's comparisons with the same
 * IEEE operations in the same order (selects in place of branches, no contraction), visits the
 * same nodes and leaves in the same order, and tests a leaf's triangles with the scalar code. A
 * ray the fast path does not take, and one whose stack would overflow, is traced by the robust
 * traversal from the start, as kd_traverse does.
 *
 * The step is written once over a lane type: OpenCL C's int8 and float8, or GCC's vector
 * extensions in C++ with AVX2 intrinsics for the gather, the selects and the lane mask; a mask is
 * -1 or 0 in every lane. A C++ includer compiles it for AVX2 and, where it includes it inside a
 * namespace, includes <immintrin.h> before.
 */
#ifndef KD_TRAVERSE_LANES_H
#define KD_TRAVERSE_LANES_H

#include "kd_traverse.h"

#define KD_LANES 8
/* Groups of lanes taking turns: while one group's loads are in flight, the others compute. On
 * PoCL, 3 traced random rays of large meshes 1-14% faster than 2 (camera rays 2% slower); on the
 * host, 3 gained on the largest meshes and lost 2-5% on smaller ones (bench/LOG.md, "PoCL traces
 * in float8 lanes"). */
#ifdef __OPENCL_VERSION__
#define KD_LANE_GROUPS 3
#else
#define KD_LANE_GROUPS 2
#endif

#ifdef __OPENCL_VERSION__
typedef float8 kd_lane_f;
typedef int8 kd_lane_i;
KD_HOT_INLINE kd_lane_f kd_lane_load_f(const float* p) { return vload8(0, p); }
KD_HOT_INLINE kd_lane_i kd_lane_load_i(const kd_u32* p) { return as_int8(vload8(0, p)); }
KD_HOT_INLINE void kd_lane_store_f(kd_lane_f v, float* p) { vstore8(v, 0, p); }
KD_HOT_INLINE void kd_lane_store_i(kd_lane_i v, kd_u32* p) { vstore8(as_uint8(v), 0, p); }
KD_HOT_INLINE kd_lane_f kd_lane_float_bits(kd_lane_i v) { return as_float8(v); }
KD_HOT_INLINE kd_lane_f kd_lane_splat_f(float x) { return (kd_lane_f)(x); }
KD_HOT_INLINE kd_lane_i kd_lane_splat_i(kd_i32 x) { return (kd_lane_i)(x); }
/* a where mask is 0, b where it is -1 */
KD_HOT_INLINE kd_lane_f kd_lane_select_f(kd_lane_f a, kd_lane_f b, kd_lane_i mask) { return select(a, b, mask); }
KD_HOT_INLINE kd_lane_i kd_lane_select_i(kd_lane_i a, kd_lane_i b, kd_lane_i mask) { return select(a, b, mask); }
KD_HOT_INLINE kd_lane_i kd_lane_shift_right(kd_lane_i v, kd_u32 bits) { return as_int8(as_uint8(v) >> bits); }
KD_HOT_INLINE kd_lane_i kd_lane_gather(KD_GLOBAL const kd_i32* base, kd_lane_i i) {
  return (kd_lane_i)(base[i.s0], base[i.s1], base[i.s2], base[i.s3], base[i.s4], base[i.s5], base[i.s6], base[i.s7]);
}
/* Bit k set where lane k's mask is -1. */
KD_HOT_INLINE kd_u32 kd_lane_bits(kd_lane_i mask) {
  const int8 bits = mask & (int8)(1, 2, 4, 8, 16, 32, 64, 128);
  const int4 halves = bits.lo | bits.hi;
  const int2 quarter = halves.lo | halves.hi;
  return (kd_u32)(quarter.x | quarter.y);
}
KD_HOT_INLINE int kd_bit_count(kd_u32 bits) { return (int)popcount(bits); }
#else
#include <immintrin.h>
typedef float kd_lane_f __attribute__((vector_size(32)));
typedef kd_i32 kd_lane_i __attribute__((vector_size(32)));
typedef kd_u32 kd_lane_u __attribute__((vector_size(32)));
inline kd_lane_f kd_lane_load_f(const float* p) { return (kd_lane_f)_mm256_loadu_ps(p); }
inline kd_lane_i kd_lane_load_i(const kd_u32* p) { return (kd_lane_i)_mm256_loadu_si256((const __m256i*)p); }
inline void kd_lane_store_f(kd_lane_f v, float* p) { _mm256_storeu_ps(p, (__m256)v); }
inline void kd_lane_store_i(kd_lane_i v, kd_u32* p) { _mm256_storeu_si256((__m256i*)p, (__m256i)v); }
inline kd_lane_f kd_lane_float_bits(kd_lane_i v) { return (kd_lane_f)v; }
inline kd_lane_f kd_lane_splat_f(float x) { return (kd_lane_f)_mm256_set1_ps(x); }
inline kd_lane_i kd_lane_splat_i(kd_i32 x) { return (kd_lane_i)_mm256_set1_epi32(x); }
inline kd_lane_f kd_lane_select_f(kd_lane_f a, kd_lane_f b, kd_lane_i mask) {
  return (kd_lane_f)_mm256_blendv_ps((__m256)a, (__m256)b, (__m256)mask);
}
inline kd_lane_i kd_lane_select_i(kd_lane_i a, kd_lane_i b, kd_lane_i mask) {
  return (kd_lane_i)_mm256_blendv_epi8((__m256i)a, (__m256i)b, (__m256i)mask);
}
inline kd_lane_i kd_lane_shift_right(kd_lane_i v, kd_u32 bits) { return (kd_lane_i)((kd_lane_u)v >> bits); }
inline kd_lane_i kd_lane_gather(const kd_i32* base, kd_lane_i i) {
  return (kd_lane_i)_mm256_i32gather_epi32(base, (__m256i)i, 4);
}
inline kd_u32 kd_lane_bits(kd_lane_i mask) { return (kd_u32)_mm256_movemask_ps((__m256)mask); }
inline int kd_bit_count(kd_u32 bits) { return __builtin_popcount(bits); }
#endif

/* kd_minf and kd_maxf, lane by lane. */
KD_HOT_INLINE kd_lane_f kd_lane_min(kd_lane_f a, kd_lane_f b) { return kd_lane_select_f(a, b, b < a); }
KD_HOT_INLINE kd_lane_f kd_lane_max(kd_lane_f a, kd_lane_f b) { return kd_lane_select_f(a, b, a < b); }

/* The rays to trace and where their hits go. A ray is taken by index from [next, end); in OpenCL
 * C the next batch of `batch` rays is then taken from the shared counter (persistent threads). */
typedef struct KdLaneRays {
  KD_GLOBAL const RayRecord* rays;
  KD_GLOBAL HitRecord* hits;
  kd_u32 next, end;
#ifdef __OPENCL_VERSION__
  __global uint* counter;
  kd_u32 count, batch;
#endif
} KdLaneRays;

/* One group's rays: what the vector step reads and writes, one array per quantity (a vector
 * load each), and what only the scalar events need, per lane. */
typedef struct KdLaneGroup {
  kd_u32 node[KD_LANES];
  float t_min[KD_LANES], t_max[KD_LANES], best_t[KD_LANES];
  float org[3][KD_LANES], inv_dir[3][KD_LANES];
  kd_u32 descending[KD_LANES], active[KD_LANES], at_leaf[KD_LANES];
  kd_u32 stack_count[KD_LANES];
  KdStackEntry stack[KD_LANES][KD_SHORT_STACK_SIZE];
  KdRay ray[KD_LANES];
  HitRecord best[KD_LANES];
  kd_u32 ray_index[KD_LANES];
} KdLaneGroup;

KD_INLINE int kd_lane_rays_next(KdLaneRays* source, kd_u32* index) {
#ifdef __OPENCL_VERSION__
  if (source->next == source->end && source->end < source->count) {
    const kd_u32 first = atomic_add(source->counter, source->batch);
    source->next = first < source->count ? first : source->count;
    source->end = first < source->count ? min(first + source->batch, source->count) : source->count;
  }
#endif
  if (source->next == source->end) return 0;
  *index = source->next++;
  return 1;
}

/* The robust traversal alone, from the start: for a ray the fast path does not take, and one
 * that overflowed its stack (it would again). */
KD_INLINE void kd_lane_trace_alone(const KdSceneView* scene, KdLaneRays* source, kd_u32 index) {
  HitRecord best;
  KdRay ray;
  float t_min, t_max;
  if (kd_traverse_begin(scene, source->rays[index], &ray, &t_min, &t_max, &best))
    kd_traverse_robust(scene, &ray, t_min, t_max, &best, 0);
  source->hits[index] = best;
}

/* Sets lane k of g to the next ray that takes the fast path; clears it when there is none left.
 * The start is kd_traverse's. */
KD_INLINE void kd_lane_refill(KdLaneGroup* g, int k, const KdSceneView* scene, KdLaneRays* source) {
  kd_u32 index;
  while (kd_lane_rays_next(source, &index)) {
    KdRay* ray = &g->ray[k];
    float t_min, t_max;
    if (!kd_traverse_begin(scene, source->rays[index], ray, &t_min, &t_max, &g->best[k])) {
      source->hits[index] = g->best[k];
      continue;
    }
    if (!kd_ray_takes_fast_path(ray)) {
      kd_lane_trace_alone(scene, source, index);
      continue;
    }
    g->best_t[k] = g->best[k].t;
    g->node[k] = 0;
    g->t_min[k] = t_min;
    g->t_max[k] = t_max;
    for (int axis = 0; axis < 3; ++axis) {
      g->org[axis][k] = ray->org[axis];
      g->inv_dir[axis][k] = ray->inv_dir[axis];
    }
    g->descending[k] = kd_ray_descending_axes(ray);
    g->active[k] = ~0u;
    g->at_leaf[k] = 0u;
    g->stack_count[k] = 0;
    g->ray_index[k] = index;
    return;
  }
  g->active[k] = 0u;
  g->node[k] = 0;
  g->at_leaf[k] = 0u;
}

/* After a leaf or an empty child: the next pending segment that may hold a closer hit, as
 * kd_traverse_fast pops it, else the ray is done and the lane takes the next one. */
KD_INLINE void kd_lane_pop_or_finish(KdLaneGroup* g, int k, const KdSceneView* scene, KdLaneRays* source) {
  g->at_leaf[k] = 0u;
  while (g->stack_count[k] > 0) {
    const KdStackEntry entry = g->stack[k][--g->stack_count[k]];
    if (kd_segment_may_precede(entry.t_min, &g->best[k])) {
      g->node[k] = entry.node;
      g->t_min[k] = entry.t_min;
      g->t_max[k] = entry.t_max;
      return;
    }
  }
  HitRecord hit = g->best[k];
  if (hit.triangle == KD_NO_HIT) hit.t = INFINITY;
  source->hits[g->ray_index[k]] = hit;
  kd_lane_refill(g, k, scene, source);
}

/* One inner step of every active lane of g not at a leaf (kd_traverse_fast's step, with
 * selects); then the events of the lanes that need one. Returns the number of lanes still
 * active. */
KD_INLINE int kd_lane_step(KdLaneGroup* g, const KdSceneView* scene, KdLaneRays* source) {
  const kd_lane_i one = kd_lane_splat_i(1), zero = kd_lane_splat_i(0);
  const kd_lane_i node = kd_lane_load_i(g->node);
  const kd_lane_i active = kd_lane_load_i(g->active);
  /* a node is its payload word, then its header word */
  KD_GLOBAL const kd_i32* words = (KD_GLOBAL const kd_i32*)scene->nodes;
  const kd_lane_i word = node + node;
  const kd_lane_i payload = kd_lane_gather(words, word);
  const kd_lane_i header = kd_lane_gather(words + 1, word);
  const kd_lane_i axis = header & 3;
  const kd_lane_i leaf = (axis == (kd_i32)KD_LEAF_TAG) & active;
  const kd_lane_i stepping = ~leaf & active;

  const kd_lane_i on_y = axis == one, on_z = axis == 2;
  const kd_lane_f org = kd_lane_select_f(
      kd_lane_select_f(kd_lane_load_f(g->org[0]), kd_lane_load_f(g->org[1]), on_y), kd_lane_load_f(g->org[2]), on_z);
  const kd_lane_f inv_dir =
      kd_lane_select_f(kd_lane_select_f(kd_lane_load_f(g->inv_dir[0]), kd_lane_load_f(g->inv_dir[1]), on_y),
                       kd_lane_load_f(g->inv_dir[2]), on_z);
  const kd_lane_f t_split = (kd_lane_float_bits(payload) - org) * inv_dir;

  const kd_lane_i below = node + one;
  const kd_lane_i above = kd_lane_shift_right(header, KD_CHILD_SHIFT);
  const kd_lane_i down = ((kd_lane_load_i(g->descending) >> axis) & one) == one;
  const kd_lane_i first = kd_lane_select_i(below, above, down);
  const kd_lane_i second = kd_lane_select_i(above, below, down);
  const kd_lane_i below_empty = kd_lane_splat_i(KD_BELOW_EMPTY), above_empty = kd_lane_splat_i(KD_ABOVE_EMPTY);
  const kd_lane_i first_bit = kd_lane_select_i(below_empty, above_empty, down);
  const kd_lane_i second_bit = kd_lane_select_i(above_empty, below_empty, down);
  const kd_lane_i first_empty = (header & first_bit) != zero;
  const kd_lane_i second_empty = (header & second_bit) != zero;

  const kd_lane_f t_min = kd_lane_load_f(g->t_min), t_max = kd_lane_load_f(g->t_max);
  const kd_lane_f far_below = /* kd_fast_far_bound */
      kd_lane_max(t_min * kd_lane_splat_f(1.0f - KD_T_EPSILON), kd_lane_splat_f(1.40129846e-45f));
  const kd_lane_f near_above = t_max * kd_lane_splat_f(1.0f + KD_T_EPSILON);
  const kd_lane_i far_only = t_split < far_below;
  const kd_lane_i near_only = ~far_only & (t_split > near_above);
  const kd_lane_i both = ~(far_only | near_only);
  const kd_lane_f t_boundary = kd_lane_min(kd_lane_max(t_split, t_min), t_max);
  const kd_lane_i skip_first = both & first_empty; /* nothing near: the far segment next */
  const kd_lane_i split_here = both & ~first_empty; /* near now, far pushed unless empty */
  /* kd_segment_may_precede(t_boundary, best): t_boundary lies in the clipped, finite segment. */
  const kd_lane_i may_precede = t_boundary <= kd_lane_load_f(g->best_t) * kd_lane_splat_f(1.0f + KD_T_EPSILON);
  const kd_lane_i empty_next =
      (far_only & second_empty) | (near_only & first_empty) | (skip_first & ~may_precede);
  const kd_lane_i stopped = stepping & empty_next;
  const kd_lane_i push = stepping & split_here & ~second_empty;

  const kd_lane_i next = kd_lane_select_i(first, second, far_only | skip_first);
  kd_lane_store_i(kd_lane_select_i(node, next, stepping), g->node);
  kd_lane_store_f(kd_lane_select_f(t_min, t_boundary, skip_first & stepping), g->t_min);
  kd_lane_store_f(kd_lane_select_f(t_max, t_boundary, split_here & stepping), g->t_max);

  /* A leaf found by this step's gather has its block prefetched and is tested at the next step. */
  const kd_lane_i waited = kd_lane_load_i(g->at_leaf);
  kd_u32 arriving = kd_lane_bits(~waited & leaf);
  const kd_u32 leaves = kd_lane_bits(waited & leaf);
  kd_lane_store_i(leaf, g->at_leaf);
  kd_u32 events = leaves | kd_lane_bits(stopped);
  kd_u32 pushes = kd_lane_bits(push);
  if (pushes) {
    kd_u32 far_node[KD_LANES];
    float far_t_min[KD_LANES], far_t_max[KD_LANES];
    kd_lane_store_i(second, far_node);
    kd_lane_store_f(t_boundary, far_t_min);
    kd_lane_store_f(t_max, far_t_max);
    do {
      const int k = kd_lowest_bit(pushes);
      pushes &= pushes - 1u;
      if (g->stack_count[k] == KD_SHORT_STACK_SIZE) { /* the fast path's overflow: traced again alone */
        kd_lane_trace_alone(scene, source, g->ray_index[k]);
        kd_lane_refill(g, k, scene, source);
        events &= ~(1u << k);
        continue;
      }
      KdStackEntry* entry = &g->stack[k][g->stack_count[k]++];
      entry->node = far_node[k];
      entry->t_min = far_t_min[k];
      entry->t_max = far_t_max[k];
    } while (pushes);
  }
  if (arriving) {
    kd_u32 first_word[KD_LANES], leaf_header[KD_LANES];
    kd_lane_store_i(payload, first_word);
    kd_lane_store_i(header, leaf_header);
    do {
      const int k = kd_lowest_bit(arriving);
      KD_GLOBAL const kd_u32* block = scene->leaf_blocks + first_word[k];
      /* A paged block's first two lines; a grouped block whole, up to four groups, since its
       * size is known from the count (a group is two and a half lines). */
      KD_PREFETCH(block);
      KD_PREFETCH(block + 16);
      KdNode leaf;
      leaf.payload = first_word[k];
      leaf.header = leaf_header[k];
      if (kd_leaf_grouped(leaf)) {
        const kd_u32 groups = (kd_leaf_count(leaf) + 3u) / 4u;
        const kd_u32 words = KD_LEAF_GROUP_WORDS * (groups < 4u ? groups : 4u);
        for (kd_u32 w = 32u; w < words; w += 16u) KD_PREFETCH(block + w);
      }
      arriving &= arriving - 1u;
    } while (arriving);
  }
  while (events) {
    const int k = kd_lowest_bit(events);
    events &= events - 1u;
    if ((leaves >> k) & 1u) {
      kd_intersect_leaf(scene, &g->ray[k], scene->nodes[g->node[k]], &g->best[k], 0);
      g->best_t[k] = g->best[k].t;
    }
    kd_lane_pop_or_finish(g, k, scene, source);
  }
  for (int k = 0; k < KD_LANES; ++k) KD_PREFETCH(scene->nodes + g->node[k]);
  return kd_bit_count(kd_lane_bits(kd_lane_load_i(g->active)));
}

/* Closest hits for every ray of source, in KD_LANE_GROUPS groups of lanes. */
KD_INLINE void kd_trace_closest_in_lanes(const KdSceneView* scene, KdLaneRays* source) {
  KdLaneGroup groups[KD_LANE_GROUPS];
  int active = 0;
  for (int group = 0; group < KD_LANE_GROUPS; ++group)
    for (int k = 0; k < KD_LANES; ++k) {
      kd_lane_refill(&groups[group], k, scene, source);
      active += groups[group].active[k] != 0u;
    }
  while (active > 0) {
    active = 0;
    for (int group = 0; group < KD_LANE_GROUPS; ++group) active += kd_lane_step(&groups[group], scene, source);
  }
}

#endif /* KD_TRAVERSE_LANES_H */
