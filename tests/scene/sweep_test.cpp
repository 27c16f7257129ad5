// Every odd or broken file we know of either converts or fails with one clear line: no
// crash, no hang, no output left behind. The files are tinyobjloader's regression OBJs and
// Debian's assimp-testmodels, one test per folder, each file run through the real kdconvert.
#include <kdray/scene_file.h>

#include <subprocess.h>
#include "test_corpus.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <filesystem>
#include <map>

namespace kdray {
namespace {

namespace fs = std::filesystem;

constexpr const char* kAssimpModels = KDRAY_ASSIMP_MODELS_DIR;
// A conversion that takes longer than this is a hang (the slowest file takes about 1 s).
constexpr double kTimeoutSeconds = 60;

// Folders that directly hold files, with their files, under each root.
std::vector<std::pair<std::string, std::vector<std::string>>> folders() {
  std::map<std::string, std::vector<std::string>> files_by_folder;
  for (const std::string& root : {std::string(KDRAY_CORPUS_DIR) + "/tinyobjloader-odd", std::string(kAssimpModels)}) {
    std::error_code error;
    if (!fs::is_directory(root, error)) continue;
    for (const auto& entry : fs::recursive_directory_iterator(root, error))
      if (entry.is_regular_file()) files_by_folder[entry.path().parent_path().string()].push_back(entry.path().string());
  }
  std::vector<std::pair<std::string, std::vector<std::string>>> result(files_by_folder.begin(), files_by_folder.end());
  for (auto& folder : result) std::sort(folder.second.begin(), folder.second.end());
  return result;
}

std::vector<std::string> folder_names() {
  std::vector<std::string> names;
  for (const auto& folder : folders()) names.push_back(folder.first);
  return names;
}

std::string test_name(const ::testing::TestParamInfo<std::string>& info) {
  std::string name = info.param;
  for (const std::string& root : {std::string(KDRAY_CORPUS_DIR) + "/", std::string(kAssimpModels) + "/"})
    if (name.rfind(root, 0) == 0) name = (root == std::string(kAssimpModels) + "/" ? "assimp_" : "") + name.substr(root.size());
  std::replace_if(name.begin(), name.end(), [](char c) { return !std::isalnum(static_cast<unsigned char>(c)); }, '_');
  return name + "_" + std::to_string(info.index);
}

TEST(SweepListing, TheFoldersAreThere) {
  if (!fs::is_directory(kAssimpModels)) {
    if (test::running_in_ci()) FAIL() << "assimp-testmodels missing in CI: " << kAssimpModels;
    GTEST_SKIP() << "assimp-testmodels not installed";
  }
  size_t files = 0;
  for (const auto& folder : folders()) files += folder.second.size();
  EXPECT_GT(files, 500u);
}

class ConvertEveryFile : public ::testing::TestWithParam<std::string> {
 protected:
  void SetUp() override { output_directory_ = test::make_temp_dir("sweep"); }
  void TearDown() override { fs::remove_all(output_directory_); }
  fs::path output_directory_;
};

TEST_P(ConvertEveryFile, ConvertsOrFailsWithOneClearLine) {
  std::vector<std::string> files;
  for (const auto& folder : folders())
    if (folder.first == GetParam()) files = folder.second;
  const std::string output = (output_directory_ / "out.kdscene").string();
  for (const std::string& file : files) {
    SCOPED_TRACE(file);
    const auto result = test::run_process({test::tool_path("kdconvert"), file, output, "--quiet"}, kTimeoutSeconds);
    ASSERT_FALSE(result.timed_out) << "hung";
    ASSERT_TRUE(result.exited) << "killed by signal " << result.signal << "\n" << result.err;
    ASSERT_TRUE(result.exit_code == 0 || result.exit_code == 1) << result.err;
    if (result.exit_code == 0) {
      EXPECT_NO_THROW(read_scene(output));
      fs::remove(output);
    } else {
      // The error is the last line; a third-party library may have printed before it
      // (Assimp's OpenGEX parser writes "nullptr returned by creating DDLNode.").
      const std::string expected = "kdconvert: error: " + file + ": ";
      const size_t at = result.err.rfind(expected);
      ASSERT_NE(at, std::string::npos) << result.err;
      EXPECT_TRUE(at == 0 || result.err[at - 1] == '\n') << result.err;
      EXPECT_EQ(result.err.find('\n', at), result.err.size() - 1) << result.err;
      EXPECT_GT(result.err.size(), at + expected.size() + 1) << "the reason is missing";
    }
    EXPECT_TRUE(fs::is_empty(output_directory_)) << "output or temporary file left behind";
  }
}

INSTANTIATE_TEST_SUITE_P(Folders, ConvertEveryFile, ::testing::ValuesIn(folder_names()), test_name);
GTEST_ALLOW_UNINSTANTIATED_PARAMETERIZED_TEST(ConvertEveryFile);

}  // namespace
}  // namespace kdray
