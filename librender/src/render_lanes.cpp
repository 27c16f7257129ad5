// The host renderer's lane form (RenderForm::Lanes, kdrender --device host --lanes): paths run in
// packets of kLanes, and before each step the sample values of every lane's current bounce are
// hashed together, in one loop over the lanes that the compiler vectorises (an AVX2 clone where the
// CPU has AVX2, chosen at load time). Traversal and shading still run one lane after another. A
// lane whose path ends starts the next (pixel, sample) of its task at once, so the lanes stay
// full until the task's last paths.
//
// The values are the bits pt_hashed_bits gives (integer arithmetic, the same in any lane width),
// and a pixel's sums are fixed-point integers, whose total does not depend on the order of the
// samples: the film is the one render_host.cpp writes one path at a time, bit for bit
// (tests/render/cpu_integrator.h).
#include <kernels/kd_compat.h>

// pt_path_sample and pt_path_sample2 read the values hashed for the packet (kernels/pt_path.h).
namespace {
struct PtPath;
kd_u32 lane_bounce_bits(const PtPath* path, kd_u32 dimension);
}  // namespace
#define PT_GIVEN_BOUNCE_BITS(path, dim) lane_bounce_bits(path, dim)
#include "host_path.h"  // before any other: its defines shape the device code's headers
#include "render_internal.h"

#include <algorithm>
#include <cstdint>

namespace {

constexpr uint32_t kLanes = 8;
// Pixels whose samples one packet renders, together: a task's range is rendered in such blocks.
constexpr uint32_t kBlockPixels = 16;
// The dimension pairs a bounce reads (kernels/pt_rng.h): light pick, BSDF, roulette and lobe,
// light kind, environment.
constexpr uint32_t kBouncePairs = 5;
constexpr uint32_t kEnvironmentPair = PT_DIM_ENV_U / 2;

struct LaneBits {
  kd_u32 dimension[2 * kBouncePairs][kLanes];
};

// For each lane, both values of the pairs whose bit is set in `pairs` (bit p: the bounce's pair
// p), from the dimensions starting at first_dimension[lane].
__attribute__((target_clones("avx2", "default"))) void hash_bounce_bits(uint32_t sampler, const kd_u32* sample_hash,
                                                                        const kd_u32* sample,
                                                                        const kd_u32* first_dimension, uint32_t pairs,
                                                                        LaneBits* bits) {
  for (uint32_t pair = 0; pair < kBouncePairs; ++pair) {
    if (!(pairs >> pair & 1u)) continue;
    for (uint32_t lane = 0; lane < kLanes; ++lane) {
      const PtBits2 two = pt_hashed_bits2(sampler, sample_hash[lane], sample[lane], first_dimension[lane] + 2 * pair);
      bits->dimension[2 * pair][lane] = two.x;
      bits->dimension[2 * pair + 1][lane] = two.y;
    }
  }
}

// A path and where its values are: the path comes first, so that lane_bounce_bits finds the rest
// from the PtPath the device code hands it.
struct LanePath {
  PtPath path;
  const LaneBits* bits;
  uint32_t lane;
  uint32_t block_pixel;  // the pixel's place in its block
};

kd_u32 lane_bounce_bits(const PtPath* path, kd_u32 dimension) {
  const LanePath* lane = reinterpret_cast<const LanePath*>(path);
  return lane->bits->dimension[dimension][lane->lane];
}

// Samples params.sample_offset .. + sample_count - 1 of pixels [first, last) (at most kBlockPixels).
void render_block(const PtSceneData& scene, const PtRenderParams& params, uint32_t first, uint32_t last, int64_t* film,
                  uint64_t* rays, uint32_t* nonfinite) {
  long sums[kBlockPixels][PT_MAX_FILM_CHANNELS] = {};
  const uint32_t paths = (last - first) * params.sample_count;
  uint32_t next_path = 0;
  LaneBits bits;
  LanePath lanes[kLanes];
  bool busy[kLanes];
  // Starts the block's next path in `lane`; false when none is left.
  auto start = [&](uint32_t lane) {
    if (next_path == paths) return false;
    const uint32_t path = next_path++;
    lanes[lane].block_pixel = path / params.sample_count;
    pt_path_begin(&lanes[lane].path, &params, first + lanes[lane].block_pixel,
                  params.sample_offset + path % params.sample_count);
    return true;
  };
  for (uint32_t lane = 0; lane < kLanes; ++lane) {
    lanes[lane].bits = &bits;
    lanes[lane].lane = lane;
    busy[lane] = start(lane);
  }
  // A bounce always reads the first four pairs (the C++ build has every feature in, so the lobe and
  // the light kind are drawn whatever the material and lights); the environment's only when
  // next-event estimation can pick it.
  const uint32_t pairs = 0xfu | (params.select_environment > 0.0f ? 1u << kEnvironmentPair : 0u);
  kd_u32 sample_hash[kLanes] = {}, sample[kLanes] = {}, first_dimension[kLanes] = {};
  while (std::any_of(busy, busy + kLanes, [](bool b) { return b; })) {
    for (uint32_t lane = 0; lane < kLanes; ++lane) {
      const PtPath& path = lanes[lane].path;
      if (!busy[lane]) continue;
      sample_hash[lane] = path.sample_hash;
      sample[lane] = path.sample;
      first_dimension[lane] = PT_BOUNCE_DIMS(path.bounce);
    }
    hash_bounce_bits(params.sampler, sample_hash, sample, first_dimension, pairs, &bits);
    for (uint32_t lane = 0; lane < kLanes; ++lane) {
      if (!busy[lane]) continue;
      PtPath& path = lanes[lane].path;
      *rays += pt_path_step(&path, &scene, &params);
      if (path.alive) continue;
      pt_path_accumulate(&path, &params, sums[lanes[lane].block_pixel], nonfinite);
      busy[lane] = start(lane);
    }
  }
  for (uint32_t pixel = first; pixel != last; ++pixel) {
    for (uint32_t c = 0; c < params.film_channels; ++c)
      film[size_t(pixel) * params.film_channels + c] += sums[pixel - first][c];
  }
}

}  // namespace

namespace kdray {

void render_pixels_in_lanes(const SceneArrays& arrays, const PtRenderParams& params, uint32_t begin, uint32_t end,
                            int64_t* film, uint64_t* rays, uint32_t* nonfinite) {
  const PtSceneData scene = make_scene(arrays, &params);
  for (uint32_t first = begin; first < end; first += kBlockPixels)
    render_block(scene, params, first, std::min(end, first + kBlockPixels), film, rays, nonfinite);
}

}  // namespace kdray
