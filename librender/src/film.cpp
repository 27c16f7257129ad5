// Film means and exact merging (see film.h).
#include <kdray/film.h>
#include <kdray/error.h>

#include <kernels/pt_types.h>

#include <algorithm>
#include <cmath>

namespace kdray {

static_assert(kFilmFixedBits == PT_FIXED_BITS, "the film reads the sums the kernels write");

std::vector<float> Film::means() const {
  std::vector<float> values(sums.size(), 0.0f);
  if (sample_count == 0) return values;
  const double scale = 1.0 / (double(sample_count) * std::ldexp(1.0, kFilmFixedBits));
  for (size_t i = 0; i < sums.size(); ++i) values[i] = static_cast<float>(double(sums[i]) * scale);
  return values;
}

double Film::mean_radiance() const {
  std::vector<float> values = means();
  const size_t stride = channels.size();
  double total = 0;
  for (size_t pixel = 0; pixel < pixel_count(); ++pixel) {
    for (size_t c = 0; c < 3; ++c) total += values[pixel * stride + c];
  }
  return pixel_count() ? total / (3.0 * pixel_count()) : 0.0;
}

const char* sampler_name(Sampler sampler) { return sampler == Sampler::Sobol ? "sobol" : "independent"; }

std::optional<Sampler> parse_sampler(const std::string& name) {
  if (name == "sobol") return Sampler::Sobol;
  if (name == "independent") return Sampler::Independent;
  return std::nullopt;
}

Film merge_films(const Film& a, const Film& b) {
  auto mismatch = [](const std::string& what) { return Error("", "cannot merge: the images differ in " + what); };
  if (a.width != b.width || a.height != b.height) throw mismatch("size");
  if (a.channels != b.channels) throw mismatch("channels (AOVs)");
  if (a.seed != b.seed) throw mismatch("seed");
  if (a.max_bounces != b.max_bounces) throw mismatch("max bounces");
  if (a.sampler != b.sampler) throw mismatch("sampler");
  if (a.scene_hash != b.scene_hash || a.tree_hash != b.tree_hash) throw mismatch("scene or tree");
  const Film& first = a.sample_offset <= b.sample_offset ? a : b;
  const Film& second = &first == &a ? b : a;
  if (uint64_t(first.sample_offset) + first.sample_count != second.sample_offset) {
    throw Error("", "cannot merge: sample ranges " + std::to_string(first.sample_offset) + ".." +
                        std::to_string(uint64_t(first.sample_offset) + first.sample_count) + " and " +
                        std::to_string(second.sample_offset) + ".." +
                        std::to_string(uint64_t(second.sample_offset) + second.sample_count) +
                        " are not adjacent (end exclusive)");
  }
  Film merged = first;
  merged.sample_count = first.sample_count + second.sample_count;
  merged.render_seconds = first.render_seconds + second.render_seconds;
  for (size_t i = 0; i < merged.sums.size(); ++i) merged.sums[i] += second.sums[i];
  return merged;
}

}  // namespace kdray
