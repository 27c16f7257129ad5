// The host's closest hits for eight rays at a time as one packet, where the CPU has AVX2: rays
// that run close together (camera rays of neighbouring pixels, shadow rays from neighbouring points
// towards one light) visit nearly the same nodes and leaves, so the packet pays for a node's step
// and for each triangle's test once for all eight. Rays that run apart share little and are
// slower so (bench/LOG.md, "Packets of eight rays"): trace_closest takes packets only when asked.
//
// The hits are one ray at a time's, byte for byte. A lane makes the one-ray traversal's
// decisions at every inner node it meets (kernels/kd_traverse_fast.h: the same t_split, the same
// widened bounds), so it visits every leaf that ray visits, and others only where the packet's
// order differs from its own; its triangle tests are the watertight test's operations in the
// same order (KD_WATERTIGHT_EDGES_FROM), and a hit replaces the best one by kd_hit_precedes's rule,
// whose result is the smallest (t, triangle) pair whatever the leaves visited in whatever order.
// A ray the fast path does not take (a zero direction component) is traced alone, robustly. A lane
// left alone in a subtree finishes it alone, on the one-ray fast path from that node (as Embree's
// hybrid packets go on one ray at a time where their rays part).
#include "traversal_variant.h"

#include <kdray/traverse.h>

#include <kernels/kd_compat.h>
#include <kernels/kd_geometry.h>
#include <kernels/kd_types.h>

#include <immintrin.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstring>

#include "avx2_functions_begin.h"

