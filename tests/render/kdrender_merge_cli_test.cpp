// Merge safety: kdrender --merge takes shards in any order and refuses, naming the file, shards
// of another render (seed, bounces, size, camera, scene, tree), overlapping ranges, gaps and,
// with --spp, ranges that do not cover the render.
#include "render_fixture.h"

#include <kdray/film.h>
#include <kdray/image_io.h>

#include <gtest/gtest.h>

#include <fstream>

namespace kdray {
namespace {

namespace fs = std::filesystem;

class KdrenderMerge : public test::CornellFilesTest<KdrenderMerge> {
 protected:
  static void SetUpTestSuite() {
    CornellFilesTest::SetUpTestSuite();
    // The shards and their variants, rendered by one batch.
    std::string jobs;
    for (int shard = 0; shard < 4; ++shard) {
      jobs += "-o " + path("s" + std::to_string(shard) + ".exr") + " --sample-offset " + std::to_string(2 * shard) + "\n";
    }
    jobs += "-o " + path("whole.exr") + " --spp 8\n";
    jobs += "-o " + path("s01.exr") + " --spp 4\n";         // overlaps s0 and s1
    jobs += "-o " + path("seed.exr") + " --sample-offset 2 --seed 9\n";
    jobs += "-o " + path("bounces.exr") + " --sample-offset 2 --max-bounces 2\n";
    jobs += "-o " + path("size.exr") + " --sample-offset 2 --width 9\n";
    jobs += "-o " + path("camera.exr") + " --sample-offset 2 --cam-pos 270,273,-800\n";
    jobs += "-o " + path("light.exr") + " --sample-offset 2 --env-color 1,1,1\n";
    std::ofstream(path("shards.jobs")) << jobs;
    test::ToolRun run = test::run_command(
        test::shell_quoted(test::tool_path("kdrender")) + " " + scene_ + " " + tree_ + " --jobs " +
        path("shards.jobs") + " --spp 2 --width 12 --height 10 --cam-pos 278,273,-800 --cam-target 278,273,0 "
                              "--fov 39.3077 --quiet 2>&1");
    if (run.exit_code != 0) throw std::runtime_error("kdrender --jobs failed: " + run.out);
  }
  static test::ToolRun merge(const std::vector<std::string>& inputs, const std::string& extra = "") {
    std::string command = test::shell_quoted(test::tool_path("kdrender")) + " --merge";
    for (const std::string& input : inputs) command += " " + path(input);
    fs::remove(path("merged.exr"));
    return test::run_command(command + " -o " + path("merged.exr") + " " + extra + " 2>&1");
  }
  // Expects a refusal that names `file` and says `what`, and no output.
  static void expect_refusal(const std::vector<std::string>& inputs, const std::string& file, const std::string& what,
                             const std::string& extra = "") {
    test::ToolRun run = merge(inputs, extra);
    EXPECT_EQ(run.exit_code, 1) << run.out;
    EXPECT_NE(run.out.find("kdrender: error: " + path(file) + ": "), std::string::npos) << run.out;
    EXPECT_NE(run.out.find(what), std::string::npos) << run.out;
    EXPECT_FALSE(fs::exists(path("merged.exr")));
  }
};

TEST_F(KdrenderMerge, ShardsInAnyOrderMergeIntoTheWholeRender) {
  test::ToolRun run = merge({"s2.exr", "s0.exr", "s3.exr", "s1.exr"}, "--spp 8 --quiet");
  ASSERT_EQ(run.exit_code, 0) << run.out;
  Film merged = read_film_exr(path("merged.exr")), whole = read_film_exr(path("whole.exr"));
  EXPECT_EQ(merged.sums, whole.sums);
  EXPECT_EQ(merged.sample_count, 8u);
  EXPECT_EQ(merged.settings_hash, whole.settings_hash);
  EXPECT_NE(merged.settings_hash, 0u);
}

TEST_F(KdrenderMerge, RefusesGapsOverlapsAndMissingEnds) {
  expect_refusal({"s0.exr", "s1.exr", "s3.exr"}, "s3.exr", "samples 4..5 are missing");
  expect_refusal({"s0.exr", "s01.exr"}, "s01.exr", "overlap samples 0..1 of " + path("s0.exr"));
  expect_refusal({"s1.exr", "s1.exr"}, "s1.exr", "overlap");
  expect_refusal({"s0.exr", "s1.exr", "s2.exr"}, "s2.exr", "samples 6..7 are missing", "--spp 8");
  expect_refusal({"s1.exr", "s2.exr", "s3.exr"}, "s1.exr", "samples 0..1 are missing", "--spp 8");
  expect_refusal({"s1.exr", "s2.exr"}, "s2.exr", "more than samples 2..3", "--spp 2 --sample-offset 2");
}

TEST_F(KdrenderMerge, RefusesShardsOfAnotherRender) {
  expect_refusal({"s0.exr", "seed.exr"}, "seed.exr", "differs in seed (9 here, 0 there)");
  expect_refusal({"s0.exr", "bounces.exr"}, "bounces.exr", "max bounces");
  expect_refusal({"s0.exr", "size.exr"}, "size.exr", "size (9x10 here, 12x10 there)");
  expect_refusal({"s0.exr", "camera.exr"}, "camera.exr", "settings (camera, environment, lights)");
  expect_refusal({"light.exr", "s0.exr"}, "s0.exr", "settings");
  expect_refusal({"s0.exr", "missing.exr"}, "missing.exr", "no such file");
}

TEST(MergeFilmRanges, NamesTheFilmOfAnotherSceneOrTree) {
  Film a;
  a.width = a.height = 1;
  a.channels = {"R", "G", "B"};
  a.sums = {1, 2, 3};
  a.sample_count = 1;
  Film other_scene = a, other_tree = a;
  other_scene.sample_offset = other_tree.sample_offset = 1;
  other_scene.scene_hash = 7;
  other_tree.tree_hash = 7;
  // merge_film_ranges must refuse `films` with an error that says `message`.
  auto expect_refused = [](std::vector<NamedFilm> films, const std::string& message) {
    try {
      merge_film_ranges(std::move(films));
      ADD_FAILURE() << "merged what it should refuse: " << message;
    } catch (const Error& e) {
      EXPECT_NE(std::string(e.what()).find(message), std::string::npos) << e.what();
    }
  };
  expect_refused({{"a.exr", a}, {"b.exr", other_scene}},
                 "b.exr: not a sample range of the same render as a.exr: it differs in scene");
  expect_refused({{"a.exr", a}, {"c.exr", other_tree}},
                 "c.exr: not a sample range of the same render as a.exr: it differs in tree");
  Film b = a;
  b.sample_offset = 1;
  Film merged = merge_film_ranges({{"b.exr", b}, {"a.exr", a}}, std::make_pair(0u, 2u));
  EXPECT_EQ(merged.sums, (std::vector<int64_t>{2, 4, 6}));
}

}  // namespace
}  // namespace kdray
