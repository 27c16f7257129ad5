/* The path tracer's sample values: counter-based, so a value is a pure function of (sampler,
 * seed, pixel, sample index, dimension). An image therefore does not depend on which work-item
 * rendered which pixel, the local size, the number of threads or the device, and sample ranges
 * rendered apart merge to the bits of one render. Compiles as OpenCL C and as C++.
 *
 * Two samplers:
 * - PT_SAMPLER_SOBOL (the default): Owen-scrambled, shuffled Sobol' points in padded 2D pairs
 *   (Burley 2020, "Practical Hash-based Owen Scrambling", JCGT 9(4)). Each dimension pair takes
 *   Sobol' dimensions 0 and 1 (a (0,2)-sequence) of a shuffled sample index and Owen-scrambles
 *   both coordinates. The shuffle is itself a nested uniform scramble of the index, so a pixel's
 *   samples 0..2^k-1 are a permuted aligned block of 2^k Sobol' points, and each pair of them is a
 *   (0,k,2)-net: one point in every elementary interval of area 2^-k. Pixels and pairs draw
 *   their own shuffle and scramble seeds, which decorrelates them (the "padding").
 * - PT_SAMPLER_INDEPENDENT: hashed independent uniform numbers, as before the sampler choice.
 *
 * Dimension plan (dimension = 2 * pair + coordinate; a pair is stratified as a 2D point):
 *   dimensions 0, 1                 pixel position (camera ray)
 *   bounce k uses PT_DIMS_PER_BOUNCE dimensions from PT_BOUNCE_DIMS(k):
 *     PT_DIM_LIGHT_PICK, PT_DIM_LIGHT_V   next-event estimation: the light pick, whose leftover
 *                                         (its position inside the picked light's cdf interval)
 *                                         is the first surface coordinate, and the second one
 *     PT_DIM_BSDF_U, PT_DIM_BSDF_V        BSDF direction
 *     PT_DIM_ROULETTE, PT_DIM_LOBE        Russian roulette; lobe choice of layered materials
 *     PT_DIM_LIGHT_TYPE, PT_DIM_ALPHA     choice between light kinds (triangles, environment,
 *                                         punctual); alpha (cut-out) test
 *     PT_DIM_ENV_U, PT_DIM_ENV_V          environment light sample
 *     pairs 5 to 7                        free for later techniques
 * Light kinds and the environment are read by pt_next_event_any (kernels/pt_direct_light.h), the lobe
 * choice by the metallic-roughness material; PT_DIM_ALPHA is unread (alpha decisions hash the
 * path and the triangle instead, kernels/pt_material.h, as a path can pass several surfaces in
 * one bounce). */
#ifndef PT_RNG_H
#define PT_RNG_H

#include "kd_compat.h"
#include "pt_codes.h"

#define PT_DIM_CAMERA_X 0u
#define PT_DIM_CAMERA_Y 1u
#define PT_DIMS_PER_BOUNCE 16u
#define PT_BOUNCE_DIMS(bounce) (2u + (bounce) * PT_DIMS_PER_BOUNCE)
#define PT_DIM_LIGHT_PICK 0u
#define PT_DIM_LIGHT_V 1u
#define PT_DIM_BSDF_U 2u
#define PT_DIM_BSDF_V 3u
#define PT_DIM_ROULETTE 4u
#define PT_DIM_LOBE 5u
#define PT_DIM_LIGHT_TYPE 6u
#define PT_DIM_ALPHA 7u
#define PT_DIM_ENV_U 8u
#define PT_DIM_ENV_V 9u

/* A 32-bit integer hash with low bias (C. Wellons, "Prospecting for Hash Functions"). */
KD_INLINE kd_u32 pt_hash32(kd_u32 x) {
  x ^= x >> 16;
  x *= 0x7feb352du;
  x ^= x >> 15;
  x *= 0x846ca68bu;
  x ^= x >> 16;
  return x;
}

KD_INLINE kd_u32 pt_reverse_bits(kd_u32 x) {
  x = ((x >> 1) & 0x55555555u) | ((x & 0x55555555u) << 1);
  x = ((x >> 2) & 0x33333333u) | ((x & 0x33333333u) << 2);
  x = ((x >> 4) & 0x0f0f0f0fu) | ((x & 0x0f0f0f0fu) << 4);
  x = ((x >> 8) & 0x00ff00ffu) | ((x & 0x00ff00ffu) << 8);
  return (x >> 16) | (x << 16);
}

/* A hash in which bit i of the result depends only on bits 0..i of x and flips with bit i of x:
 * applied to bit-reversed values it is an Owen scramble (each bit flipped by a function of the
 * more significant bits). The Laine-Karras form with the constants Burley 2020 gives. */
KD_INLINE kd_u32 pt_laine_karras(kd_u32 x, kd_u32 seed) {
  x += seed;
  x ^= x * 0x6c50b47cu;
  x ^= x * 0xb82f1e52u;
  x ^= x * 0xc7afe638u;
  x ^= x * 0x8d22f6e6u;
  return x;
}

KD_INLINE kd_u32 pt_owen_scramble(kd_u32 x, kd_u32 seed) {
  return pt_reverse_bits(pt_laine_karras(pt_reverse_bits(x), seed));
}

