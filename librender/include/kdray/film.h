// The film: per-pixel channel sums of a sample range in fixed point, so that ranges rendered
// apart merge exactly.
//
// Merge rule: every sample's value of every channel is rounded to the nearest multiple of
// 2^-20 (kFilmFixedBits, kernels/pt_codes.h) and summed as a 64-bit integer. Integer addition is
// associative, so the sums of samples K..K+N-1 do not depend on how the range was split, on the
// order of the additions or on the device; merging two adjacent ranges adds their sums. The
// image is sum / (N * 2^20) per pixel, computed the same way for every film, so one 16-sample
// render and two merged 8-sample ranges give the same bytes.
#pragma once

#include <kernels/pt_codes.h>

#include <cstdint>
#include <optional>
#include <string>
#include <utility>
#include <vector>

namespace kdray {

constexpr int kFilmFixedBits = PT_FIXED_BITS;

// Where sample values come from (kernels/pt_rng.h), numbered as the kernels number them.
enum class Sampler : uint32_t {
  Sobol = PT_SAMPLER_SOBOL,              // Owen-scrambled, shuffled Sobol' points in padded 2D pairs (the default)
  Independent = PT_SAMPLER_INDEPENDENT,  // hashed independent uniform numbers
};
const char* sampler_name(Sampler sampler);  // "sobol", "independent"
std::optional<Sampler> parse_sampler(const std::string& name);

struct Film {
  uint32_t width = 0, height = 0;
  std::vector<std::string> channels;  // "R","G","B", then AOVs: "albedo.R/G/B", "N.X/Y/Z", "Z"
  std::vector<int64_t> sums;          // pixel-major: (y * width + x) * channels.size() + channel
  uint32_t sample_offset = 0, sample_count = 0;
  uint32_t seed = 0, max_bounces = 0;
  Sampler sampler = Sampler::Sobol;
  uint64_t scene_hash = 0, tree_hash = 0;
  // Everything else that decides the pixels: camera, environment, default light, MIS switch
  // (render_settings_hash in render.h); 0 in images written before it was recorded.
  uint64_t settings_hash = 0;
  double render_seconds = 0;  // summed over merged ranges

  size_t pixel_count() const { return size_t(width) * height; }
  // Mean of each channel per pixel, same layout as sums (0 when no samples).
  std::vector<float> means() const;
  // Mean radiance over all pixels and the three colour channels.
  double mean_radiance() const;
};

// The film of samples min(offsets)..: a and b must have the same size, channels, seed, bounces,
// sampler and hashes, and adjacent sample ranges (in either order). Throws kdray::Error otherwise.
Film merge_films(const Film& a, const Film& b);

struct NamedFilm {
  std::string name;  // the file it came from, for messages
  Film film;
};

// Merges sample ranges of one render given in any order. Every film must be of the same render
// as the first (size, channels, seed, bounces, sampler, scene, tree and settings hashes); sorted
// by offset, the ranges must neither overlap nor leave a gap; with `expected_range` (first
// sample, count) they must cover exactly it. Throws kdray::Error naming the offending film.
Film merge_film_ranges(std::vector<NamedFilm> films,
                       std::optional<std::pair<uint32_t, uint32_t>> expected_range = std::nullopt);

}  // namespace kdray
