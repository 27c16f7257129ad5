/* Ray/box and ray/triangle tests shared by the CPU reference traversal and the OpenCL kernels.
 *
 * The triangle test is the watertight one of Woop, Benthin & Wald, "Watertight Ray/Triangle
 * Intersection" (JCGT 2013): the ray is sheared so that it runs along +z, and the three 2D edge
 * functions decide inside/outside. Rays through a shared edge or vertex of two triangles hit at
 * least one of them, because each edge function is computed from the same rounded products in
 * both triangles (so it is exactly negated there). When an edge function rounds to exactly 0 it
 * is recomputed in double precision, where the products of two floats are exact. Devices without
 * double (no cl_khr_fp64) keep the float 0, which counts as "on the edge": still no leaks, but a
 * hit may be reported on both sides of an edge.
 *
 * Contraction of a*b - c*d into an FMA would break that symmetry, so it is switched off (kd_compat.h). */
#ifndef KD_GEOMETRY_H
#define KD_GEOMETRY_H

#include "kd_compat.h"

#ifdef __OPENCL_VERSION__
#if defined(cl_khr_fp64) || defined(__opencl_c_fp64)
#pragma OPENCL EXTENSION cl_khr_fp64 : enable
#define KD_HAS_DOUBLE 1
#else
#define KD_HAS_DOUBLE 0
#endif
#else
#define KD_HAS_DOUBLE 1
#endif

/* Direction components smaller than this get a finite reciprocal of the same sign instead of
 * 1/0: t = (plane - origin) * reciprocal then stays a number (0 * huge = 0), never NaN. */
#define KD_TINY_DIRECTION 1e-30f
#define KD_HUGE_RECIPROCAL 1e30f

/* Minimum and maximum as plain comparisons, not fmin/fmax: traversal never passes NaN here
 * (kd_ray_setup rejects non-finite rays and reciprocals stay finite), and fmin's NaN rule costs
 * a compare and a blend per call on CPUs (OpenCL) or a library call (C++ without -ffast-math). */
KD_INLINE float kd_minf(float a, float b) { return b < a ? b : a; }
KD_INLINE float kd_maxf(float a, float b) { return a < b ? b : a; }
#ifdef __OPENCL_VERSION__
KD_INLINE float kd_absf(float x) { return fabs(x); }
KD_INLINE float kd_copysignf(float magnitude, float sign) { return copysign(magnitude, sign); }
KD_INLINE int kd_isfinitef(float x) { return isfinite(x); }
#else
KD_INLINE float kd_absf(float x) { return std::fabs(x); }
KD_INLINE float kd_copysignf(float magnitude, float sign) { return std::copysign(magnitude, sign); }
KD_INLINE int kd_isfinitef(float x) { return std::isfinite(x) ? 1 : 0; }
#endif

/* Everything a traversal needs about one ray, computed once. */
typedef struct KdRay {
  float org[3];
  float dir[3];
  float inv_dir[3]; /* finite: see KD_HUGE_RECIPROCAL */
  float tmin, tmax;
  int kx, ky, kz;    /* kz: the axis of the largest |dir|; kx, ky keep the winding */
  float sx, sy, sz;  /* shear constants */
} KdRay;

/* The watertight test's axes: kz the first axis of the largest |dir|, kx and ky the next two in
 * cyclic order, swapped where dir[kz] < 0 so that the winding is kept. The axis and the sign are
 * as good as random from ray to ray, so a branch on them is mispredicted half the time. PoCL's
 * LLVM makes selects of the conditional form, and the arithmetic form cost it 6-13%; GCC makes
 * branches of the conditional form, so the C++ builds compute the same axes by arithmetic
 * (bench/LOG.md, "The ray's axes without a branch"). A kernel test holds the two to the same
 * axes where components tie. */
KD_INLINE void kd_ray_axes(KdRay* ray) {
  const float ax = kd_absf(ray->dir[0]), ay = kd_absf(ray->dir[1]), az = kd_absf(ray->dir[2]);
#ifdef __OPENCL_VERSION__
  int kz = ax < ay ? 1 : 0;
  kz = kd_absf(ray->dir[kz]) < az ? 2 : kz;
  const int next = kz == 2 ? 0 : kz + 1;
  const int after = next == 2 ? 0 : next + 1;
  const int negative = ray->dir[kz] < 0.0f;
  ray->kx = negative ? after : next;
  ray->ky = negative ? next : after;
#else
  const int y_over_x = ax < ay;
  const int z_largest = kd_maxf(ax, ay) < az;
  const int kz = y_over_x + z_largest * (2 - y_over_x);
  const int negative = ray->dir[kz] < 0.0f;
  const int kx = kz + 1 + negative, ky = kz + 2 - negative;
  ray->kx = kx - 3 * (kx >= 3);
  ray->ky = ky - 3 * (ky >= 3);
#endif
  ray->kz = kz;
}

