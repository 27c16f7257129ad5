// The fast path (kernels/kd_traverse_fast.h) for 16 rays at once per thread, in two groups of 8
// AVX2 lanes: the host's closest-hit traversal where the CPU has AVX2.
//
// Why: one ray's descent is a chain of dependent node loads and hard-to-predict branches, so a
// core mostly waits (on a random ray the scalar step runs at under one instruction a cycle). Here
// an inner step is taken for 8 rays with the same vector instructions and no branch on the
// data: the 8 node loads are one gather, and the nodes each lane goes to next are prefetched,
// as is the block of a leaf a lane has just reached (its triangles are tested one step later).
// Two groups alternate, so one group's loads are in flight while the other computes. The rare
// events (a leaf, an empty child, a push onto the stack, a finished ray) are handled lane by
// lane in scalar code.
//
// The same hits bit for bit: every lane makes the scalar fast path's comparisons with the same
// IEEE operations in the same order (selects in place of branches; _mm256_min_ps(b, a) and
// _mm256_max_ps(b, a) are kd_minf(a, b) and kd_maxf(a, b) for the finite values met here; no
// contraction), visits the same nodes and leaves in the same order, and tests a leaf's
// triangles with the scalar code. A ray the fast path does not take, and one whose stack would
// overflow, is traced by the robust traversal from the start, as kd_traverse does.
#include "traversal_variant.h"

#include <kernels/kd_compat.h>
#include <kernels/kd_geometry.h>
#include <kernels/kd_types.h>

#include <immintrin.h>

