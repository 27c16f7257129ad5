// Metrics of kdray::compare_images on tiny images whose answers are worked out by hand.
#include <kdray/error.h>
#include <kdray/image_compare.h>

#include "synthetic_images.h"
#include "test_corpus.h"

#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <limits>

namespace fs = std::filesystem;
using kdray::test::constant_pixels;
using kdray::test::write_test_image;

namespace {

class ImageCompare : public kdray::test::TempDirTest<> {
 protected:
  // Writes the pixels as an EXR and reads them back through the code under test.
  kdray::FloatImage round_trip(const std::string& name, int width, int height, const std::vector<std::string>& channels,
                               const std::vector<float>& pixels) {
    const fs::path path = dir_ / name;
    write_test_image(path, width, height, channels, pixels);
    return kdray::read_float_image(path.string());
  }
};

}  // namespace

TEST_F(ImageCompare, ConstantOffsetInOneChannelGivesKnownFigures) {
  // R differs by 0.1 everywhere (test 0.5, reference 0.6); G and B are equal.
  const auto test = round_trip("t.exr", 4, 2, {"R", "G", "B"}, constant_pixels(4, 2, {0.5f, 0.25f, 0.125f}));
  const auto reference = round_trip("r.exr", 4, 2, {"R", "G", "B"}, constant_pixels(4, 2, {0.75f, 0.25f, 0.125f}));
  const kdray::CompareResult result = kdray::compare_images(test, reference);

  ASSERT_EQ(result.channel_names, (std::vector<std::string>{"R", "G", "B"}));
  const kdray::ErrorMetrics& red = result.per_channel[0];
  EXPECT_DOUBLE_EQ(red.rmse, 0.25);
  EXPECT_DOUBLE_EQ(red.mae, 0.25);
  EXPECT_DOUBLE_EQ(red.max_abs, 0.25);
  EXPECT_DOUBLE_EQ(red.relmse, 0.0625 / (0.5625 + 0.01));
  EXPECT_DOUBLE_EQ(red.psnr, 10 * std::log10(1.0 / 0.0625));  // peak 1: the reference is below 1
  EXPECT_DOUBLE_EQ(red.mean_test, 0.5);
  EXPECT_DOUBLE_EQ(red.mean_reference, 0.75);
  EXPECT_EQ(result.per_channel[1].rmse, 0.0);
  EXPECT_TRUE(std::isinf(result.per_channel[1].psnr));

  // Overall: the mean over every compared sample, so one of three channels carries the error.
  EXPECT_DOUBLE_EQ(result.overall.rmse, std::sqrt(0.0625 / 3));
  EXPECT_DOUBLE_EQ(result.overall.mae, 0.25 / 3);
  EXPECT_DOUBLE_EQ(result.overall.relmse, 0.0625 / (0.5625 + 0.01) / 3);
  EXPECT_DOUBLE_EQ(result.overall.max_abs, 0.25);
  EXPECT_DOUBLE_EQ(result.overall.mean_test, (0.5 + 0.25 + 0.125) / 3);
  EXPECT_EQ(result.compared_pixels, 8u);
}

TEST_F(ImageCompare, RelativeMseWeighsDarkPixelsMore) {
  // The same absolute error of 0.5 over a reference of 0 and of 4: 0.25/0.01 and 0.25/16.01.
  const auto test = round_trip("t.exr", 2, 1, {"Y"}, {0.5f, 4.5f});
  const auto reference = round_trip("r.exr", 2, 1, {"Y"}, {0.0f, 4.0f});
  const kdray::CompareResult result = kdray::compare_images(test, reference);
  EXPECT_DOUBLE_EQ(result.overall.relmse, (0.25 / 0.01 + 0.25 / 16.01) / 2);
  EXPECT_DOUBLE_EQ(result.overall.rmse, 0.5);
}

