// kdrender --jobs: a batch frame is the single command's image bit for bit, kernels are built
// once, --resume skips exactly the complete frames, failed frames are listed with exit 1, and
// a bad line is a usage error (exit 2) naming FILE:LINE before anything renders.
#include "render_fixture.h"

#include <kdray/image_io.h>

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include <fstream>
#include <iterator>

namespace kdray {
namespace {

namespace fs = std::filesystem;

class KdrenderBatch : public test::CornellFilesTest<KdrenderBatch> {
 protected:
  static std::string kdrender(const std::string& arguments) {
    return kdrender_command(test::shell_quoted(scene_) + " " + test::shell_quoted(tree_) + " " + arguments);
  }
  // Runs a batch of `lines` with `defaults`; stdout only (the JSON report when --json is given).
  static test::ToolRun batch(const std::string& name, const std::string& lines, const std::string& defaults) {
    std::ofstream(path(name)) << lines;
    return test::run_command(kdrender("--jobs " + test::shell_quoted(path(name)) + " " + defaults));
  }
  static std::string read_bytes(const std::string& file) {
    std::ifstream in(file, std::ios::binary);
    return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
  }

  static constexpr const char* kDefaults = "--width 16 --height 12 --spp 2 --cam-pos 278,273,-800 "
                                           "--cam-target 278,273,0 --fov 39.3077";
};

TEST_F(KdrenderBatch, FramesEqualSingleCommandsBitForBit) {
  // Each line, and the single command it stands for: the batch's defaults where the line sets nothing.
  struct Case {
    std::string output, line, single;
  };
  const std::string view = " --cam-target 278,273,0 --height 12";
  const std::vector<Case> cases = {
      {"f0.exr", "", " --spp 2 --cam-pos 278,273,-800 --fov 39.3077 --width 16"},
      {"f1.exr", " --cam-pos 200,300,-700 --seed 5 --spp 3 --sample-offset 4",
       " --cam-pos 200,300,-700 --seed 5 --spp 3 --sample-offset 4 --fov 39.3077 --width 16"},
      {"f2.exr", " --max-bounces 1 --width 9 --aov albedo,depth",
       " --spp 2 --cam-pos 278,273,-800 --fov 39.3077 --max-bounces 1 --width 9 --aov albedo,depth"},
      {"f3.png", " --fov 50 --sampler independent", " --spp 2 --cam-pos 278,273,-800 --fov 50 --sampler independent --width 16"},
      {"f4.exr", " --no-mis --env-color 0.2,0.3,0.4",
       " --spp 2 --cam-pos 278,273,-800 --fov 39.3077 --no-mis --env-color 0.2,0.3,0.4 --width 16"},
  };
  std::string text = "# frames of the Cornell box\n\n";
  for (const Case& c : cases) text += "  -o " + path(c.output) + c.line + "   # a comment\n";
  // the batch on PoCL, the single commands on the default device (the host here, without a GPU)
  test::ToolRun run = batch("equal.jobs", text, std::string(kDefaults) + " --json --device cpu");
  ASSERT_EQ(run.exit_code, 0) << run.out;
  nlohmann::json report = nlohmann::json::parse(run.out);
  ASSERT_EQ(report["frames"].size(), cases.size());
  EXPECT_EQ(report["rendered"], cases.size());
  // The second frame uses the first one's kernel (same features); the fifth needs another.
  EXPECT_EQ(report["frames"][1]["build_source"], "memory");
  EXPECT_NE(report["frames"][4]["kernel_options"], report["frames"][0]["kernel_options"]);
  EXPECT_EQ(report["frames"][2]["line"], 5);

  for (const Case& c : cases) {
    const std::string alone = path("single-" + c.output);
    test::ToolRun one = test::run_command(kdrender("-o " + alone + view + c.single + " --quiet 2>&1"));
    ASSERT_EQ(one.exit_code, 0) << c.single << ": " << one.out;
    if (c.output.size() > 4 && c.output.substr(c.output.size() - 4) == ".png") {
      EXPECT_EQ(read_bytes(path(c.output)), read_bytes(alone)) << c.line;
      continue;
    }
    Film from_batch = read_film_exr(path(c.output)), from_single = read_film_exr(alone);
    EXPECT_EQ(from_batch.sums, from_single.sums) << c.line;
    EXPECT_EQ(from_batch.channels, from_single.channels) << c.line;
    EXPECT_EQ(from_batch.sample_offset, from_single.sample_offset) << c.line;
    EXPECT_EQ(from_batch.sample_count, from_single.sample_count) << c.line;
    EXPECT_EQ(from_batch.seed, from_single.seed) << c.line;
  }
}

// The host traces a tree copied out of its file when the batch's rays on the host repay the
// copy, as a single command on the host does (not when --resume finds every frame present);
// OpenCL devices read the mapping.
TEST_F(KdrenderBatch, HostFramesTraceTheTreeCopiedOutOfItsFile) {
  const std::string host_frames = "-o " + path("h0.exr") + " --device host\n-o " + path("h1.exr") + "\n";
  test::ToolRun run = batch("host.jobs", host_frames, std::string(kDefaults) + " --json");
  ASSERT_EQ(run.exit_code, 0) << run.out;
  nlohmann::json report = nlohmann::json::parse(run.out);
  EXPECT_EQ(report["tree_memory"], "copied");
  EXPECT_GE(report["tree_copy_seconds"].get<double>(), 0.0);
  // Resumed with every frame present, the batch renders nothing and copies nothing.
  run = batch("host.jobs", host_frames, std::string(kDefaults) + " --resume --json");
  ASSERT_EQ(run.exit_code, 0) << run.out;
  report = nlohmann::json::parse(run.out);
  EXPECT_EQ(report["skipped"], 2);
  EXPECT_EQ(report["tree_memory"], "file mapping");

  run = batch("opencl.jobs", "-o " + path("c0.exr") + " --device cpu\n", std::string(kDefaults) + " --json");
  ASSERT_EQ(run.exit_code, 0) << run.out;
  report = nlohmann::json::parse(run.out);
  EXPECT_EQ(report["tree_memory"], "file mapping");
  EXPECT_FALSE(report.contains("tree_copy_seconds"));

  run = test::run_command(kdrender("-o " + path("single-host.exr") + " --device host --json " + kDefaults));
  ASSERT_EQ(run.exit_code, 0) << run.out;
  EXPECT_EQ(nlohmann::json::parse(run.out)["tree_memory"], "copied");
  EXPECT_EQ(read_film_exr(path("single-host.exr")).sums, read_film_exr(path("h0.exr")).sums);
}

TEST_F(KdrenderBatch, ResumeSkipsOnlyCompleteFrames) {
  const std::string text = "-o " + path("r0.exr") + "\n-o " + path("r1.exr") + "\n-o " + path("r2.png") + "\n-o " +
                           path("r3.exr") + "\n";
  ASSERT_EQ(batch("resume.jobs", text, std::string(kDefaults) + " --quiet").exit_code, 0);
  fs::remove(path("r1.exr"));
  // r3.exr replaced by an image of another sample range: present but not this frame's.
  ASSERT_EQ(test::run_command(kdrender("--width 16 --height 12 --spp 1 --cam-pos 278,273,-800 --cam-target 278,273,0 "
                                       "--fov 39.3077 --quiet -o " + path("other.exr"))).exit_code,
            0);
  fs::copy_file(path("other.exr"), path("r3.exr"), fs::copy_options::overwrite_existing);
  const std::string r0_before = read_bytes(path("r0.exr"));
  test::ToolRun run = batch("resume.jobs", text, std::string(kDefaults) + " --resume --json");
  ASSERT_EQ(run.exit_code, 0) << run.out;
  nlohmann::json report = nlohmann::json::parse(run.out);
  EXPECT_EQ(report["frames"][0]["status"], "skipped");
  EXPECT_EQ(report["frames"][1]["status"], "rendered");
  EXPECT_EQ(report["frames"][2]["status"], "skipped");
  EXPECT_EQ(report["frames"][3]["status"], "rendered");
  EXPECT_EQ(report["skipped"], 2);
  EXPECT_EQ(read_bytes(path("r0.exr")), r0_before);
  EXPECT_EQ(read_film_exr(path("r3.exr")).sample_count, 2u);
}

TEST_F(KdrenderBatch, FailedFramesAreListedAndTheRestRender) {
  const std::string text = "-o " + path("ok0.exr") + "\n-o " + path("no-such-dir/x.exr") + "\n-o " + path("flat.exr") +
                           " --cam-pos 1,2,3 --cam-target 1,2,3\n-o " + path("ok1.exr") + "\n";
  std::ofstream(path("fail.jobs")) << text;
  test::ToolRun run = test::run_command(kdrender("--jobs " + path("fail.jobs") + " " + kDefaults + " 2>&1"));
  EXPECT_EQ(run.exit_code, 1) << run.out;
  EXPECT_NE(run.out.find("2 of 4 frames failed"), std::string::npos) << run.out;
  EXPECT_NE(run.out.find(path("fail.jobs") + ":2 " + path("no-such-dir/x.exr")), std::string::npos) << run.out;
  EXPECT_NE(run.out.find(path("fail.jobs") + ":3 " + path("flat.exr")), std::string::npos) << run.out;
  EXPECT_TRUE(fs::exists(path("ok0.exr")));
  EXPECT_TRUE(fs::exists(path("ok1.exr")));
  EXPECT_FALSE(fs::exists(path("flat.exr")));
}

TEST_F(KdrenderBatch, BadLinesAreUsageErrorsBeforeAnyFrameRenders) {
  const std::pair<const char*, const char*> bad[] = {
      {"--frobnicate", ":2: "},         {"--json", ":2: "},          {"--jobs other", ":2: "},
      {"--spp 0", ":2: "},              {"'unterminated", ":2: "},   {"--cam-pos 1,2", ":2: "},
      {"--aov albedo -o x.png", ":2: "}, {"-o " , ":2: "},
  };
  for (const auto& [line, where] : bad) {
    const std::string first = "-o " + path("never.exr");
    std::ofstream(path("bad.jobs")) << first << "\n" << line << "\n";
    test::ToolRun run = test::run_command(kdrender("--jobs " + path("bad.jobs") + " " + kDefaults + " 2>&1"));
    EXPECT_EQ(run.exit_code, 2) << line << ": " << run.out;
    EXPECT_NE(run.out.find("kdrender: error: " + path("bad.jobs") + where), std::string::npos)
        << line << ": " << run.out;
    EXPECT_FALSE(fs::exists(path("never.exr"))) << line;
  }
  // Two lines writing one file; a file with no frame; a missing file (exit 1, named).
  std::ofstream(path("dup.jobs")) << "-o " << path("d.exr") << "\n# x\n-o " << path("d.exr") << " --seed 2\n";
  test::ToolRun dup = test::run_command(kdrender("--jobs " + path("dup.jobs") + " " + kDefaults + " 2>&1"));
  EXPECT_EQ(dup.exit_code, 2);
  EXPECT_NE(dup.out.find(":3: " + path("d.exr") + " is also written by line 1"), std::string::npos) << dup.out;
  std::ofstream(path("empty.jobs")) << "# nothing\n\n";
  EXPECT_EQ(test::run_command(kdrender("--jobs " + path("empty.jobs") + " 2>&1")).exit_code, 2);
  test::ToolRun missing = test::run_command(kdrender("--jobs " + path("missing.jobs") + " 2>&1"));
  EXPECT_EQ(missing.exit_code, 1);
  EXPECT_NE(missing.out.find(path("missing.jobs")), std::string::npos) << missing.out;
  EXPECT_EQ(test::run_command(kdrender("-o " + path("x.exr") + " --resume 2>&1")).exit_code, 2);
}

}  // namespace
}  // namespace kdray
