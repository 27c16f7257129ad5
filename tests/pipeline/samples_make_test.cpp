// samples/Makefile as a pipeline, run on a copy of samples/ with two small scenes (the Cornell box
// and a one-triangle OBJ) rendered at a few pixels: a second make does nothing, touching one asset
// redoes only its chain, touching a material redoes that scene's image but takes its tree from the
// tree cache.
#include <subprocess.h>
#include <test_corpus.h>

#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

namespace kdray {
namespace {

namespace fs = std::filesystem;

const std::vector<std::string> kCornellChain = {"cornell-box.kdscene", "cornell-box.kdtree", "cornell-box.png"};
const std::vector<std::string> kTriangleChain = {"tri.kdscene", "tri.kdtree", "tri.png"};

class SamplesMake : public test::TempDirTest<> {
 protected:
  void SetUp() override {
    for (const char* file : {"Makefile", "report.mk", "gallery.mk", "cornell-box.obj", "cornell-box.mtl"})
      fs::copy_file(fs::path(KDRAY_SOURCE_DIR) / "samples" / file, dir_ / file);
    std::ofstream(dir_ / "tri.obj") << "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n";
  }

  // make in the copy, the two scenes only, at sizes that render in a moment; stdout and stderr.
  test::ToolRun make(const std::string& arguments) const {
    const std::string small = "--width 8 --height 8 --spp 1 --quiet";
    return test::run_command("make -C " + test::shell_quoted(dir_.string()) + " --no-print-directory" +
                             " BUILD=" + test::shell_quoted(std::string(KDRAY_TOOLS_DIR) + "/..") +
                             " OUT=" + test::shell_quoted(out().string()) + " 'IMAGES=cornell-box tri'" +
                             " 'RENDER_cornell-box=" + small + "' 'RENDER_tri=" + small + " --no-default-light' " +
                             arguments + " 2>&1");
  }
  fs::path out() const { return dir_ / "out"; }

  // Every file of the copy gets one old time, so that a file touched later is strictly newer and
  // a file a recipe rewrites is seen to have changed, whatever the file system's time resolution.
  void age_every_file() const {
    for (const fs::directory_entry& entry : fs::recursive_directory_iterator(dir_))
      if (entry.is_regular_file()) fs::last_write_time(entry.path(), old_time_);
  }
  void touch(const std::string& file) const { fs::last_write_time(dir_ / file, fs::file_time_type::clock::now()); }
  bool rewritten(const std::string& output) const { return fs::last_write_time(out() / output) != old_time_; }

  const fs::file_time_type old_time_ = fs::file_time_type::clock::now() - std::chrono::hours(24);
};

TEST_F(SamplesMake, ParallelMakeBuildsEveryStageAndASecondMakeDoesNothing) {
  const test::ToolRun first = make("-j2 all");
  ASSERT_EQ(first.exit_code, 0) << first.out;
  for (const auto* chain : {&kCornellChain, &kTriangleChain})
    for (const std::string& output : *chain) EXPECT_TRUE(fs::is_regular_file(out() / output)) << output;

  EXPECT_EQ(make("-q all").exit_code, 0) << "make -q says something is out of date";
  const test::ToolRun second = make("all");
  EXPECT_EQ(second.exit_code, 0) << second.out;
  EXPECT_NE(second.out.find("Nothing to be done"), std::string::npos) << second.out;
}

TEST_F(SamplesMake, TouchingOneAssetRedoesOnlyItsChain) {
  ASSERT_EQ(make("-j2 all").exit_code, 0);
  age_every_file();
  ASSERT_EQ(make("-q all").exit_code, 0);

  touch("tri.obj");
  EXPECT_NE(make("-q all").exit_code, 0);
  const test::ToolRun again = make("-j2 all");
  ASSERT_EQ(again.exit_code, 0) << again.out;
  for (const std::string& output : kTriangleChain) EXPECT_TRUE(rewritten(output)) << output;
  for (const std::string& output : kCornellChain) EXPECT_FALSE(rewritten(output)) << output;
  EXPECT_EQ(make("-q all").exit_code, 0);
}

TEST_F(SamplesMake, TouchingAMaterialRedoesThatScenesImageButNotItsTree) {
  ASSERT_EQ(make("-j2 all").exit_code, 0);
  age_every_file();

  touch("cornell-box.mtl");
  const test::ToolRun again = make("-j2 all");
  ASSERT_EQ(again.exit_code, 0) << again.out;
  EXPECT_TRUE(rewritten("cornell-box.kdscene"));
  EXPECT_TRUE(rewritten("cornell-box.png"));
  for (const std::string& output : kTriangleChain) EXPECT_FALSE(rewritten(output)) << output;
  // The tree is not built again: the cache has it (kdbuild says so) and holds no more entries.
  EXPECT_NE(again.out.find("cache                    hit"), std::string::npos) << again.out;
  EXPECT_EQ(again.out.find("cache                    miss"), std::string::npos) << again.out;
  size_t entries = 0;
  for (const fs::directory_entry& entry : fs::directory_iterator(out() / "tree-cache"))
    entries += entry.path().extension() == ".kdtree";
  EXPECT_EQ(entries, 2u);
}

TEST_F(SamplesMake, AMissingAssetFailsAndLeavesNoOutput) {
  const test::ToolRun run = make("'IMAGES=nothing-here' all");
  EXPECT_NE(run.exit_code, 0);
  EXPECT_NE(run.out.find("nothing-here.obj: no such asset"), std::string::npos) << run.out;
  EXPECT_FALSE(fs::exists(out() / "nothing-here.kdscene"));
}

}  // namespace
}  // namespace kdray
