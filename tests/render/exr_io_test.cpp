// EXR files go through OpenEXR alone: a film written and read back keeps its exact sums and all
// its metadata, and neither that, nor reading the EXR as an image or an environment map, nor
// kdrender's preload for an EXR output, loads the OpenImageIO module. An executable of its own,
// linked without OpenImageIO (render_tests links it to read films itself), so that its libraries
// are in the process only when librender loads the module.
#include "test_corpus.h"

#include <kdray/environment.h>
#include <kdray/film.h>
#include <kdray/image_compare.h>
#include <kdray/image_io.h>

#include <gtest/gtest.h>

#include <fstream>

namespace kdray {
namespace {

// Whether the process has mapped a file whose path contains `name`.
bool mapped(const std::string& name) {
  std::ifstream maps("/proc/self/maps");
  for (std::string line; std::getline(maps, line);) {
    if (line.find(name) != std::string::npos) return true;
  }
  return false;
}

// Every channel kdrender writes, sums with their high and low words and sign bits set, and
// metadata at the edges of its types.
Film every_channel_film() {
  Film film;
  film.width = 3;
  film.height = 2;
  film.channels = {"R", "G", "B", "albedo.R", "albedo.G", "albedo.B", "N.X", "N.Y", "N.Z", "Z"};
  for (size_t i = 0; i < film.pixel_count() * film.channels.size(); ++i) {
    film.sums.push_back(int64_t(i) * 0x123456789abcd * (i % 2 ? -1 : 1));
  }
  film.sample_offset = 4000000000u;
  film.sample_count = 7;
  film.seed = 3000000000u;  // above INT32_MAX: EXR attributes are signed
  film.max_bounces = 9;
  film.sampler = Sampler::Independent;
  film.scene_hash = 0xfedcba9876543210;
  film.tree_hash = 1;
  film.settings_hash = 0x8000000000000001;
  film.render_seconds = 1.5;
  return film;
}

using ExrWithoutImageModule = test::TempDirTest<>;

TEST_F(ExrWithoutImageModule, FilmsRoundTripExactlyAndOnlyOtherFormatsLoadTheModule) {
  const Film film = every_channel_film();
  const std::string exr = path("film.EXR");  // extensions are matched in any case
  preload_image_io(exr);
  write_film_image(exr, film);
  const Film back = read_film_exr(exr);
  EXPECT_EQ(back.width, film.width);
  EXPECT_EQ(back.height, film.height);
  EXPECT_EQ(back.channels, film.channels);
  EXPECT_EQ(back.sums, film.sums);
  EXPECT_EQ(back.sample_offset, film.sample_offset);
  EXPECT_EQ(back.sample_count, film.sample_count);
  EXPECT_EQ(back.seed, film.seed);
  EXPECT_EQ(back.max_bounces, film.max_bounces);
  EXPECT_EQ(back.sampler, film.sampler);
  EXPECT_EQ(back.scene_hash, film.scene_hash);
  EXPECT_EQ(back.tree_hash, film.tree_hash);
  EXPECT_EQ(back.settings_hash, film.settings_hash);
  EXPECT_EQ(back.render_seconds, film.render_seconds);

  EXPECT_EQ(read_image_size(exr), std::make_pair(film.width, film.height));
  const FloatImage image = read_float_image(exr);
  ASSERT_GE(image.channel_count(), 3u);
  EXPECT_EQ(std::vector<std::string>(image.channel_names.begin(), image.channel_names.begin() + 3),
            (std::vector<std::string>{"R", "G", "B"}));
  write_float_image_atomic(path("map.exr"), image);
  EXPECT_EQ(load_environment(path("map.exr")).width, film.width);

  EXPECT_FALSE(mapped("kdray_image_codec"));
  EXPECT_FALSE(mapped("libOpenImageIO"));
  // The check sees the module once it is loaded: a PNG goes through it.
  write_film_image(path("film.png"), film);
  EXPECT_TRUE(mapped("kdray_image_codec"));
  EXPECT_TRUE(mapped("libOpenImageIO"));
}

}  // namespace
}  // namespace kdray