/* Sobol' dimensions 0 and 1 with the bits of the result reversed (bit k holds the coefficient of
 * 2^-(k+1)), the form the Owen scramble takes. Dimension 0 is the index itself. Dimension 1
 * (primitive polynomial x + 1) has the direction numbers of Pascal's triangle mod 2: result bit k
 * is the XOR of index bits j with C(j, k) odd, i.e. (Lucas) with k a bit-subset of j. That
 * superset XOR over the five bits of a position takes five shift-and-mask steps instead of a loop
 * over the index bits. */
KD_INLINE kd_u32 pt_sobol_reversed(kd_u32 index, kd_u32 dimension) {
  if (dimension == 0u) return index;
  index ^= (index >> 1) & 0x55555555u;
  index ^= (index >> 2) & 0x33333333u;
  index ^= (index >> 4) & 0x0f0f0f0fu;
  index ^= (index >> 8) & 0x00ff00ffu;
  index ^= (index >> 16) & 0x0000ffffu;
  return index;
}

/* The part of a value's hashes that depends on the sample alone: for sobol on (seed, pixel),
 * for independent on (seed, pixel, index). A path computes it once (PtPath.sample_hash) rather
 * than once per value; pt_hashed_bits then gives the same bits as pt_sample_bits. */
KD_INLINE kd_u32 pt_sample_hash(kd_u32 sampler, kd_u32 seed, kd_u32 pixel, kd_u32 index) {
  if (sampler == PT_SAMPLER_INDEPENDENT) return pt_hash32(pt_hash32(pt_hash32(seed ^ 0x9e3779b9u) ^ pixel) ^ index);
  return pt_hash32(pt_hash32(seed ^ 0x5851f42du) ^ pixel);
}

/* The seeds of one dimension pair of one pixel: the index shuffle and the two coordinates' scrambles. */
KD_INLINE kd_u32 pt_pair_seed(kd_u32 sample_hash, kd_u32 pair) { return pt_hash32(sample_hash ^ pair); }
KD_INLINE kd_u32 pt_shuffled_index(kd_u32 pair_seed, kd_u32 index) {
  return pt_owen_scramble(index, pt_hash32(pair_seed ^ 0x68e31da4u));
}
/* pt_owen_scramble of Sobol' coordinate c, whose first bit reversal undoes pt_sobol_reversed's. */
KD_INLINE kd_u32 pt_scrambled_sobol(kd_u32 pair_seed, kd_u32 shuffled, kd_u32 c) {
  return pt_reverse_bits(pt_laine_karras(pt_sobol_reversed(shuffled, c), pt_hash32(pair_seed ^ (0xb5297a4du + c))));
}

KD_INLINE kd_u32 pt_hashed_bits(kd_u32 sampler, kd_u32 sample_hash, kd_u32 index, kd_u32 dimension) {
  if (sampler == PT_SAMPLER_INDEPENDENT) return pt_hash32(sample_hash ^ dimension);
  kd_u32 pair_seed = pt_pair_seed(sample_hash, dimension >> 1);
  return pt_scrambled_sobol(pair_seed, pt_shuffled_index(pair_seed, index), dimension & 1u);
}

/* Both dimensions of the pair starting at even `dimension`, the bits pt_hashed_bits gives, sharing
 * the seeds and the shuffle. */
typedef struct PtBits2 {
  kd_u32 x, y;
} PtBits2;
KD_INLINE PtBits2 pt_hashed_bits2(kd_u32 sampler, kd_u32 sample_hash, kd_u32 index, kd_u32 dimension) {
  PtBits2 bits;
  if (sampler == PT_SAMPLER_INDEPENDENT) {
    bits.x = pt_hash32(sample_hash ^ dimension);
    bits.y = pt_hash32(sample_hash ^ (dimension + 1u));
    return bits;
  }
  kd_u32 pair_seed = pt_pair_seed(sample_hash, dimension >> 1);
  kd_u32 shuffled = pt_shuffled_index(pair_seed, index);
  bits.x = pt_scrambled_sobol(pair_seed, shuffled, 0u);
  bits.y = pt_scrambled_sobol(pair_seed, shuffled, 1u);
  return bits;
}

/* The sampler's values by their coordinates. */
KD_INLINE kd_u32 pt_sample_bits(kd_u32 sampler, kd_u32 seed, kd_u32 pixel, kd_u32 index, kd_u32 dimension) {
  return pt_hashed_bits(sampler, pt_sample_hash(sampler, seed, pixel, index), index, dimension);
}
KD_INLINE PtBits2 pt_sample_bits2(kd_u32 sampler, kd_u32 seed, kd_u32 pixel, kd_u32 index, kd_u32 dimension) {
  return pt_hashed_bits2(sampler, pt_sample_hash(sampler, seed, pixel, index), index, dimension);
}

/* Uniform in [0, 1): the top 24 bits, exactly representable as float. */
KD_INLINE float pt_bits_to_unit(kd_u32 bits) { return (float)(bits >> 8) * (1.0f / 16777216.0f); }

KD_INLINE float pt_sample(kd_u32 sampler, kd_u32 seed, kd_u32 pixel, kd_u32 index, kd_u32 dimension) {
  return pt_bits_to_unit(pt_sample_bits(sampler, seed, pixel, index, dimension));
}

#endif /* PT_RNG_H */
