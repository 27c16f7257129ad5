// kdrender --device all / a list: one render split across OpenCL devices by their speed equals
// the single-device render bit for bit. PoCL exposes two CPU devices here (POCL_DEVICES="pthread
// pthread", one core each), so the split runs on any machine.
#include "render_fixture.h"

#include <kdray/image_io.h>

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

namespace kdray {
namespace {

namespace fs = std::filesystem;

class MultiDevice : public test::CornellFilesTest<MultiDevice> {
 protected:
  // kdrender on two single-core PoCL CPU devices.
  static test::ToolRun kdrender(const std::string& output, const std::string& extra) {
    return test::run_command("POCL_DEVICES='pthread pthread' POCL_MAX_PTHREAD_COUNT=1 " +
                             test::shell_quoted(test::tool_path("kdrender")) + " " + scene_ + " " + tree_ + " -o " +
                             path(output) +
                             " --width 24 --height 20 --spp 12 --sample-offset 3 --seed 4 --cam-pos 278,273,-800 "
                             "--cam-target 278,273,0 --fov 39.3077 " + extra);
  }
};

TEST_F(MultiDevice, TwoDevicesGiveTheSingleDeviceImageAndReportTheirShares) {
  test::ToolRun listed = test::run_command("POCL_DEVICES='pthread pthread' " +
                                           test::shell_quoted(test::tool_path("kdrender")) + " --device list --json");
  ASSERT_EQ(listed.exit_code, 0) << listed.out;
  ASSERT_EQ(nlohmann::json::parse(listed.out)["devices"].size(), 2u) << "PoCL did not expose two devices";

  ASSERT_EQ(kdrender("one.exr", "--device 0 --quiet").exit_code, 0);
  for (const char* devices : {"all", "1,0"}) {
    test::ToolRun run = kdrender("split.exr", std::string("--device ") + devices + " --json");
    ASSERT_EQ(run.exit_code, 0) << run.out;
    Film one = read_film_exr(path("one.exr")), split = read_film_exr(path("split.exr"));
    EXPECT_EQ(split.sums, one.sums) << devices;
    EXPECT_EQ(split.sample_offset, 3u);
    EXPECT_EQ(split.sample_count, 12u);

    nlohmann::json report = nlohmann::json::parse(run.out);
    ASSERT_EQ(report["devices"].size(), 2u) << run.out;
    uint32_t samples = 0;
    double share = 0;
    for (const auto& device : report["devices"]) {
      EXPECT_GE(device["samples"].get<uint32_t>(), 1u) << run.out;  // every device renders a first pass
      EXPECT_GT(device["samples_per_second"].get<double>(), 0.0) << run.out;
      samples += device["samples"].get<uint32_t>();
      share += device["share"].get<double>();
    }
    EXPECT_EQ(samples, 12u);
    EXPECT_DOUBLE_EQ(share, 1.0);
    EXPECT_EQ(report["devices"][0]["index"], std::string(devices) == "all" ? 0 : 1);
  }
}

TEST_F(MultiDevice, RefusesUnknownAndRepeatedDevices) {
  for (const char* devices : {"0,0", "0,7", "0,"}) {
    test::ToolRun run = kdrender("bad.exr", std::string("--device ") + devices + " 2>&1");
    EXPECT_EQ(run.exit_code, 1) << devices << ": " << run.out;
    EXPECT_NE(run.out.find("kdrender: error: OpenCL device"), std::string::npos) << run.out;
  }
  EXPECT_FALSE(fs::exists(path("bad.exr")));
}

}  // namespace
}  // namespace kdray