TEST_F(ImageCompare, PsnrPeakIsTheBrightestReferenceValueForHdrData) {
  const auto test = round_trip("t.exr", 2, 1, {"Y"}, {3.0f, 1.0f});
  const auto reference = round_trip("r.exr", 2, 1, {"Y"}, {4.0f, 1.0f});
  const kdray::CompareResult result = kdray::compare_images(test, reference);
  EXPECT_DOUBLE_EQ(result.peak, 4.0);
  EXPECT_DOUBLE_EQ(result.overall.psnr, 10 * std::log10(16.0 / 0.5));

  kdray::CompareOptions fixed_peak;
  fixed_peak.peak = 1.0;
  EXPECT_DOUBLE_EQ(kdray::compare_images(test, reference, fixed_peak).overall.psnr, 10 * std::log10(1.0 / 0.5));
}

TEST_F(ImageCompare, NonFinitePixelsAreCountedAndLeftOutOfTheFigures) {
  const float nan = std::numeric_limits<float>::quiet_NaN();
  const float inf = std::numeric_limits<float>::infinity();
  const auto test = round_trip("t.exr", 4, 1, {"R", "G"}, {nan, 0, 1, inf, 1, 1, 2, 2});
  const auto reference = round_trip("r.exr", 4, 1, {"R", "G"}, {0, 0, 0, 0, -inf, 0, 1, 1});
  const kdray::CompareResult result = kdray::compare_images(test, reference);
  EXPECT_EQ(result.nonfinite_test, 2u);
  EXPECT_EQ(result.nonfinite_reference, 1u);
  EXPECT_EQ(result.compared_pixels, 1u);  // only the last pixel is finite in both
  EXPECT_DOUBLE_EQ(result.overall.rmse, 1.0);
  EXPECT_DOUBLE_EQ(result.overall.mean_test, 2.0);
}

TEST_F(ImageCompare, NothingComparableGivesNaNFiguresNotZeros) {
  const float nan = std::numeric_limits<float>::quiet_NaN();
  const auto test = round_trip("t.exr", 1, 1, {"Y"}, {nan});
  const auto reference = round_trip("r.exr", 1, 1, {"Y"}, {1.0f});
  const kdray::CompareResult result = kdray::compare_images(test, reference);
  EXPECT_TRUE(std::isnan(result.overall.rmse));
  EXPECT_TRUE(std::isnan(result.overall.psnr));
}

TEST_F(ImageCompare, AlphaIsLeftOutUnlessAskedFor) {
  const auto test = round_trip("t.exr", 1, 1, {"R", "G", "B", "A"}, {1, 1, 1, 0});
  const auto reference = round_trip("r.exr", 1, 1, {"R", "G", "B", "A"}, {1, 1, 1, 1});
  EXPECT_EQ(kdray::compare_images(test, reference).overall.rmse, 0.0);

  kdray::CompareOptions with_alpha;
  with_alpha.channels = {"A"};
  EXPECT_DOUBLE_EQ(kdray::compare_images(test, reference, with_alpha).overall.rmse, 1.0);
}

TEST_F(ImageCompare, ComparesTheRadianceWhenBothHaveRgb) {
  // Like a kdrender EXR with a depth AOV: the extra layer is not the picture.
  const auto test = round_trip("t.exr", 1, 1, {"R", "G", "B", "Z"}, {0.5f, 0.5f, 0.5f, 100.0f});
  const auto reference = round_trip("r.exr", 1, 1, {"R", "G", "B", "Z"}, {0.5f, 0.5f, 0.5f, 7.0f});
  const kdray::CompareResult result = kdray::compare_images(test, reference);
  EXPECT_EQ(result.channel_names, (std::vector<std::string>{"R", "G", "B"}));
  EXPECT_EQ(result.overall.max_abs, 0.0);

  kdray::CompareOptions depth;
  depth.channels = {"Z"};
  EXPECT_DOUBLE_EQ(kdray::compare_images(test, reference, depth).overall.max_abs, 93.0);
}

