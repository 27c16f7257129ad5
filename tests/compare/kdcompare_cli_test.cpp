// kdcompare as a user runs it: exit codes, thresholds, JSON, heat map, and the failures.
#include <subprocess.h>
#include "synthetic_images.h"
#include "test_corpus.h"

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <limits>

namespace fs = std::filesystem;
using kdray::test::constant_pixels;
using kdray::test::shell_quoted;
using kdray::test::run_command;
using kdray::test::ToolRun;

namespace {

// test.exr differs from reference.exr by 0.25 in R only (overall RMSE sqrt(0.0625/3) = 0.144,
// PSNR with peak 1 = 16.8 dB); small.exr has another size.
class KdCompareCli : public kdray::test::TempDirTest<> {
 protected:
  void SetUp() override {
    kdray::test::write_test_image(path("test.exr"), 4, 4, {"R", "G", "B"}, constant_pixels(4, 4, {0.5f, 0.5f, 0.5f}));
    kdray::test::write_test_image(path("reference.exr"), 4, 4, {"R", "G", "B"},
                                  constant_pixels(4, 4, {0.75f, 0.5f, 0.5f}));
    kdray::test::write_test_image(path("small.exr"), 2, 4, {"R", "G", "B"}, constant_pixels(2, 4, {0.5f, 0.5f, 0.5f}));
  }

  ToolRun kdcompare(const std::string& test, const std::string& reference, const std::string& options = "") const {
    return run_command(shell_quoted(kdray::test::tool_path("kdcompare")) + " " + shell_quoted(path(test)) + " " +
                       shell_quoted(path(reference)) + " " + options);
  }
};

}  // namespace

TEST_F(KdCompareCli, IdenticalImagesExitZeroWithInfinitePsnrAsNull) {
  const ToolRun run = kdcompare("test.exr", "test.exr", "--json --threshold psnr=100 --threshold rmse=0");
  ASSERT_EQ(run.exit_code, 0) << run.out;
  const auto document = nlohmann::json::parse(run.out);
  EXPECT_EQ(document["rmse"], 0.0);
  EXPECT_TRUE(document["psnr"].is_null());
  EXPECT_TRUE(document["passed"].get<bool>());
}

TEST_F(KdCompareCli, JsonNamesTheOverallFigures) {
  const ToolRun run = kdcompare("test.exr", "reference.exr", "--json");
  ASSERT_EQ(run.exit_code, 0) << run.out;
  const auto document = nlohmann::json::parse(run.out);
  for (const char* name : {"rmse", "relmse", "mae", "psnr", "max_abs", "mean_test", "mean_reference",
                           "nonfinite_test", "nonfinite_reference"}) {
    EXPECT_TRUE(document.contains(name)) << name;
  }
  EXPECT_NEAR(document["rmse"].get<double>(), std::sqrt(0.0625 / 3), 1e-9);
  EXPECT_NEAR(document["per_channel"]["R"]["rmse"].get<double>(), 0.25, 1e-9);
}

TEST_F(KdCompareCli, ErrorAboveThresholdExitsThree) {
  EXPECT_EQ(kdcompare("test.exr", "reference.exr", "--threshold rmse=0.2").exit_code, 0);
  EXPECT_EQ(kdcompare("test.exr", "reference.exr", "--threshold rmse=0.1").exit_code, 3);
  EXPECT_EQ(kdcompare("test.exr", "reference.exr", "--threshold max_abs=0.25").exit_code, 0);  // equal is within
  EXPECT_EQ(kdcompare("test.exr", "reference.exr", "--threshold rmse=0.2 --threshold mae=0.01").exit_code, 3);
}

TEST_F(KdCompareCli, PsnrThresholdFailsWhenBelow) {
  EXPECT_EQ(kdcompare("test.exr", "reference.exr", "--threshold psnr=16").exit_code, 0);
  EXPECT_EQ(kdcompare("test.exr", "reference.exr", "--threshold psnr=17").exit_code, 3);
}

TEST_F(KdCompareCli, NonFiniteThresholdCountsTestPixels) {
  std::vector<float> pixels = constant_pixels(4, 4, {0.5f, 0.5f, 0.5f});
  pixels[4] = std::numeric_limits<float>::quiet_NaN();
  kdray::test::write_test_image(path("nan.exr"), 4, 4, {"R", "G", "B"}, pixels);
  EXPECT_EQ(kdcompare("nan.exr", "reference.exr", "--threshold nonfinite=0").exit_code, 3);
  EXPECT_EQ(kdcompare("nan.exr", "reference.exr", "--threshold nonfinite=1").exit_code, 0);
  EXPECT_EQ(kdcompare("test.exr", "reference.exr", "--threshold nonfinite=0").exit_code, 0);
}

TEST_F(KdCompareCli, SizeMismatchFails) {
  EXPECT_EQ(kdcompare("test.exr", "small.exr").exit_code, 1);
  EXPECT_EQ(kdcompare("test.exr", "reference.exr", "--channels Z").exit_code, 1);
}

TEST_F(KdCompareCli, UnreadableFileFails) {
  { std::ofstream(path("garbage.exr")) << "not an image"; }
  EXPECT_EQ(kdcompare("test.exr", "missing.exr").exit_code, 1);
  EXPECT_EQ(kdcompare("garbage.exr", "reference.exr").exit_code, 1);
  EXPECT_EQ(kdcompare("test.exr", "reference.exr", "--heatmap " + shell_quoted(path("no-dir/map.png"))).exit_code, 1);
}

TEST_F(KdCompareCli, BadArgumentsExitTwo) {
  EXPECT_EQ(kdcompare("test.exr", "reference.exr", "--threshold rmse").exit_code, 2);
  EXPECT_EQ(kdcompare("test.exr", "reference.exr", "--threshold speed=1").exit_code, 2);
  EXPECT_EQ(kdcompare("test.exr", "reference.exr", "--threshold rmse=abc").exit_code, 2);
  EXPECT_EQ(run_command(shell_quoted(kdray::test::tool_path("kdcompare")) + " only-one.exr").exit_code, 2);
}

TEST_F(KdCompareCli, HeatmapIsWrittenAsAPng) {
  const ToolRun run = kdcompare("test.exr", "reference.exr", "--heatmap " + shell_quoted(path("map.png")));
  ASSERT_EQ(run.exit_code, 0) << run.out;
  auto input = OIIO::ImageInput::open(path("map.png"));
  ASSERT_TRUE(input);
  EXPECT_EQ(input->spec().width, 4);
  EXPECT_EQ(input->spec().nchannels, 3);
  for (const auto& entry : fs::directory_iterator(dir_)) {
    EXPECT_EQ(entry.path().string().find(".tmp-"), std::string::npos) << "left behind: " << entry.path();
  }
}

TEST_F(KdCompareCli, HelpDocumentsExitCodesAndPsnrPeak) {
  const ToolRun run = run_command(shell_quoted(kdray::test::tool_path("kdcompare")) + " --help");
  ASSERT_EQ(run.exit_code, 0);
  EXPECT_NE(run.out.find("Exit status"), std::string::npos);
  EXPECT_NE(run.out.find("  3  compared, and a metric is worse"), std::string::npos);
  EXPECT_NE(run.out.find("peak"), std::string::npos);
}
