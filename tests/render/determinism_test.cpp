// Byte-identical images: across runs, local sizes, the two kernel forms, and between one
// sample range and two merged halves (in memory and through EXR files).
#include "render_fixture.h"
#include "test_scenes.h"

#include <kdray/error.h>
#include <kdray/image_io.h>
#include <kdray/render.h>

#include <gtest/gtest.h>

#include <OpenImageIO/imageio.h>

#include <cmath>
#include <cstring>

namespace kdray {
namespace {

class FeatureRoom : public ::testing::Test {
 protected:
  static void SetUpTestSuite() {
    scene_ = new Scene(test::make_feature_room());
    tree_ = new KdTree(test::tree_for(*scene_));
  }
  static void TearDownTestSuite() {
    delete tree_;
    delete scene_;
  }
  static Film render_room(uint32_t spp, uint32_t offset, const DeviceSelection& device = {},
                          RenderForm form = RenderForm::Megakernel, RenderStats* stats = nullptr) {
    RenderSettings settings = test::tiny_settings(24, spp);
    settings.sample_offset = offset;
    settings.seed = 7;
    settings.form = form;
    settings.aov_albedo = settings.aov_normal = settings.aov_depth = true;
    return render(*scene_, *tree_, settings, device, stats);
  }
  static Scene* scene_;
  static KdTree* tree_;
};
Scene* FeatureRoom::scene_ = nullptr;
KdTree* FeatureRoom::tree_ = nullptr;

TEST_F(FeatureRoom, CompilesEveryFeatureAndOnlyThose) {
  std::string options = kernel_feature_options(*scene_, {}, {});
  for (const char* feature : {"EMISSION", "MIRROR", "GLOSSY", "GLASS", "TEXTURES", "NORMALS"}) {
    EXPECT_NE(options.find(std::string("-DKD_FEATURE_") + feature), std::string::npos) << feature;
  }
  Material diffuse;
  Scene plain = test::make_inward_cube(diffuse);
  RenderSettings unlit;
  unlit.default_light = false;
  EXPECT_EQ(kernel_feature_options(plain, unlit, {}).find("KD_FEATURE"), std::string::npos);
}

TEST_F(FeatureRoom, RendersFiniteLitImage) {
  RenderStats stats;
  Film film = render_room(8, 0, {}, RenderForm::Megakernel, &stats);
  EXPECT_EQ(stats.nonfinite_values, 0u);
  EXPECT_GT(stats.rays, film.pixel_count() * 8);
  for (float value : film.means()) ASSERT_TRUE(std::isfinite(value));
  EXPECT_GT(film.mean_radiance(), 0.05);
}

TEST_F(FeatureRoom, TwoRunsGiveIdenticalSums) {
  EXPECT_EQ(render_room(4, 0).sums, render_room(4, 0).sums);
}

TEST_F(FeatureRoom, LocalSizeDoesNotChangeTheImage) {
  DeviceSelection small, large;
  small.local_size = 8;
  large.local_size = 128;
  EXPECT_EQ(render_room(4, 3, small).sums, render_room(4, 3, large).sums);
}

TEST_F(FeatureRoom, WavefrontAndMegakernelGiveTheSameImage) {
  EXPECT_EQ(render_room(2, 0, {}, RenderForm::Wavefront).sums, render_room(2, 0).sums);
}

TEST_F(FeatureRoom, SixteenSamplesEqualTwoMergedHalves) {
  Film whole = render_room(16, 0);
  Film first = render_room(8, 0), second = render_room(8, 8);
  Film merged = merge_films(second, first);
  EXPECT_EQ(merged.sample_offset, 0u);
  EXPECT_EQ(merged.sample_count, 16u);
  EXPECT_EQ(merged.sums, whole.sums);

  auto dir = test::make_temp_dir("merge");
  std::string a = (dir / "a.exr").string(), b = (dir / "b.exr").string(), w = (dir / "w.exr").string();
  write_film_image(a, first);
  write_film_image(b, second);
  write_film_image(w, whole);
  Film from_files = merge_films(read_film_exr(a), read_film_exr(b));
  EXPECT_EQ(from_files.sums, whole.sums);
  std::vector<float> merged_means = from_files.means(), whole_means = read_film_exr(w).means();
  ASSERT_EQ(merged_means.size(), whole_means.size());
  EXPECT_EQ(std::memcmp(merged_means.data(), whole_means.data(), merged_means.size() * sizeof(float)), 0);
  std::filesystem::remove_all(dir);
}

TEST_F(FeatureRoom, MergeRefusesRangesThatAreNotAdjacent) {
  Film first = render_room(2, 0), third = render_room(2, 4);
  EXPECT_THROW(merge_films(first, third), Error);
  EXPECT_THROW(merge_films(first, first), Error);
}

TEST_F(FeatureRoom, ExrCarriesLayersAndMetadata) {
  auto dir = test::make_temp_dir("exr");
  std::string path = (dir / "room.exr").string();
  write_film_image(path, render_room(2, 5));
  auto in = OIIO::ImageInput::open(path);
  ASSERT_TRUE(in);
  const OIIO::ImageSpec& spec = in->spec();
  for (const char* channel : {"R", "G", "B", "albedo.R", "N.X", "Z"}) {
    EXPECT_NE(std::find(spec.channelnames.begin(), spec.channelnames.end(), channel), spec.channelnames.end())
        << channel;
  }
  EXPECT_EQ(spec.get_int_attribute("kdray:spp"), 2);
  EXPECT_EQ(spec.get_int_attribute("kdray:sample_offset"), 5);
  EXPECT_EQ(spec.get_int_attribute("kdray:seed"), 7);
  EXPECT_EQ(spec.get_int_attribute("kdray:max_bounces"), 8);
  EXPECT_EQ(spec.get_string_attribute("kdray:scene_hash").size(), 16u);
  EXPECT_EQ(spec.get_string_attribute("kdray:tree_hash").size(), 16u);
  in->close();
  std::filesystem::remove_all(dir);
}

TEST_F(FeatureRoom, TimeLimitStopsAtAWholePass) {
  RenderSettings settings = test::tiny_settings(24, 100000);
  settings.time_limit_seconds = 0.2;
  RenderStats stats;
  Film film = render(*scene_, *tree_, settings, {}, &stats);
  EXPECT_GE(film.sample_count, 1u);
  EXPECT_LT(film.sample_count, 100000u);
  EXPECT_EQ(film.sample_count, stats.samples_rendered);
}

}  // namespace
}  // namespace kdray