TEST_F(ImageCompare, WithoutRgbComparesTheChannelsBothHave) {
  const auto test = round_trip("t.exr", 1, 1, {"Y", "Z"}, {0.5f, 100.0f});
  const auto reference = round_trip("r.exr", 1, 1, {"Y"}, {0.25f});
  const kdray::CompareResult result = kdray::compare_images(test, reference);
  EXPECT_EQ(result.channel_names, (std::vector<std::string>{"Y"}));
  EXPECT_DOUBLE_EQ(result.overall.max_abs, 0.25);

  kdray::CompareOptions depth;
  depth.channels = {"Z"};
  EXPECT_THROW(kdray::compare_images(test, reference, depth), kdray::Error);
}

TEST_F(ImageCompare, DifferentSizesThrow) {
  const auto test = round_trip("t.exr", 2, 2, {"Y"}, constant_pixels(2, 2, {0}));
  const auto reference = round_trip("r.exr", 2, 1, {"Y"}, constant_pixels(2, 1, {0}));
  EXPECT_FALSE(kdray::images_same_size(test, reference));
  EXPECT_THROW(kdray::compare_images(test, reference), kdray::Error);
}

TEST_F(ImageCompare, EightBitPngReadsAsZeroToOne) {
  write_test_image(dir_ / "white.png", 2, 2, {"R", "G", "B"}, constant_pixels(2, 2, {1, 1, 1}));
  const kdray::FloatImage image = kdray::read_float_image((dir_ / "white.png").string());
  ASSERT_EQ(image.channel_count(), 3u);
  for (float value : image.pixels) EXPECT_EQ(value, 1.0f);
}

TEST_F(ImageCompare, UnreadableFileThrowsNamingIt) {
  const fs::path garbage = dir_ / "garbage.exr";
  { std::ofstream(garbage) << "not an image"; }
  try {
    kdray::read_float_image(garbage.string());
    FAIL() << "a text file read as an image";
  } catch (const kdray::Error& error) {
    EXPECT_NE(std::string(error.what()).find("garbage.exr"), std::string::npos) << error.what();
  }
  EXPECT_THROW(kdray::read_float_image((dir_ / "missing.exr").string()), kdray::Error);
}

TEST_F(ImageCompare, TruncatedExrThrowsNamingIt) {
  std::vector<float> pixels;
  for (int i = 0; i < 64 * 64 * 3; ++i) pixels.push_back(float(i % 97) / 7);
  write_test_image(dir_ / "whole.exr", 64, 64, {"R", "G", "B"}, pixels);
  std::ifstream whole(dir_ / "whole.exr", std::ios::binary);
  std::string bytes((std::istreambuf_iterator<char>(whole)), std::istreambuf_iterator<char>());
  const fs::path truncated = dir_ / "truncated.exr";
  std::ofstream(truncated, std::ios::binary) << bytes.substr(0, bytes.size() * 2 / 3);
  try {
    kdray::read_float_image(truncated.string());
    FAIL() << "a truncated EXR read";
  } catch (const kdray::Error& error) {
    EXPECT_NE(std::string(error.what()).find("truncated.exr"), std::string::npos) << error.what();
  }
}

namespace {

// EXR goes through OpenEXR, every other format through OpenImageIO, so an EXR from another program
// must read as OpenImageIO read it: the same channels in the same order (R, G, B, A first in each
// layer, X, Y, Z together), the same alpha channel, the same values.
void expect_read_as_openimageio_reads(const std::string& path) {
  auto input = OIIO::ImageInput::open(path);
  ASSERT_TRUE(input) << OIIO::geterror();
  const OIIO::ImageSpec spec = input->spec();
  std::vector<float> pixels(size_t(spec.width) * size_t(spec.height) * size_t(spec.nchannels));
  ASSERT_TRUE(input->read_image(0, 0, 0, spec.nchannels, OIIO::TypeDesc::FLOAT, pixels.data()));
  const kdray::FloatImage image = kdray::read_float_image(path);
  EXPECT_EQ(image.width, spec.width);
  EXPECT_EQ(image.height, spec.height);
  EXPECT_EQ(image.channel_names, spec.channelnames);
  EXPECT_EQ(image.alpha_channel, spec.alpha_channel);
  EXPECT_EQ(image.pixels, pixels);
}

}  // namespace