/* 1 / d (given as `quotient`), or KD_HUGE_RECIPROCAL with d's sign where d is tiny. */
KD_INLINE float kd_finite_reciprocal(float d, float quotient) {
  return kd_absf(d) > KD_TINY_DIRECTION ? quotient : kd_copysignf(KD_HUGE_RECIPROCAL, d);
}
KD_INLINE float kd_safe_reciprocal(float d) { return kd_finite_reciprocal(d, 1.0f / d); }

/* Fills `ray`; returns 0 for a ray no triangle can be hit by (non-finite numbers, zero
 * direction, empty interval). */
KD_HOT_INLINE int kd_ray_setup(KdRay* ray, float ox, float oy, float oz, float dx, float dy, float dz,
                               float tmin, float tmax) {
  ray->org[0] = ox;
  ray->org[1] = oy;
  ray->org[2] = oz;
  ray->dir[0] = dx;
  ray->dir[1] = dy;
  ray->dir[2] = dz;
  ray->tmin = tmin;
  ray->tmax = tmax;
#ifdef __OPENCL_VERSION__
  /* Written out, not a loop: PoCL kept the loop, with a branch around each division. */
  ray->inv_dir[0] = kd_safe_reciprocal(dx);
  ray->inv_dir[1] = kd_safe_reciprocal(dy);
  ray->inv_dir[2] = kd_safe_reciprocal(dz);
  kd_ray_axes(ray);
  const int kx = ray->kx, ky = ray->ky, kz = ray->kz;
  ray->sx = ray->dir[kx] / ray->dir[kz];
  ray->sy = ray->dir[ky] / ray->dir[kz];
  ray->sz = 1.0f / ray->dir[kz];
#else
  /* The same six divisions as two four-wide ones: each lane is rounded as the scalar division
   * is, so the values are the same bits. The host's renders, whose shading in lanes divides as
   * well, run faster so; traces alone do not change (bench/LOG.md, "A ray's divisions four at
   * a time"). */
  const kd_f4 reciprocal = KD_F4(1.0f, 1.0f, 1.0f, 1.0f) / KD_F4(dx, dy, dz, 1.0f);
  ray->inv_dir[0] = kd_finite_reciprocal(dx, reciprocal[0]);
  ray->inv_dir[1] = kd_finite_reciprocal(dy, reciprocal[1]);
  ray->inv_dir[2] = kd_finite_reciprocal(dz, reciprocal[2]);
  kd_ray_axes(ray);
  const int kx = ray->kx, ky = ray->ky, kz = ray->kz;
  const float dir_kz = ray->dir[kz];
  const kd_f4 shear = KD_F4(ray->dir[kx], ray->dir[ky], 1.0f, 1.0f) / KD_F4(dir_kz, dir_kz, dir_kz, 1.0f);
  ray->sx = shear[0];
  ray->sy = shear[1];
  ray->sz = shear[2];
#endif
  int finite = kd_isfinitef(ox) && kd_isfinitef(oy) && kd_isfinitef(oz) && kd_isfinitef(dx) &&
               kd_isfinitef(dy) && kd_isfinitef(dz) && !(tmin != tmin) && !(tmax != tmax);
  return finite && ray->dir[kz] != 0.0f && tmin < tmax;
}

/* Slab test against the closed box [bmin, bmax]; narrows [*t_near, *t_far] and returns 0 if it
 * becomes empty. A zero direction component keeps the whole slab when the origin lies in it,
 * boundary included (the signed finite reciprocal alone would make a ray with d = -0 on the
 * lower face leave at once). The far distance is widened by a few ulps (pbrt's 1 + 2*gamma(3))
 * so rounding never drops a box the ray really touches. */
KD_INLINE int kd_ray_box(const KdRay* ray, const float bmin[3], const float bmax[3], float* t_near,
                         float* t_far) {
  float lo = *t_near;
  float hi = *t_far;
  for (int k = 0; k < 3; ++k) {
    if (ray->dir[k] == 0.0f) {
      if (ray->org[k] < bmin[k] || ray->org[k] > bmax[k]) return 0;
      continue;
    }
    float t0 = (bmin[k] - ray->org[k]) * ray->inv_dir[k];
    float t1 = (bmax[k] - ray->org[k]) * ray->inv_dir[k];
    float entry = kd_minf(t0, t1);
    float exit = kd_maxf(t0, t1) * (1.0f + 4.0f * 5.96046448e-08f);
    lo = kd_maxf(lo, entry);
    hi = kd_minf(hi, exit);
  }
  *t_near = lo;
  *t_far = hi;
  return lo <= hi;
}

/* The watertight test's arithmetic, written once for one triangle (TYPE float), for four side by
 * side (TYPE kd_f4, kd_intersect_leaf on CPUs) and for one triangle against eight rays (the host's
 * packets, libkdtree/src/traversal_packets.cpp), so that every lane makes the one triangle's
 * operations in the same order: from the corners' coordinates in the ray's axis order (kx, ky,
 * kz) it declares the corners' z relative to the origin (Az, Bz, Cz), their sheared x and y, and
 * the edge functions U, V and W. KD_WATERTIGHT_EDGES_FROM takes the origin in that order and the
 * shear (of type ORIGIN_TYPE: a float, or a lane of each ray's in a packet); KD_WATERTIGHT_EDGES
 * takes them from a KdRay. */