namespace kdray::detail {
namespace packets {

#include <kernels/kd_traverse.h>

constexpr int kRays = 8;
typedef float Floats __attribute__((vector_size(32)));
typedef int32_t Ints __attribute__((vector_size(32)));

// Bit l set where lane l of a comparison's answer is true.
inline int bits_of(Ints mask) { return _mm256_movemask_ps((__m256)mask); }
inline Floats splat(float x) { return Floats{} + x; }
inline Ints splat(int32_t x) { return Ints{} + x; }
inline Floats load(const float* p) {
  Floats v;
  std::memcpy(&v, p, sizeof v);
  return v;
}
// kd_minf and kd_maxf lane by lane, the same operands in the same places.
inline Floats min_of(Floats a, Floats b) { return b < a ? b : a; }
inline Floats max_of(Floats a, Floats b) { return a < b ? b : a; }
// Per lane, a0, a1 or a2 as the lane's axis k is 0, 1 or 2 (is0, is1: its masks).
inline Floats by_axis(Ints is0, Ints is1, Floats a0, Floats a1, Floats a2) { return is0 ? a0 : (is1 ? a1 : a2); }

// The packet's rays, set up lane by lane as kd_traverse_begin and kd_ray_setup set up one ray.
struct Packet {
  Floats org[3], dir[3], inv_dir[3];
  Floats org_x, org_y, org_z;  // the origin in the watertight test's axis order (kx, ky, kz)
  Floats sx, sy, sz, tmin;
  Ints kx_is0, kx_is1, ky_is0, ky_is1, kz_is0, kz_is1, descending[3];
  int32_t kx[kRays], ky[kRays], kz[kRays];
  Floats best_t, best_u, best_v;
  Ints best_triangle;
  int started = 0;  // lanes whose ray meets the root voxel
  int fast = 0;     // of those, the lanes on the fast path: traced as the packet
  int done = 0;     // lanes of an any-hit packet that have found a hit
  Floats t_min, t_max;  // the segment in the root voxel
};

// Lane l's KdRay, for the one-ray code: a test that recomputes in double (kd_ray_triangle_line),
// and a lane finishing a subtree alone (trace_singly). Neither reads its tmax.
KdRay lane_ray(const Packet& p, int l) {
  KdRay ray;
  for (int k = 0; k < 3; ++k) ray.org[k] = p.org[k][l], ray.dir[k] = p.dir[k][l], ray.inv_dir[k] = p.inv_dir[k][l];
  ray.tmin = p.tmin[l];
  ray.tmax = 0.0f;  // not read (above)
  ray.kx = p.kx[l], ray.ky = p.ky[l], ray.kz = p.kz[l];
  ray.sx = p.sx[l], ray.sy = p.sy[l], ray.sz = p.sz[l];
  return ray;
}

// kd_traverse_begin for the `count` rays from `rays`, eight lanes at once. Lanes past count and
// rays that meet no voxel are left out of `started`; their hits are the miss.
void set_up(Packet& p, const KdSceneView* scene, const RayRecord* rays, int count) {
  alignas(32) float field[8][kRays];  // the rays' records, field by field
  for (int l = 0; l < kRays; ++l) {
    const RayRecord& ray = rays[l < count ? l : 0];
    const float record[8] = {ray.ox, ray.oy, ray.oz, ray.dx, ray.dy, ray.dz, ray.tmin, ray.tmax};
    for (int f = 0; f < 8; ++f) field[f][l] = record[f];
  }
  Ints finite = splat(-1);
  for (int k = 0; k < 3; ++k) {
    p.org[k] = load(field[k]);
    p.dir[k] = load(field[3 + k]);
    finite &= (p.org[k] - p.org[k] == splat(0.0f)) & (p.dir[k] - p.dir[k] == splat(0.0f));  // x - x: NaN unless finite
    // kd_safe_reciprocal
    const Floats magnitude = (Floats)((Ints)p.dir[k] & 0x7fffffff);
    const Floats huge = (Floats)(((Ints)splat(KD_HUGE_RECIPROCAL)) | ((Ints)p.dir[k] & INT32_MIN));
    p.inv_dir[k] = magnitude > splat(KD_TINY_DIRECTION) ? splat(1.0f) / p.dir[k] : huge;
  }
  const Floats tmin = load(field[6]), tmax = load(field[7]);
  // kd_ray_axes's arithmetic form
  const Floats ax = (Floats)((Ints)p.dir[0] & 0x7fffffff), ay = (Floats)((Ints)p.dir[1] & 0x7fffffff),
               az = (Floats)((Ints)p.dir[2] & 0x7fffffff);
  const Ints y_over_x = (ax < ay) & 1;
  const Ints z_largest = (max_of(ax, ay) < az) & 1;
  const Ints kz = y_over_x + z_largest * (2 - y_over_x);
  p.kz_is0 = kz == 0, p.kz_is1 = kz == 1;
  const Floats dir_kz = by_axis(p.kz_is0, p.kz_is1, p.dir[0], p.dir[1], p.dir[2]);
  const Ints negative = (dir_kz < splat(0.0f)) & 1;
  Ints kx = kz + 1 + negative, ky = kz + 2 - negative;
  kx = kx - 3 * ((kx >= 3) & 1);
  ky = ky - 3 * ((ky >= 3) & 1);
  p.kx_is0 = kx == 0, p.kx_is1 = kx == 1, p.ky_is0 = ky == 0, p.ky_is1 = ky == 1;
  std::memcpy(p.kx, &kx, sizeof p.kx);
  std::memcpy(p.ky, &ky, sizeof p.ky);
  std::memcpy(p.kz, &kz, sizeof p.kz);
  p.sx = by_axis(p.kx_is0, p.kx_is1, p.dir[0], p.dir[1], p.dir[2]) / dir_kz;
  p.sy = by_axis(p.ky_is0, p.ky_is1, p.dir[0], p.dir[1], p.dir[2]) / dir_kz;
  p.sz = splat(1.0f) / dir_kz;
  p.org_x = by_axis(p.kx_is0, p.kx_is1, p.org[0], p.org[1], p.org[2]);
  p.org_y = by_axis(p.ky_is0, p.ky_is1, p.org[0], p.org[1], p.org[2]);
  p.org_z = by_axis(p.kz_is0, p.kz_is1, p.org[0], p.org[1], p.org[2]);
  p.tmin = tmin;
  Ints ok = finite & (tmin == tmin) & (tmax == tmax) & (dir_kz != splat(0.0f)) & (tmin < tmax);
  // kd_traverse_begin's segment, then kd_ray_box
  Floats lo = tmin > splat(0.0f) ? tmin : splat(0.0f), hi = tmax;
  Ints no_zero = splat(-1);
  for (int k = 0; k < 3; ++k) {
    const Ints zero = p.dir[k] == splat(0.0f);
    no_zero &= ~zero;
    const Floats bmin = splat(scene->bounds_min[k]), bmax = splat(scene->bounds_max[k]);
    ok &= ~(zero & ((p.org[k] < bmin) | (p.org[k] > bmax)));
    const Floats t0 = (bmin - p.org[k]) * p.inv_dir[k], t1 = (bmax - p.org[k]) * p.inv_dir[k];
    const Floats entry = min_of(t0, t1);
    const Floats exit = max_of(t0, t1) * splat(1.0f + 4.0f * 5.96046448e-08f);
    lo = zero ? lo : max_of(lo, entry);
    hi = zero ? hi : min_of(hi, exit);
    p.descending[k] = p.dir[k] < splat(0.0f);
  }
  ok &= lo <= hi;
  const int lanes = count >= kRays ? 0xff : (1 << count) - 1;
  p.started = bits_of(ok) & lanes;
  p.fast = p.started & bits_of(no_zero);
  p.t_min = lo;
  p.t_max = hi;
  // best: the ray's tmax with no triangle where the ray started (kd_traverse_begin), the miss
  // elsewhere
  const Ints started_lanes = (Ints{1, 2, 4, 8, 16, 32, 64, 128} & p.started) != 0;
  p.best_t = started_lanes ? tmax : splat(INFINITY);
  p.best_triangle = splat((int32_t)KD_NO_HIT);
  p.best_u = p.best_v = splat(0.0f);
}

// kd_intersect_leaf for the lanes in `lanes`, each triangle tested for all of them at once; with
// any_hit, a lane that takes a hit is done.
void intersect_leaf(Packet& p, const KdSceneView* scene, KdNode leaf, int lanes, bool any_hit) {
  const kd_u32 count = kd_leaf_count(leaf);
  const int grouped = kd_leaf_grouped(leaf);
  KD_GLOBAL const kd_u32* block = scene->leaf_blocks + kd_leaf_first(leaf);
  Ints active = (Ints{1, 2, 4, 8, 16, 32, 64, 128} & lanes) != 0;
  const Ints no_hit = splat((int32_t)KD_NO_HIT);
  for (kd_u32 i = 0; i < count; ++i) {
    KD_GLOBAL const float *a, *b, *c;
    const int stride = kd_leaf_corners(block, count, grouped, i, &a, &b, &c);
    const Floats a0 = splat(a[0]), a1 = splat(a[stride]), a2 = splat(a[2 * stride]);
    const Floats b0 = splat(b[0]), b1 = splat(b[stride]), b2 = splat(b[2 * stride]);
    const Floats c0 = splat(c[0]), c1 = splat(c[stride]), c2 = splat(c[2 * stride]);
    // each lane with its own ray's axis order
    KD_WATERTIGHT_EDGES_FROM(Floats, Floats, p.org_x, p.org_y, p.org_z, p.sx, p.sy,
                             by_axis(p.kx_is0, p.kx_is1, a0, a1, a2), by_axis(p.ky_is0, p.ky_is1, a0, a1, a2),
                             by_axis(p.kz_is0, p.kz_is1, a0, a1, a2), by_axis(p.kx_is0, p.kx_is1, b0, b1, b2),
                             by_axis(p.ky_is0, p.ky_is1, b0, b1, b2), by_axis(p.kz_is0, p.kz_is1, b0, b1, b2),
                             by_axis(p.kx_is0, p.kx_is1, c0, c1, c2), by_axis(p.ky_is0, p.ky_is1, c0, c1, c2),
                             by_axis(p.kz_is0, p.kz_is1, c0, c1, c2));
    const Floats zero = splat(0.0f);
    const Ints any_zero = (U == zero) | (V == zero) | (W == zero);
    const Ints outside = ((U < zero) | (V < zero) | (W < zero)) & ((U > zero) | (V > zero) | (W > zero));
    const Floats det = U + V + W;
    // Lanes with an edge function of 0 take the one-ray test, which recomputes in double.
    const int again = bits_of(active & any_zero);
    Ints candidates = active & ~any_zero & ~outside & (det != zero);
    if (!bits_of(candidates) && !again) continue;
    const Floats inv_det = splat(1.0f) / det;
    Floats t = KD_WATERTIGHT_T(&p, U, V, W, Az, Bz, Cz) * inv_det;
    Floats u = V * inv_det, v = W * inv_det;
    for (int rest = again; rest; rest &= rest - 1) {
      const int l = __builtin_ctz(rest);
      const KdRay ray = lane_ray(p, l);
      float tl, ul, vl;
      if (!kd_ray_triangle_line(&ray, a, b, c, stride, &tl, &ul, &vl)) continue;
      t[l] = tl, u[l] = ul, v[l] = vl;
      candidates[l] = -1;
    }
    // kd_hit_precedes, with the triangle indices compared unsigned
    const Ints index = splat((int32_t)kd_leaf_index(block, grouped, i));
    const Ints smaller = (index ^ INT32_MIN) < (p.best_triangle ^ INT32_MIN);
    const Ints precedes = (t < p.best_t) | ((t == p.best_t) & smaller & (p.best_triangle != no_hit));
    const Ints take = candidates & (t > p.tmin) & precedes;
    if (any_hit) {
      p.done |= bits_of(take);
      if (!bits_of(take)) continue;
      active &= ~take;
    }
    p.best_t = take ? t : p.best_t;
    p.best_u = take ? u : p.best_u;
    p.best_v = take ? v : p.best_v;
    p.best_triangle = take ? index : p.best_triangle;
  }
}

// Lanes `lanes` of the packet, each alone through the subtree at node_index over its segment there
// (kd_traverse_fast_from: the one-ray fast path, whose decisions the packet's lanes make), with
// its best hit so far. A lane whose short stack overflows leaves p.fast: the caller traces that
// ray again, alone.
void trace_singly(Packet& p, const KdSceneView* scene, kd_u32 node_index, int lanes, Floats t_min, Floats t_max,
                  bool any_hit) {
  for (; lanes; lanes &= lanes - 1) {
    const int l = __builtin_ctz(lanes);
    const KdRay ray = lane_ray(p, l);
    HitRecord best;
    best.t = p.best_t[l], best.triangle = (kd_u32)p.best_triangle[l], best.u = p.best_u[l], best.v = p.best_v[l];
    const int result = kd_traverse_fast_from(scene, &ray, node_index, t_min[l], t_max[l], &best, any_hit);
    if (result == KD_FAST_OVERFLOW) {
      p.fast &= ~(1 << l);
      continue;
    }
    p.best_t[l] = best.t, p.best_triangle[l] = (int32_t)best.triangle, p.best_u[l] = best.u, p.best_v[l] = best.v;
    if (any_hit && result == 1) p.done |= 1 << l;
  }
}

struct PacketEntry {
  Floats t_min, t_max;
  kd_u32 node;
  int lanes;
};

// The fast-path lanes of the packet through the tree, from the root: each to its closest hit,
// or with any_hit until it has one.
void traverse(Packet& p, const KdSceneView* scene, bool any_hit) {
  // One entry per level of the path from the root: the deepest tree never overflows it.
  PacketEntry stack[KD_MAX_TREE_DEPTH + 1];
  int depth = 0;
  const Ints lane_bit = {1, 2, 4, 8, 16, 32, 64, 128};
  const Floats below_one = splat(1.0f - KD_T_EPSILON), above_one = splat(1.0f + KD_T_EPSILON);
  const Floats smallest = splat(1.40129846e-45f);
  kd_u32 node_index = 0;
  int lanes = p.fast;
  Floats t_min = p.t_min, t_max = p.t_max;
  for (;;) {
    KdNode node = scene->nodes[node_index];
    while (!kd_node_is_leaf(node)) {
      // One lane left: it goes on alone, without the packet's masks and union of nodes.
      if ((lanes & (lanes - 1)) == 0) {
        trace_singly(p, scene, node_index, lanes, t_min, t_max, any_hit);
        lanes = 0;
        break;
      }
      const kd_u32 axis = kd_node_axis(node);
      const Floats t_split = (splat(kd_node_split(node)) - p.org[axis]) * p.inv_dir[axis];
      const Floats far_below = max_of(t_min * below_one, smallest);  // kd_fast_far_bound
      const Floats near_above = t_max * above_one;
      const Ints far_only = t_split < far_below, near_only = t_split > near_above;
      const Ints both = ~(far_only | near_only);
      const Floats t_boundary = min_of(max_of(t_split, t_min), t_max);
      // The below child is the near one where the ray runs up this axis.
      const Ints down = p.descending[axis];
      const Ints in_lanes = (lane_bit & lanes) != 0;
      int below_lanes = bits_of(in_lanes & (down ? ~near_only : ~far_only));
      int above_lanes = bits_of(in_lanes & (down ? ~far_only : ~near_only));
      if (node.header & KD_BELOW_EMPTY) below_lanes = 0;
      if (node.header & KD_ABOVE_EMPTY) above_lanes = 0;
      const Floats below_min = (both & down) ? t_boundary : t_min, below_max = (both & ~down) ? t_boundary : t_max;
      const Floats above_min = (both & ~down) ? t_boundary : t_min, above_max = (both & down) ? t_boundary : t_max;
      const kd_u32 below = node_index + 1u, above = kd_node_far_child(node);
      if (below_lanes && above_lanes) {
        // The side more of the lanes meet first comes first.
        const int ascending = __builtin_popcount(lanes & ~bits_of(down));
        if (2 * ascending >= __builtin_popcount(lanes)) {
          stack[depth++] = PacketEntry{above_min, above_max, above, above_lanes};
          node_index = below, lanes = below_lanes, t_min = below_min, t_max = below_max;
        } else {
          stack[depth++] = PacketEntry{below_min, below_max, below, below_lanes};
          node_index = above, lanes = above_lanes, t_min = above_min, t_max = above_max;
        }
      } else if (below_lanes) {
        node_index = below, lanes = below_lanes, t_min = below_min, t_max = below_max;
      } else if (above_lanes) {
        node_index = above, lanes = above_lanes, t_min = above_min, t_max = above_max;
      } else {
        lanes = 0;
        break;
      }
      node = scene->nodes[node_index];
    }
    if (lanes) intersect_leaf(p, scene, node, lanes, any_hit);
    if (any_hit && p.done == p.fast) return;
    // The next pending segment that may hold a hit preceding a lane's best (kd_segment_may_precede).
    for (;;) {
      if (depth == 0) return;
      const PacketEntry& entry = stack[--depth];
      const Ints may = (entry.t_min <= p.best_t * above_one) & (entry.t_min < splat(INFINITY));
      lanes = entry.lanes & ~p.done & p.fast & bits_of(may);
      if (lanes) {
        node_index = entry.node, t_min = entry.t_min, t_max = entry.t_max;
        break;
      }
    }
  }
}

// Sets up and traces the packet of rays [0, count), count <= kRays; rays it leaves out (not
// started, or not on the fast path) are for the caller to trace alone.
void trace(Packet& p, const KdSceneView* scene, const RayRecord* rays, int count, bool any_hit) {
  set_up(p, scene, rays, count);
  if (p.fast) traverse(p, scene, any_hit);
}

}  // namespace packets

void closest_in_packets(const TraversalArrays& arrays, const RayRecord* rays, HitRecord* hits, size_t count) {
  const packets::KdSceneView scene = make_view(&packets::kd_scene_view, arrays);
  for (size_t first = 0; first < count; first += packets::kRays) {
    const int n = static_cast<int>(std::min<size_t>(packets::kRays, count - first));
    packets::Packet p;
    packets::trace(p, &scene, rays + first, n, false);
    for (int l = 0; l < n; ++l) {
      HitRecord& hit = hits[first + l];
      if ((p.fast >> l & 1) == 0) {
        hit = packets::kd_traverse(&scene, rays[first + l], 0);  // the miss, or a ray for the robust traversal
        continue;
      }
      hit.triangle = static_cast<kd_u32>(p.best_triangle[l]);
      hit.t = hit.triangle == KD_NO_HIT ? INFINITY : p.best_t[l];
      hit.u = p.best_u[l];
      hit.v = p.best_v[l];
    }
  }
}

void any_in_packets(const TraversalArrays& arrays, const RayRecord* rays, uint8_t* occluded, size_t count) {
  const packets::KdSceneView scene = make_view(&packets::kd_scene_view, arrays);
  for (size_t first = 0; first < count; first += packets::kRays) {
    const int n = static_cast<int>(std::min<size_t>(packets::kRays, count - first));
    packets::Packet p;
    packets::trace(p, &scene, rays + first, n, true);
    for (int l = 0; l < n; ++l)
      occluded[first + l] = (p.fast >> l & 1) ? (p.done >> l & 1)
                                              : packets::kd_traverse(&scene, rays[first + l], 1).triangle != KD_NO_HIT;
  }
}

}  // namespace kdray::detail

#include "avx2_functions_end.h"
