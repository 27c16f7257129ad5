// Film means and exact merging (see film.h).
#include <kdray/film.h>
#include <kdray/error.h>
#include <kdray/util.h>

#include <algorithm>
#include <cmath>

namespace kdray {

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

namespace {

// Inclusive, as kdrender prints ranges: "samples 8..15".
std::string sample_range(uint64_t first, uint64_t count) {
  return "samples " + std::to_string(first) + ".." + std::to_string(first + count - 1);
}

// Throws naming `name` when `film` is not a sample range of the same render as `first`.
void check_same_render(const NamedFilm& first, const NamedFilm& other) {
  const Film &a = first.film, &b = other.film;
  auto refuse = [&](const std::string& what, const std::string& mine, const std::string& theirs) {
    return Error(other.name, "not a sample range of the same render as " + first.name + ": it differs in " + what +
                                 " (" + theirs + " here, " + mine + " there)");
  };
  auto number = [](uint64_t v) { return std::to_string(v); };
  if (a.width != b.width || a.height != b.height) {
    throw refuse("size", number(a.width) + "x" + number(a.height), number(b.width) + "x" + number(b.height));
  }
  if (a.channels != b.channels) {
    throw refuse("channels (AOVs)", number(a.channels.size()) + " channels", number(b.channels.size()) + " channels");
  }
  if (a.seed != b.seed) throw refuse("seed", number(a.seed), number(b.seed));
  if (a.max_bounces != b.max_bounces) throw refuse("max bounces", number(a.max_bounces), number(b.max_bounces));
  if (a.sampler != b.sampler) throw refuse("sampler", sampler_name(a.sampler), sampler_name(b.sampler));
  if (a.scene_hash != b.scene_hash) throw refuse("scene", hash_hex(a.scene_hash), hash_hex(b.scene_hash));
  if (a.tree_hash != b.tree_hash) throw refuse("tree", hash_hex(a.tree_hash), hash_hex(b.tree_hash));
  if (a.settings_hash != b.settings_hash) {
    throw refuse("settings (camera, environment, lights)", hash_hex(a.settings_hash), hash_hex(b.settings_hash));
  }
}

}  // namespace

Film merge_film_ranges(std::vector<NamedFilm> films, std::optional<std::pair<uint32_t, uint32_t>> expected_range) {
  if (films.empty()) throw Error("", "nothing to merge");
  for (size_t i = 1; i < films.size(); ++i) check_same_render(films.front(), films[i]);
  std::stable_sort(films.begin(), films.end(),
                   [](const NamedFilm& a, const NamedFilm& b) { return a.film.sample_offset < b.film.sample_offset; });
  for (const NamedFilm& named : films) {
    if (named.film.sample_count == 0) throw Error(named.name, "holds no samples");
  }
  Film merged = films.front().film;
  uint64_t end = uint64_t(merged.sample_offset) + merged.sample_count;
  for (size_t i = 1; i < films.size(); ++i) {
    const NamedFilm &previous = films[i - 1], &next = films[i];
    const Film& film = next.film;
    const std::string previous_range = sample_range(previous.film.sample_offset, previous.film.sample_count);
    if (film.sample_offset < end) {
      throw Error(next.name, sample_range(film.sample_offset, film.sample_count) + " overlap " + previous_range +
                                 " of " + previous.name);
    }
    if (film.sample_offset > end) {
      throw Error(next.name, "starts at sample " + std::to_string(film.sample_offset) + ", but " + previous.name +
                                 " ends at " + std::to_string(end - 1) + ": " +
                                 sample_range(end, film.sample_offset - end) + " are missing");
    }
    for (size_t k = 0; k < merged.sums.size(); ++k) merged.sums[k] += film.sums[k];
    merged.render_seconds += film.render_seconds;
    end += film.sample_count;
  }
  merged.sample_count = static_cast<uint32_t>(end - merged.sample_offset);
  if (expected_range) {
    const uint64_t want_first = expected_range->first, want_end = want_first + expected_range->second;
    const std::string have = sample_range(merged.sample_offset, merged.sample_count);
    const std::string want = sample_range(want_first, expected_range->second);
    if (merged.sample_offset > want_first) {
      throw Error(films.front().name, "the inputs cover " + have + ", not " + want + ": " +
                                          sample_range(want_first, merged.sample_offset - want_first) + " are missing");
    }
    if (end < want_end) {
      throw Error(films.back().name, "the inputs cover " + have + ", not " + want + ": " +
                                         sample_range(end, want_end - end) + " are missing");
    }
    if (merged.sample_offset < want_first || end > want_end) {
      throw Error(merged.sample_offset < want_first ? films.front().name : films.back().name,
                  "the inputs cover " + have + ", more than " + want);
    }
  }
  return merged;
}

Film merge_films(const Film& a, const Film& b) { return merge_film_ranges({{"the first image", a}, {"the second image", b}}); }

}  // namespace kdray
