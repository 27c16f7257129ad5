// kdrender's command line: outputs, JSON, merging, the program cache, and every refusal
// (stale tree, damaged file, bad arguments) with its exit code and message.
#include "render_fixture.h"
#include "test_scenes.h"

#include <kdray/image_io.h>

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include <fstream>

namespace kdray {
namespace {

namespace fs = std::filesystem;

class KdrenderCli : public test::CornellFilesTest<KdrenderCli> {
 protected:
  static test::ToolRun kdrender(const std::string& arguments) {
    return test::run_command(kdrender_command(arguments) + " 2>&1");
  }
  static std::string cornell(const std::string& output, const std::string& extra) {
    return test::shell_quoted(scene_) + " " + test::shell_quoted(tree_) + " -o " + test::shell_quoted(output) +
           " --width 16 --height 16 --cam-pos 278,273,-800 --cam-target 278,273,0 --fov 39.3077 " + extra;
  }
};

TEST_F(KdrenderCli, RendersPngAndReportsJsonWithAWarmSecondBuild) {
  test::ToolRun first = kdrender(cornell(path("a.png"), "--spp 2 --json --device cpu"));
  ASSERT_EQ(first.exit_code, 0) << first.out;
  test::ToolRun second = kdrender(cornell(path("b.png"), "--spp 2 --json --device cpu"));
  ASSERT_EQ(second.exit_code, 0) << second.out;
  nlohmann::json report = nlohmann::json::parse(second.out);
  EXPECT_EQ(report["build_source"], "disk cache");
  EXPECT_EQ(report["spp"], 2);
  EXPECT_GT(report["mrays_per_s"].get<double>(), 0.0);
  EXPECT_GT(report["samples_per_second"].get<double>(), 0.0);
  for (const char* key : {"load_seconds", "build_seconds", "render_seconds"}) EXPECT_TRUE(report.contains(key)) << key;
  EXPECT_TRUE(fs::exists(path("a.png")));
  EXPECT_TRUE(fs::exists(path("b.png")));
}

TEST_F(KdrenderCli, MergedRangesEqualOneRender) {
  ASSERT_EQ(kdrender(cornell(path("whole.exr"), "--spp 4 --quiet")).exit_code, 0);
  ASSERT_EQ(kdrender(cornell(path("low.exr"), "--spp 2 --quiet")).exit_code, 0);
  ASSERT_EQ(kdrender(cornell(path("high.exr"), "--spp 2 --sample-offset 2 --quiet")).exit_code, 0);
  test::ToolRun merge =
      kdrender("--merge " + test::shell_quoted(path("high.exr")) + " " + test::shell_quoted(path("low.exr")) + " -o " +
               test::shell_quoted(path("merged.exr")) + " --quiet");
  ASSERT_EQ(merge.exit_code, 0) << merge.out;
  Film whole = read_film_exr(path("whole.exr")), merged = read_film_exr(path("merged.exr"));
  EXPECT_EQ(merged.sums, whole.sums);
  EXPECT_EQ(merged.sample_count, 4u);
  test::ToolRun gap = kdrender("--merge " + test::shell_quoted(path("high.exr")) + " " +
                                     test::shell_quoted(path("high.exr")) + " -o " + test::shell_quoted(path("gap.exr")));
  EXPECT_EQ(gap.exit_code, 1);
  EXPECT_NE(gap.out.find("overlap"), std::string::npos) << gap.out;
  EXPECT_FALSE(fs::exists(path("gap.exr")));
}

TEST_F(KdrenderCli, RefusesAStaleTree) {
  Material grey;
  Scene other = test::make_inward_cube(grey);
  KdTree other_tree = test::tree_for(other);
  write_tree(path("other.kdtree"), other_tree);
  test::ToolRun run = kdrender(test::shell_quoted(scene_) + " " + test::shell_quoted(path("other.kdtree")) + " -o " +
                                     test::shell_quoted(path("stale.png")));
  EXPECT_EQ(run.exit_code, 1);
  EXPECT_NE(run.out.find("kdrender: error:"), std::string::npos) << run.out;
  EXPECT_NE(run.out.find("stale"), std::string::npos) << run.out;
  EXPECT_FALSE(fs::exists(path("stale.png")));
}

TEST_F(KdrenderCli, RefusesADamagedScene) {
  std::string damaged = path("damaged.kdscene");
  fs::copy_file(scene_, damaged, fs::copy_options::overwrite_existing);
  {
    std::fstream file(damaged, std::ios::in | std::ios::out | std::ios::binary);
    file.seekp(static_cast<std::streamoff>(fs::file_size(damaged) / 2));
    file.put('\x5a');
  }
  test::ToolRun run = kdrender(test::shell_quoted(damaged) + " " + test::shell_quoted(tree_) + " -o " +
                                     test::shell_quoted(path("damaged.png")));
  EXPECT_EQ(run.exit_code, 1);
  EXPECT_NE(run.out.find(damaged), std::string::npos) << run.out;
  EXPECT_FALSE(fs::exists(path("damaged.png")));
}

TEST_F(KdrenderCli, BadArgumentsExitWithUsageStatus) {
  const char* bad[] = {"--spp 0", "--width 0", "--aov shadows", "--cam-pos 1,2", "--max-bounces 5000",
                       "--frobnicate", "--cam-pos 0,0,0"};
  for (const char* arguments : bad) {
    test::ToolRun run = kdrender(cornell(path("bad.exr"), arguments));
    EXPECT_EQ(run.exit_code, 2) << arguments << ": " << run.out;
    EXPECT_NE(run.out.find("kdrender: error:"), std::string::npos) << run.out;
  }
  EXPECT_EQ(kdrender(test::shell_quoted(scene_) + " " + test::shell_quoted(tree_)).exit_code, 2);  // no -o
  EXPECT_EQ(kdrender(cornell(path("bad.tiff"), "")).exit_code, 2);
  EXPECT_FALSE(fs::exists(path("bad.exr")));
}

TEST_F(KdrenderCli, AovsNeedAnExrOutputOfEitherCase) {
  EXPECT_EQ(kdrender(cornell(path("aov.png"), "--spp 1 --aov albedo --quiet")).exit_code, 2);
  test::ToolRun run = kdrender(cornell(path("aov.EXR"), "--spp 1 --aov albedo --quiet"));
  ASSERT_EQ(run.exit_code, 0) << run.out;
  EXPECT_TRUE(fs::exists(path("aov.EXR")));
}

// The default marked: the host where no device named renders there, else the OpenCL device.
TEST_F(KdrenderCli, ListsDevices) {
  test::ToolRun run = kdrender("--device list");
  EXPECT_EQ(run.exit_code, 0) << run.out;
  const bool host = device_for_render() == kHostDevice;
  EXPECT_EQ(run.out.find("host: kdray's C++ build on this CPU  [default]") != std::string::npos, host) << run.out;
  EXPECT_EQ(run.out.find(")  [default]") != std::string::npos, !host) << run.out;
  test::ToolRun json = kdrender("--device list --json");
  ASSERT_EQ(json.exit_code, 0) << json.out;
  const nlohmann::json report = nlohmann::json::parse(json.out);
  EXPECT_GE(report["devices"].size(), 1u);
  if (host) {
    EXPECT_EQ(report["default"], "host");
  }
  EXPECT_EQ(kdrender(cornell(path("nodevice.png"), "--device 99")).exit_code, 1);
}

// --device host renders with the C++ build of the kernel's code: the same EXR pixels and sums as
// PoCL (--device cpu), whatever its thread count, and its sample ranges merge with PoCL's.
TEST_F(KdrenderCli, HostWritesTheSameExrAsPocl) {
  const std::string options = "--spp 3 --aov albedo,depth --seed 4 ";
  test::ToolRun host = kdrender(cornell(path("host.exr"), options + "--device host --threads 2 --json"));
  ASSERT_EQ(host.exit_code, 0) << host.out;
  nlohmann::json report = nlohmann::json::parse(host.out);
  EXPECT_EQ(report["device"], "host");
  EXPECT_EQ(report["threads"], 2);
  EXPECT_GT(report["rays"].get<double>(), 0.0);
  ASSERT_EQ(kdrender(cornell(path("host1.exr"), options + "--device host --threads 1 --quiet")).exit_code, 0);
  ASSERT_EQ(kdrender(cornell(path("cpu.exr"), options + "--device cpu --quiet")).exit_code, 0);
  const Film on_host = read_film_exr(path("host.exr")), on_pocl = read_film_exr(path("cpu.exr"));
  EXPECT_EQ(on_host.channels, on_pocl.channels);
  EXPECT_EQ(on_host.sums, on_pocl.sums);
  EXPECT_EQ(on_host.means(), on_pocl.means());
  EXPECT_EQ(read_film_exr(path("host1.exr")).sums, on_pocl.sums);

  ASSERT_EQ(kdrender(cornell(path("pocl-low.exr"), "--spp 1 --aov albedo,depth --seed 4 --device cpu -q")).exit_code, 0);
  ASSERT_EQ(kdrender(cornell(path("host-high.exr"), "--spp 2 --sample-offset 1 --aov albedo,depth --seed 4 "
                                                     "--device host -q")).exit_code, 0);
  test::ToolRun merge = kdrender("--merge " + test::shell_quoted(path("pocl-low.exr")) + " " +
                                 test::shell_quoted(path("host-high.exr")) + " -o " +
                                 test::shell_quoted(path("merged.exr")) + " -q");
  ASSERT_EQ(merge.exit_code, 0) << merge.out;
  EXPECT_EQ(read_film_exr(path("merged.exr")).sums, on_pocl.sums);
}

// --traversal picks the traversal the program compiles (auto: the device's own, the fast path on
// a CPU); the robust code alone renders the same film, and --json says which ran.
TEST_F(KdrenderCli, TraversalsRenderTheSameFilmAndJsonNamesTheOneThatRan) {
  const std::string options = "--spp 2 --seed 5 --device cpu --json ";
  test::ToolRun fast = kdrender(cornell(path("fast.exr"), options));
  ASSERT_EQ(fast.exit_code, 0) << fast.out;
  test::ToolRun robust = kdrender(cornell(path("robust.exr"), options + "--traversal robust"));
  ASSERT_EQ(robust.exit_code, 0) << robust.out;
  const nlohmann::json fast_report = nlohmann::json::parse(fast.out), robust_report = nlohmann::json::parse(robust.out);
  EXPECT_EQ(fast_report["traversal"], "fast");
  EXPECT_EQ(fast_report["devices"][0]["traversal"], "fast");
  EXPECT_EQ(robust_report["traversal"], "robust");
  EXPECT_NE(robust_report["kernel_options"].get<std::string>().find("-DKD_TRAVERSAL_ROBUST_ONLY"), std::string::npos);
  EXPECT_EQ(fast_report["kernel_options"].get<std::string>().find("-DKD_TRAVERSAL_ROBUST_ONLY"), std::string::npos);
  EXPECT_EQ(read_film_exr(path("fast.exr")).sums, read_film_exr(path("robust.exr")).sums);
  test::ToolRun host = kdrender(cornell(path("host-robust.exr"), "--device host --traversal robust"));
  EXPECT_EQ(host.exit_code, 2) << host.out;
  EXPECT_NE(host.out.find("--traversal robust"), std::string::npos) << host.out;
  EXPECT_FALSE(fs::exists(path("host-robust.exr")));
}

// Naming no device: an OpenCL GPU where there is one, else the faster CPU path, the host on an
// x86-64-v3 CPU (kdray::device_for_render); --json says which ran, and the film is PoCL's. An
// option only OpenCL devices take keeps the render on OpenCL, and --threads is taken where the
// host renders.
TEST_F(KdrenderCli, WithNoDeviceNamedRendersOnTheFasterPath) {
  const bool host = device_for_render() == kHostDevice;
  test::ToolRun run = kdrender(cornell(path("default.exr"), "--spp 2 --seed 3 --json"));
  ASSERT_EQ(run.exit_code, 0) << run.out;
  const nlohmann::json report = nlohmann::json::parse(run.out);
  EXPECT_EQ(report["device"] == "host", host) << report["device"];
  if (host && __builtin_cpu_supports("avx2")) {
    EXPECT_EQ(report["build_source"], "built in, x86-64-v3, paths in lanes");
  }
  ASSERT_EQ(kdrender(cornell(path("pocl.exr"), "--spp 2 --seed 3 --device cpu -q")).exit_code, 0);
  EXPECT_EQ(read_film_exr(path("default.exr")).sums, read_film_exr(path("pocl.exr")).sums);

  test::ToolRun wavefront = kdrender(cornell(path("wavefront.exr"), "--spp 1 --wavefront --json"));
  ASSERT_EQ(wavefront.exit_code, 0) << wavefront.out;
  EXPECT_NE(nlohmann::json::parse(wavefront.out)["device"], "host");
  EXPECT_EQ(kdrender(cornell(path("threads.exr"), "--spp 1 --threads 2 -q")).exit_code, host ? 0 : 2);
}

// named, or as the default device where there is no OpenCL platform
TEST_F(KdrenderCli, HostRendersWithoutAnOpenClPlatform) {
  for (const char* device : {"--device host", ""}) {
    const std::string output = path(std::string("no-opencl") + (*device ? "-host" : "") + ".png");
    test::ToolRun run = test::run_command("OCL_ICD_VENDORS=" + test::shell_quoted(path("no-vendors")) + " " +
                                          test::shell_quoted(test::tool_path("kdrender")) + " " +
                                          cornell(output, std::string("--spp 1 -q ") + device) + " 2>&1");
    EXPECT_EQ(run.exit_code, 0) << device << ": " << run.out;
    EXPECT_TRUE(fs::exists(output)) << device;
  }
}

TEST_F(KdrenderCli, WithoutTheImageModuleFailsNamingTheOutputAndWritesNothing) {
  const std::string output = path("no-module.png");
  test::ToolRun run = test::run_command("KDRAY_IMAGE_CODEC=" + test::shell_quoted(path("missing.so")) + " " +
                                        test::shell_quoted(test::tool_path("kdrender")) + " " +
                                        cornell(output, "--spp 2 -q") + " 2>&1");
  EXPECT_EQ(run.exit_code, 1) << run.out;
  EXPECT_NE(run.out.find("kdrender: error: " + output + ": image files cannot be read or written"), std::string::npos)
      << run.out;
  EXPECT_NE(run.out.find("missing.so"), std::string::npos) << run.out;
  EXPECT_FALSE(fs::exists(output));
}

TEST_F(KdrenderCli, WithoutAnOpenClPlatformSaysHowToInstallPocl) {
  // An empty vendor directory hides every ICD from the loader.
  test::ToolRun run = test::run_command("OCL_ICD_VENDORS=" + test::shell_quoted(path("no-vendors")) +
                                              " " + test::shell_quoted(test::tool_path("kdrender")) + " --device list 2>&1");
  EXPECT_EQ(run.exit_code, 1);
  EXPECT_NE(run.out.find("pocl-opencl-icd"), std::string::npos) << run.out;
}

}  // namespace
}  // namespace kdray