TEST_F(ImageCompare, HalfFloatLayersReadAsOpenImageIoReadsThem) {
  const std::vector<std::string> channels = {"Z",         "A",         "B",         "G",         "R",
                                             "N.Z",       "N.X",       "N.Y",       "diffuse.A", "diffuse.B",
                                             "diffuse.R", "diffuse.G", "diffuse.Y", "beauty"};
  std::vector<float> pixels;
  for (int i = 0; i < 3 * 2 * int(channels.size()); ++i) pixels.push_back(float(i) * 0.25f);  // exact in half
  const fs::path path = dir_ / "layers.exr";
  write_test_image(path, 3, 2, channels, pixels, OIIO::TypeDesc::HALF);
  expect_read_as_openimageio_reads(path.string());
  const kdray::FloatImage image = kdray::read_float_image(path.string());
  EXPECT_EQ(std::vector<std::string>(image.channel_names.begin(), image.channel_names.begin() + 4),
            (std::vector<std::string>{"R", "G", "B", "A"}));
  EXPECT_EQ(image.alpha_channel, 3);
  EXPECT_EQ(image.at(5, 0), pixels[5 * channels.size() + 4]);  // R of the last pixel
}

TEST_F(ImageCompare, AnotherProgramsExrReadsAsOpenImageIoReadsIt) {
  std::string path;
  KDRAY_CORPUS_FILE(path, "hdri/studio.exr");  // stored B, G, R, DWAB-compressed
  expect_read_as_openimageio_reads(path);
}

TEST_F(ImageCompare, HeatmapIsDarkWhereEqualBrightWhereWrongAndMagentaWhereNaN) {
  const float nan = std::numeric_limits<float>::quiet_NaN();
  const std::vector<float> error = {0.0f, 1.0f, nan, 10.0f};
  kdray::HeatmapOptions options;
  options.scale = 1.0;
  const kdray::FloatImage map = kdray::error_heatmap(error, 2, 2, options);
  ASSERT_EQ(map.pixels.size(), 12u);
  EXPECT_LT(map.pixels[0] + map.pixels[1] + map.pixels[2], 0.1f);   // no error: near black
  EXPECT_GT(map.pixels[3] + map.pixels[4] + map.pixels[5], 2.5f);   // at the scale: pale yellow
  EXPECT_EQ((std::vector<float>{map.pixels[6], map.pixels[7], map.pixels[8]}), (std::vector<float>{1, 0, 1}));
  EXPECT_EQ((std::vector<float>{map.pixels[9], map.pixels[10], map.pixels[11]}),
            (std::vector<float>{map.pixels[3], map.pixels[4], map.pixels[5]}));  // clamped above the scale
}

TEST_F(ImageCompare, HeatmapScaleDefaultsToThe99thPercentile) {
  std::vector<float> error(1000);
  for (size_t i = 0; i < error.size(); ++i) error[i] = float(i % 10);
  error[999] = 1e6f;  // one firefly must not set the scale
  double scale = 0;
  kdray::error_heatmap(error, 100, 10, {}, &scale);
  EXPECT_EQ(scale, 9.0);
}

TEST_F(ImageCompare, AtomicWriteLeavesOnlyTheFinishedFile) {
  kdray::FloatImage image;
  image.width = 3;
  image.height = 1;
  image.channel_names = {"R", "G", "B"};
  image.pixels = {0, 0.5f, 1, 0, 0.5f, 1, 0, 0.5f, 1};
  const fs::path path = dir_ / "out.png";
  kdray::write_float_image_atomic(path.string(), image);
  size_t files = 0;
  for ([[maybe_unused]] const auto& entry : fs::directory_iterator(dir_)) ++files;
  EXPECT_EQ(files, 1u);
  EXPECT_NEAR(kdray::read_float_image(path.string()).pixels[1], 0.5f, 1.0f / 255);
  EXPECT_THROW(kdray::write_float_image_atomic((dir_ / "no-such-dir" / "x.png").string(), image), kdray::Error);
}
