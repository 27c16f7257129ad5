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

/* The bit mixers below are written once as statement macros over a variable, so that the same
 * operations run on one kd_u32 and on 8 lanes of them (pt_bounce_bits_in_lanes); integer
 * arithmetic gives every lane the scalar function's bits. */

/* A 32-bit integer hash with low bias (C. Wellons, "Prospecting for Hash Functions"). */
#define PT_HASH32_STEPS(x) \
  x ^= x >> 16;            \
  x *= 0x7feb352du;        \
  x ^= x >> 15;            \
  x *= 0x846ca68bu;        \
  x ^= x >> 16
KD_INLINE kd_u32 pt_hash32(kd_u32 x) {
  PT_HASH32_STEPS(x);
  return x;
}

#define PT_REVERSE_BITS_STEPS(x)                                \
  x = ((x >> 1) & 0x55555555u) | ((x & 0x55555555u) << 1);    \
  x = ((x >> 2) & 0x33333333u) | ((x & 0x33333333u) << 2);    \
  x = ((x >> 4) & 0x0f0f0f0fu) | ((x & 0x0f0f0f0fu) << 4);    \
  x = ((x >> 8) & 0x00ff00ffu) | ((x & 0x00ff00ffu) << 8);    \
  x = (x >> 16) | (x << 16)
KD_INLINE kd_u32 pt_reverse_bits(kd_u32 x) {
  PT_REVERSE_BITS_STEPS(x);
  return x;
}

/* A hash in which bit i of the result depends only on bits 0..i of x and flips with bit i of x:
 * applied to bit-reversed values it is an Owen scramble (each bit flipped by a function of the
 * more significant bits). The Laine-Karras form with the constants Burley 2020 gives. */
#define PT_LAINE_KARRAS_STEPS(x, seed) \
  x += seed;                           \
  x ^= x * 0x6c50b47cu;                \
  x ^= x * 0xb82f1e52u;                \
  x ^= x * 0xc7afe638u;                \
  x ^= x * 0x8d22f6e6u