namespace kdray::detail {
namespace lanes {

#include <kernels/kd_traverse.h>

constexpr int kLanes = 8;
constexpr int kGroups = 2;

// One group's rays: what the vector step reads and writes, one array per quantity (a vector
// load each), and what only the scalar events need, per lane.
struct Group {
  alignas(32) kd_u32 node[kLanes];
  alignas(32) float t_min[kLanes], t_max[kLanes], best_t[kLanes];
  alignas(32) float org[3][kLanes], inv_dir[3][kLanes];
  alignas(32) kd_u32 descending[kLanes], active[kLanes], at_leaf[kLanes];
  kd_u32 stack_count[kLanes];
  KdStackEntry stack[kLanes][KD_SHORT_STACK_SIZE];
  KdRay ray[kLanes];
  HitRecord best[kLanes];
  size_t ray_index[kLanes];
};

// The rays of one chunk, handed to lanes in order; a ray the lanes do not trace is finished here.
struct RaySource {
  const TraversalArrays& arrays;
  const KdSceneView* scene;
  const RayRecord* rays;
  HitRecord* hits;
  size_t count, next;
};

// The robust traversal alone, as kd_traverse turns to it for such rays: it gives the fast path's
// hits, and a ray that overflowed the fast path's stack would overflow it again.
void trace_alone(const RaySource& source, size_t index) {
  traversal_robust_short_stack().closest(source.arrays, source.rays + index, source.hits + index, 1);
}

// Sets lane k of g to the next ray that takes the fast path; clears it when there is none left.
// The setup is kd_traverse's.
void refill(Group& g, int k, RaySource& source) {
  while (source.next < source.count) {
    const size_t index = source.next++;
    const RayRecord& record = source.rays[index];
    KdRay& ray = g.ray[k];
    HitRecord miss;
    miss.t = INFINITY;
    miss.triangle = KD_NO_HIT;
    miss.u = 0.0f;
    miss.v = 0.0f;
    if (!kd_ray_setup(&ray, record.ox, record.oy, record.oz, record.dx, record.dy, record.dz, record.tmin,
                      record.tmax)) {
      source.hits[index] = miss;
      continue;
    }
    if (!kd_ray_takes_fast_path(&ray)) {
      trace_alone(source, index);
      continue;
    }
    float t_min = record.tmin > 0.0f ? record.tmin : 0.0f;
    float t_max = record.tmax;
    if (!kd_ray_box(&ray, source.scene->bounds_min, source.scene->bounds_max, &t_min, &t_max)) {
      source.hits[index] = miss;
      continue;
    }
    g.best[k] = miss;
    g.best[k].t = record.tmax;
    g.best_t[k] = record.tmax;
    g.node[k] = 0;
    g.t_min[k] = t_min;
    g.t_max[k] = t_max;
    for (int axis = 0; axis < 3; ++axis) {
      g.org[axis][k] = ray.org[axis];
      g.inv_dir[axis][k] = ray.inv_dir[axis];
    }
    g.descending[k] = (ray.dir[0] < 0.0f ? 1u : 0u) | (ray.dir[1] < 0.0f ? 2u : 0u) | (ray.dir[2] < 0.0f ? 4u : 0u);
    g.active[k] = ~0u;
    g.at_leaf[k] = 0u;
    g.stack_count[k] = 0;
    g.ray_index[k] = index;
    return;
  }
  g.active[k] = 0u;
  g.node[k] = 0;
  g.at_leaf[k] = 0u;
}

// After a leaf or an empty child: the next pending segment that may hold a closer hit, as
// kd_traverse_fast pops it, else the ray is done and the lane takes the next one.
void pop_or_finish(Group& g, int k, RaySource& source) {
  g.at_leaf[k] = 0u;
  while (g.stack_count[k] > 0) {
    const KdStackEntry& entry = g.stack[k][--g.stack_count[k]];
    if (kd_segment_may_precede(entry.t_min, &g.best[k])) {
      g.node[k] = entry.node;
      g.t_min[k] = entry.t_min;
      g.t_max[k] = entry.t_max;
      return;
    }
  }
  HitRecord hit = g.best[k];
  if (hit.triangle == KD_NO_HIT) hit.t = INFINITY;
  source.hits[g.ray_index[k]] = hit;
  refill(g, k, source);
}

__attribute__((target("avx2"))) inline unsigned lane_bits(__m256i mask) {
  return (unsigned)_mm256_movemask_ps(_mm256_castsi256_ps(mask));
}

// One inner step of every active lane of g not at a leaf (kd_traverse_fast's step, with
// selects); then the events of the lanes that need one. Returns the lanes still active.
__attribute__((target("avx2"))) int step(Group& g, RaySource& source) {
  const KdSceneView* scene = source.scene;
  const __m256i all = _mm256_set1_epi32(-1), zero = _mm256_setzero_si256();
  const __m256i one = _mm256_set1_epi32(1), two = _mm256_set1_epi32(2), leaf_tag = _mm256_set1_epi32(KD_LEAF_TAG);
  const __m256i below_empty = _mm256_set1_epi32(KD_BELOW_EMPTY), above_empty = _mm256_set1_epi32(KD_ABOVE_EMPTY);
  const __m256i node = _mm256_load_si256((const __m256i*)g.node);
  const __m256i active = _mm256_load_si256((const __m256i*)g.active);
  const int* words = (const int*)scene->nodes;  // a node is its payload word, then its header word
  const __m256i word = _mm256_add_epi32(node, node);
  const __m256i payload = _mm256_i32gather_epi32(words, word, 4);
  const __m256i header = _mm256_i32gather_epi32(words + 1, word, 4);
  const __m256i axis = _mm256_and_si256(header, _mm256_set1_epi32(3));
  const __m256i leaf = _mm256_and_si256(_mm256_cmpeq_epi32(axis, leaf_tag), active);
  const __m256i stepping = _mm256_andnot_si256(leaf, active);

  const __m256 on_y = _mm256_castsi256_ps(_mm256_cmpeq_epi32(axis, one));
  const __m256 on_z = _mm256_castsi256_ps(_mm256_cmpeq_epi32(axis, two));
  const __m256 org = _mm256_blendv_ps(_mm256_blendv_ps(_mm256_load_ps(g.org[0]), _mm256_load_ps(g.org[1]), on_y),
                                      _mm256_load_ps(g.org[2]), on_z);
  const __m256 inv_dir = _mm256_blendv_ps(
      _mm256_blendv_ps(_mm256_load_ps(g.inv_dir[0]), _mm256_load_ps(g.inv_dir[1]), on_y),
      _mm256_load_ps(g.inv_dir[2]), on_z);
  const __m256 t_split = _mm256_mul_ps(_mm256_sub_ps(_mm256_castsi256_ps(payload), org), inv_dir);

  const __m256i below = _mm256_add_epi32(node, one);
  const __m256i above = _mm256_srli_epi32(header, KD_CHILD_SHIFT);
  const __m256i descending = _mm256_load_si256((const __m256i*)g.descending);
  const __m256i down = _mm256_cmpeq_epi32(_mm256_and_si256(_mm256_srlv_epi32(descending, axis), one), one);
  const __m256i first = _mm256_blendv_epi8(below, above, down);
  const __m256i second = _mm256_blendv_epi8(above, below, down);
  const __m256i first_bit = _mm256_blendv_epi8(below_empty, above_empty, down);
  const __m256i second_bit = _mm256_blendv_epi8(above_empty, below_empty, down);
  const __m256i first_empty = _mm256_xor_si256(_mm256_cmpeq_epi32(_mm256_and_si256(header, first_bit), zero), all);
  const __m256i second_empty = _mm256_xor_si256(_mm256_cmpeq_epi32(_mm256_and_si256(header, second_bit), zero), all);

  const __m256 t_min = _mm256_load_ps(g.t_min), t_max = _mm256_load_ps(g.t_max);
  const __m256 far_below =  // kd_fast_far_bound
      _mm256_max_ps(_mm256_set1_ps(1.40129846e-45f), _mm256_mul_ps(t_min, _mm256_set1_ps(1.0f - KD_T_EPSILON)));
  const __m256 near_above = _mm256_mul_ps(t_max, _mm256_set1_ps(1.0f + KD_T_EPSILON));
  const __m256i far_only = _mm256_castps_si256(_mm256_cmp_ps(t_split, far_below, _CMP_LT_OQ));
  const __m256i near_only =
      _mm256_andnot_si256(far_only, _mm256_castps_si256(_mm256_cmp_ps(t_split, near_above, _CMP_GT_OQ)));
  const __m256i both = _mm256_xor_si256(_mm256_or_si256(far_only, near_only), all);
  const __m256 t_boundary = _mm256_min_ps(t_max, _mm256_max_ps(t_min, t_split));
  const __m256i skip_first = _mm256_and_si256(both, first_empty);   // nothing near: the far segment next
  const __m256i split_here = _mm256_andnot_si256(first_empty, both);  // near now, far pushed unless empty
  // kd_segment_may_precede(t_boundary, best): t_boundary lies in the clipped, finite segment.
  const __m256 best_bound = _mm256_mul_ps(_mm256_load_ps(g.best_t), _mm256_set1_ps(1.0f + KD_T_EPSILON));
  const __m256i may_precede = _mm256_castps_si256(_mm256_cmp_ps(t_boundary, best_bound, _CMP_LE_OQ));
  const __m256i empty_next = _mm256_or_si256(
      _mm256_or_si256(_mm256_and_si256(far_only, second_empty), _mm256_and_si256(near_only, first_empty)),
      _mm256_andnot_si256(may_precede, skip_first));
  const __m256i stopped = _mm256_and_si256(stepping, empty_next);
  const __m256i push = _mm256_and_si256(stepping, _mm256_andnot_si256(second_empty, split_here));

  const __m256i next = _mm256_blendv_epi8(first, second, _mm256_or_si256(far_only, skip_first));
  _mm256_store_si256((__m256i*)g.node, _mm256_blendv_epi8(node, next, stepping));
  const __m256 new_t_min = _mm256_castsi256_ps(_mm256_and_si256(skip_first, stepping));
  const __m256 new_t_max = _mm256_castsi256_ps(_mm256_and_si256(split_here, stepping));
  _mm256_store_ps(g.t_min, _mm256_blendv_ps(t_min, t_boundary, new_t_min));
  _mm256_store_ps(g.t_max, _mm256_blendv_ps(t_max, t_boundary, new_t_max));

  // A leaf found by this step's gather has its block prefetched and is tested at the next step.
  const __m256i waited = _mm256_load_si256((const __m256i*)g.at_leaf);
  unsigned arriving = lane_bits(_mm256_andnot_si256(waited, leaf));
  const unsigned leaves = lane_bits(_mm256_and_si256(waited, leaf));
  _mm256_store_si256((__m256i*)g.at_leaf, leaf);
  unsigned events = leaves | lane_bits(stopped);
  if (unsigned pushes = lane_bits(push)) {
    alignas(32) kd_u32 far_node[kLanes];
    alignas(32) float far_t_min[kLanes], far_t_max[kLanes];
    _mm256_store_si256((__m256i*)far_node, second);
    _mm256_store_ps(far_t_min, t_boundary);
    _mm256_store_ps(far_t_max, t_max);
    do {
      const int k = __builtin_ctz(pushes);
      pushes &= pushes - 1;
      if (g.stack_count[k] == KD_SHORT_STACK_SIZE) {  // the fast path's overflow: traced again alone
        trace_alone(source, g.ray_index[k]);
        refill(g, k, source);
        events &= ~(1u << k);
        continue;
      }
      KdStackEntry& entry = g.stack[k][g.stack_count[k]++];
      entry.node = far_node[k];
      entry.t_min = far_t_min[k];
      entry.t_max = far_t_max[k];
    } while (pushes);
  }
  if (arriving) {
    alignas(32) kd_u32 first_word[kLanes];
    _mm256_store_si256((__m256i*)first_word, payload);
    do {
      const kd_u32* block = scene->leaf_blocks + first_word[__builtin_ctz(arriving)];
      __builtin_prefetch(block);
      __builtin_prefetch(block + 16);
      arriving &= arriving - 1;
    } while (arriving);
  }
  while (events) {
    const int k = __builtin_ctz(events);
    events &= events - 1;
    if ((leaves >> k) & 1u) {
      kd_intersect_leaf(scene, &g.ray[k], scene->nodes[g.node[k]], &g.best[k], 0);
      g.best_t[k] = g.best[k].t;
    }
    pop_or_finish(g, k, source);
  }
  for (int k = 0; k < kLanes; ++k) __builtin_prefetch(scene->nodes + g.node[k]);
  return __builtin_popcount(lane_bits(_mm256_load_si256((const __m256i*)g.active)));
}

}  // namespace lanes

bool closest_in_lanes_supported() { return __builtin_cpu_supports("avx2"); }

void closest_in_lanes(const TraversalArrays& arrays, const RayRecord* rays, HitRecord* hits, size_t count) {
  const lanes::KdSceneView scene = make_view(&lanes::kd_scene_view, arrays);
  lanes::RaySource source{arrays, &scene, rays, hits, count, 0};
  lanes::Group groups[lanes::kGroups];
  int active = 0;
  for (lanes::Group& g : groups)
    for (int k = 0; k < lanes::kLanes; ++k) {
      lanes::refill(g, k, source);
      active += g.active[k] != 0u;
    }
  while (active > 0) {
    active = 0;
    for (lanes::Group& g : groups) active += lanes::step(g, source);
  }
}

}  // namespace kdray::detail