#define KD_WATERTIGHT_EDGES_FROM(TYPE, ORIGIN_TYPE, OX, OY, OZ, SX, SY, AX, AY, AZ, BX, BY, BZ, CX, CY, CZ) \
  const ORIGIN_TYPE kd_ox_ = (OX), kd_oy_ = (OY), kd_oz_ = (OZ);                                      \
  const TYPE Az = (AZ) - kd_oz_, Bz = (BZ) - kd_oz_, Cz = (CZ) - kd_oz_;                              \
  const TYPE ax = ((AX) - kd_ox_) - (SX) * Az;                                                       \
  const TYPE ay = ((AY) - kd_oy_) - (SY) * Az;                                                       \
  const TYPE bx = ((BX) - kd_ox_) - (SX) * Bz;                                                       \
  const TYPE by = ((BY) - kd_oy_) - (SY) * Bz;                                                       \
  const TYPE cx = ((CX) - kd_ox_) - (SX) * Cz;                                                       \
  const TYPE cy = ((CY) - kd_oy_) - (SY) * Cz;                                                       \
  TYPE U = cx * by - cy * bx;                                                                        \
  TYPE V = ax * cy - ay * cx;                                                                        \
  TYPE W = bx * ay - by * ax
#define KD_WATERTIGHT_EDGES(TYPE, ray, AX, AY, AZ, BX, BY, BZ, CX, CY, CZ)                                      \
  KD_WATERTIGHT_EDGES_FROM(TYPE, float, (ray)->org[(ray)->kx], (ray)->org[(ray)->ky], (ray)->org[(ray)->kz], \
                           (ray)->sx, (ray)->sy, AX, AY, AZ, BX, BY, BZ, CX, CY, CZ)

/* The hit's distance times the determinant U + V + W, from KD_WATERTIGHT_EDGES's values. */
#define KD_WATERTIGHT_T(ray, U, V, W, Az, Bz, Cz) \
  ((U) * ((ray)->sz * (Az)) + (V) * ((ray)->sz * (Bz)) + (W) * ((ray)->sz * (Cz)))

/* Watertight ray/triangle test against the whole line of the ray. Returns 1 when the line
 * passes through the triangle (a, b, c), whose coordinates lie `stride` floats apart (1: x, y, z
 * side by side; a grouped leaf block's 4), and writes its t and the barycentrics u (of b) and
 * v (of c); the caller decides which t it accepts. Triangles seen edge-on (determinant 0) are
 * missed from both sides. The corners are read where they lie (the kernels: the leaf blocks
 * in global memory), in the ray's axis order: copied into local arrays first, they
 * were stored to the stack and read back by index, at a dozen instructions per test. */
KD_HOT_INLINE int kd_ray_triangle_line(const KdRay* ray, KD_GLOBAL const float* a, KD_GLOBAL const float* b,
                                       KD_GLOBAL const float* c, int stride, float* t_out, float* u_out,
                                       float* v_out) {
  const int kx = ray->kx * stride, ky = ray->ky * stride, kz = ray->kz * stride;
  KD_WATERTIGHT_EDGES(float, ray, a[kx], a[ky], a[kz], b[kx], b[ky], b[kz], c[kx], c[ky], c[kz]);
#if KD_HAS_DOUBLE
  if (U == 0.0f || V == 0.0f || W == 0.0f) {
    U = (float)((double)cx * (double)by - (double)cy * (double)bx);
    V = (float)((double)ax * (double)cy - (double)ay * (double)cx);
    W = (float)((double)bx * (double)ay - (double)by * (double)ax);
  }
#endif
  if ((U < 0.0f || V < 0.0f || W < 0.0f) && (U > 0.0f || V > 0.0f || W > 0.0f)) return 0;
  const float det = U + V + W;
  if (det == 0.0f) return 0;
  const float T = KD_WATERTIGHT_T(ray, U, V, W, Az, Bz, Cz);
  const float inv_det = 1.0f / det;
  *t_out = T * inv_det;
  *u_out = V * inv_det;
  *v_out = W * inv_det;
  return 1;
}

/* The same test for ray->tmin < t < t_max. */
KD_INLINE int kd_ray_triangle(const KdRay* ray, KD_GLOBAL const float* a, KD_GLOBAL const float* b,
                              KD_GLOBAL const float* c, float t_max, float* t_out, float* u_out, float* v_out) {
  float t, u, v;
  if (!kd_ray_triangle_line(ray, a, b, c, 1, &t, &u, &v) || !(t > ray->tmin && t < t_max)) return 0;
  *t_out = t;
  *u_out = u;
  *v_out = v;
  return 1;
}

#endif /* KD_GEOMETRY_H */