KD_INLINE kd_u32 pt_laine_karras(kd_u32 x, kd_u32 seed) {
  PT_LAINE_KARRAS_STEPS(x, seed);
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
#define PT_SOBOL1_REVERSED_STEPS(index)      \
  index ^= (index >> 1) & 0x55555555u;       \
  index ^= (index >> 2) & 0x33333333u;       \
  index ^= (index >> 4) & 0x0f0f0f0fu;       \
  index ^= (index >> 8) & 0x00ff00ffu;       \
  index ^= (index >> 16) & 0x0000ffffu
KD_INLINE kd_u32 pt_sobol_reversed(kd_u32 index, kd_u32 dimension) {
  if (dimension == 0u) return index;
  PT_SOBOL1_REVERSED_STEPS(index);
  return index;
}

/* The part of a value's hashes that depends on the sample alone: for sobol on (seed, pixel),
 * for independent on (seed, pixel, index). A path computes it once (PtPath.sample_hash) rather
 * than once per value; pt_hashed_bits then gives the same bits as pt_sample_bits. Steps on a
 * variable `hash` of one path's or of 8 paths' (librender/src/path_lanes.h), as the mixers above. */
#define PT_SAMPLE_HASH_STEPS(hash, sampler, seed, pixel, index) \
  if ((sampler) == PT_SAMPLER_INDEPENDENT) {                    \
    hash = pt_hash32((seed) ^ 0x9e3779b9u) ^ (pixel);           \
    PT_HASH32_STEPS(hash);                                      \
    hash ^= (index);                                            \
    PT_HASH32_STEPS(hash);                                      \
  } else {                                                      \
    hash = pt_hash32((seed) ^ 0x5851f42du) ^ (pixel);           \
    PT_HASH32_STEPS(hash);                                      \
  }
KD_INLINE kd_u32 pt_sample_hash(kd_u32 sampler, kd_u32 seed, kd_u32 pixel, kd_u32 index) {
  kd_u32 hash;
  PT_SAMPLE_HASH_STEPS(hash, sampler, seed, pixel, index);
  return hash;
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

/* A bounce's first PT_BOUNCE_LANES dimensions (its pairs 0 to 3: the light pick, the BSDF
 * direction, roulette and lobe, the light kind), computed together in 8 lanes: on a CPU one
 * vector pass costs about what one pair costs in scalar code, and a bounce that shades a surface
 * reads two or three of the pairs. Every lane makes pt_hashed_bits's integer operations, so the
 * bits are the same. In C++ the lanes are GCC's vector extensions (one AVX2 register where the
 * target has it), in OpenCL C a uint8. */
#define PT_BOUNCE_LANES 8u
typedef struct PtBounceBits {
  kd_u32 bits[PT_BOUNCE_LANES];
} PtBounceBits;
#ifdef __OPENCL_VERSION__
typedef uint8 pt_lanes_u32;
#define PT_LANES_U32(a, b, c, d, e, f, g, h) ((uint8)(a, b, c, d, e, f, g, h))
#define PT_LANES_SPLAT(x) ((uint8)(x))
#define PT_LANES_STORE(v, p) vstore8(v, 0, p)
#define PT_LANES_REVERSE_BITS(x) PT_REVERSE_BITS_STEPS(x)
#else
typedef kd_u32 pt_lanes_u32 __attribute__((vector_size(32)));
#define PT_LANES_U32(a, b, c, d, e, f, g, h) (pt_lanes_u32{a, b, c, d, e, f, g, h})
#define PT_LANES_SPLAT(x) (pt_lanes_u32{} + (x))
#define PT_LANES_STORE(v, p) std::memcpy(p, &(v), sizeof(v))
#ifdef __AVX2__
#include <immintrin.h> /* an includer that wraps this header in a namespace includes it before */
/* Each byte's bits reversed by looking up its two nibbles (vpshufb), then each lane's bytes
 * swapped: 7 instructions where the shift-and-mask steps take 25 on vectors, which have no bswap. */
inline pt_lanes_u32 pt_lanes_reverse_bits(pt_lanes_u32 x) {
  const __m256i low_to_high = _mm256_setr_epi8(0x00, 0x80, 0x40, (char)0xc0, 0x20, (char)0xa0, 0x60, (char)0xe0, 0x10,
                                               (char)0x90, 0x50, (char)0xd0, 0x30, (char)0xb0, 0x70, (char)0xf0, 0x00,
                                               (char)0x80, 0x40, (char)0xc0, 0x20, (char)0xa0, 0x60, (char)0xe0, 0x10,
                                               (char)0x90, 0x50, (char)0xd0, 0x30, (char)0xb0, 0x70, (char)0xf0);
  const __m256i high_to_low = _mm256_setr_epi8(0x0, 0x8, 0x4, 0xc, 0x2, 0xa, 0x6, 0xe, 0x1, 0x9, 0x5, 0xd, 0x3, 0xb, 0x7,
                                               0xf, 0x0, 0x8, 0x4, 0xc, 0x2, 0xa, 0x6, 0xe, 0x1, 0x9, 0x5, 0xd, 0x3, 0xb,
                                               0x7, 0xf);
  const __m256i byte_swap = _mm256_setr_epi8(3, 2, 1, 0, 7, 6, 5, 4, 11, 10, 9, 8, 15, 14, 13, 12, 3, 2, 1, 0, 7, 6, 5, 4,
                                             11, 10, 9, 8, 15, 14, 13, 12);
  const __m256i nibble = _mm256_set1_epi8(0x0f);
  const __m256i v = (__m256i)x;
  const __m256i low = _mm256_shuffle_epi8(low_to_high, _mm256_and_si256(v, nibble));
  const __m256i high = _mm256_shuffle_epi8(high_to_low, _mm256_and_si256(_mm256_srli_epi16(v, 4), nibble));
  return (pt_lanes_u32)_mm256_shuffle_epi8(_mm256_or_si256(low, high), byte_swap);
}
#define PT_LANES_REVERSE_BITS(x) x = pt_lanes_reverse_bits(x)
#else
#define PT_LANES_REVERSE_BITS(x) PT_REVERSE_BITS_STEPS(x)
#endif
#endif
/* pt_hashed_bits of each lane's (sample_hash, index, dimension) into the lanes `bits`, from the
 * index with its bits reversed (pt_reverse_bits): the 8 values of one bounce
 * (pt_bounce_bits_in_lanes), or one value of 8 paths (the host's paths in lanes,
 * librender/src/path_lanes.h). Statement macros, as the steps above, so that no function passes
 * 32-byte vectors where the target has no AVX. */
#define PT_HASHED_BITS_IN_LANES(bits, sampler, sample_hash, reversed_index, dimension)        \
  do {                                                                                     \
    if ((sampler) == PT_SAMPLER_INDEPENDENT) {                                             \
      bits = (sample_hash) ^ (dimension);                                                  \
      PT_HASH32_STEPS(bits);                                                               \
    } else {                                                                               \
      pt_lanes_u32 pair_seed, shuffled;                                                    \
      PT_SOBOL_PAIR_IN_LANES(pair_seed, shuffled, sample_hash, reversed_index, dimension); \
      PT_SCRAMBLED_SOBOL_IN_LANES(bits, pair_seed, shuffled, (dimension) & 1u);            \
    }                                                                                      \
  } while (0)
/* The same for both dimensions of each lane's pair that starts at even `dimension`
 * (pt_hashed_bits2): the pair's seed and shuffled index computed once for the two. */
#define PT_HASHED_BITS2_IN_LANES(bits0, bits1, sampler, sample_hash, reversed_index, dimension) \
  do {                                                                                      \
    if ((sampler) == PT_SAMPLER_INDEPENDENT) {                                              \
      bits0 = (sample_hash) ^ (dimension);                                                  \
      PT_HASH32_STEPS(bits0);                                                               \
      bits1 = (sample_hash) ^ ((dimension) + 1u);                                           \
      PT_HASH32_STEPS(bits1);                                                               \
    } else {                                                                                \
      pt_lanes_u32 pair_seed, shuffled;                                                     \
      PT_SOBOL_PAIR_IN_LANES(pair_seed, shuffled, sample_hash, reversed_index, dimension);  \
      PT_SCRAMBLED_SOBOL_IN_LANES(bits0, pair_seed, shuffled, PT_LANES_SPLAT(0u));          \
      PT_SCRAMBLED_SOBOL_IN_LANES(bits1, pair_seed, shuffled, PT_LANES_SPLAT(1u));          \
    }                                                                                       \
  } while (0)
/* The sobol sampler's parts of the above: the pair's seed (pt_pair_seed) and the index shuffled
 * (pt_shuffled_index) into `pair_seed` and `shuffled`; then coordinate `coordinate` (0 or 1 in
 * each lane) of the shuffled point, scrambled (pt_scrambled_sobol), into `bits`. */
#define PT_SOBOL_PAIR_IN_LANES(pair_seed, shuffled, sample_hash, reversed_index, dimension) \
  do {                                                                                   \
    pair_seed = (sample_hash) ^ ((dimension) >> 1);                                      \
    PT_HASH32_STEPS(pair_seed);                                                          \
    pt_lanes_u32 shuffle_seed = pair_seed ^ 0x68e31da4u;                                 \
    PT_HASH32_STEPS(shuffle_seed);                                                       \
    shuffled = (reversed_index);                                                         \
    PT_LAINE_KARRAS_STEPS(shuffled, shuffle_seed);                                       \
    PT_LANES_REVERSE_BITS(shuffled);                                                     \
  } while (0)
#define PT_SCRAMBLED_SOBOL_IN_LANES(bits, pair_seed, shuffled, coordinate)              \
  do {                                                                               \
    const pt_lanes_u32 sobol_coordinate = (coordinate);                              \
    pt_lanes_u32 sobol1 = (shuffled);                                                \
    PT_SOBOL1_REVERSED_STEPS(sobol1);                                                \
    bits = (shuffled) ^ ((sobol1 ^ (shuffled)) & (0u - sobol_coordinate));           \
    pt_lanes_u32 scramble_seed = (pair_seed) ^ (0xb5297a4du + sobol_coordinate);     \
    PT_HASH32_STEPS(scramble_seed);                                                  \
    PT_LAINE_KARRAS_STEPS(bits, scramble_seed);                                      \
    PT_LANES_REVERSE_BITS(bits);                                                     \
  } while (0)
KD_INLINE PtBounceBits pt_bounce_bits_in_lanes(kd_u32 sampler, kd_u32 sample_hash, kd_u32 index, kd_u32 first_dimension) {
  pt_lanes_u32 bits;
  PT_HASHED_BITS_IN_LANES(bits, sampler, PT_LANES_SPLAT(sample_hash), PT_LANES_SPLAT(pt_reverse_bits(index)),
                          PT_LANES_U32(0u, 1u, 2u, 3u, 4u, 5u, 6u, 7u) + first_dimension);
  PtBounceBits out;
  PT_LANES_STORE(bits, out.bits);
  return out;
}

/* One bounce's sample values: pt_hashed_bits of (sampler, sample_hash, index, first_dimension +
 * d). Where PT_BOUNCE_BITS_IN_LANES is defined (CPUs: kdray defines it for PoCL's programs and
 * the host build that has AVX2), the first PT_BOUNCE_LANES are computed at once when the bounce
 * begins to sample; elsewhere (GPUs, where lanes are work-items) each is computed when read, so
 * a bounce pays only for the values it reads. */
typedef struct PtBounceSamples {
  kd_u32 sampler, sample_hash, index, first_dimension;
#ifdef PT_BOUNCE_BITS_IN_LANES
  PtBounceBits lanes;
#endif
} PtBounceSamples;
KD_INLINE PtBounceSamples pt_bounce_samples(kd_u32 sampler, kd_u32 sample_hash, kd_u32 index, kd_u32 first_dimension) {
  PtBounceSamples s;
  s.sampler = sampler;
  s.sample_hash = sample_hash;
  s.index = index;
  s.first_dimension = first_dimension;
#ifdef PT_BOUNCE_BITS_IN_LANES
  s.lanes = pt_bounce_bits_in_lanes(sampler, sample_hash, index, first_dimension);
#endif
  return s;
}
/* Value d of the bounce, and both values of the pair starting at even d. */
KD_INLINE kd_u32 pt_bounce_bits(const PtBounceSamples* s, kd_u32 d) {
#ifdef PT_BOUNCE_BITS_IN_LANES
  if (d < PT_BOUNCE_LANES) return s->lanes.bits[d];
#endif
  return pt_hashed_bits(s->sampler, s->sample_hash, s->index, s->first_dimension + d);
}
KD_INLINE PtBits2 pt_bounce_bits2(const PtBounceSamples* s, kd_u32 d) {
#ifdef PT_BOUNCE_BITS_IN_LANES
  if (d + 1u < PT_BOUNCE_LANES) {
    PtBits2 bits;
    bits.x = s->lanes.bits[d];
    bits.y = s->lanes.bits[d + 1u];
    return bits;
  }
#endif
  return pt_hashed_bits2(s->sampler, s->sample_hash, s->index, s->first_dimension + d);
}

/* Uniform in [0, 1): the top 24 bits, exactly representable as float. */
KD_INLINE float pt_bits_to_unit(kd_u32 bits) { return (float)(bits >> 8) * (1.0f / 16777216.0f); }

KD_INLINE float pt_sample(kd_u32 sampler, kd_u32 seed, kd_u32 pixel, kd_u32 index, kd_u32 dimension) {
  return pt_bits_to_unit(pt_sample_bits(sampler, seed, pixel, index, dimension));
}

#endif /* PT_RNG_H */
