// Locating shared corpus files, the sample scene and built tools from tests, and temporary directories for them.
#pragma once

#include <gtest/gtest.h>

#include <algorithm>
#include <cstdlib>
#include <filesystem>
#include <string>
#include <system_error>

namespace kdray::test {

inline bool running_in_ci() {
  const char* ci = std::getenv("CI");
  return ci != nullptr && std::string(ci) == "true";
}

// Path of a corpus file. A missing file fails the test under CI=true and skips it elsewhere
// (use as: std::string path; KDRAY_CORPUS_FILE(path, "bunny/stanford-bunny.obj");).
#define KDRAY_CORPUS_FILE(var, relative)                                                  \
  do {                                                                                    \
    var = std::string(KDRAY_CORPUS_DIR) + "/" + (relative);                              \
    if (!std::filesystem::exists(var)) {                                                  \
      if (::kdray::test::running_in_ci()) FAIL() << "corpus file missing in CI: " << var; \
      GTEST_SKIP() << "corpus file missing: " << var;                                     \
    }                                                                                     \
  } while (0)

inline std::string tool_path(const std::string& tool) { return std::string(KDRAY_TOOLS_DIR) + "/" + tool + "/" + tool; }

// The repository's sample scene, the Cornell box (its .mtl beside it).
inline std::string cornell_obj() { return std::string(KDRAY_SOURCE_DIR) + "/samples/cornell-box.obj"; }

// A fresh empty directory under the system temp dir, removed by the fixture's owner.
inline std::filesystem::path make_temp_dir(const std::string& stem) {
  auto base = std::filesystem::temp_directory_path() / ("kdray-" + stem + "-XXXXXX");
  std::string pattern = base.string();
  if (mkdtemp(pattern.data()) == nullptr) throw std::runtime_error("mkdtemp failed");
  return pattern;
}

// The running test suite's name, usable in a file name.
inline std::string test_suite_stem() {
  std::string name = ::testing::UnitTest::GetInstance()->current_test_suite()->name();
  std::replace(name.begin(), name.end(), '/', '-');  // a parameterised suite's prefix
  return name;
}

// A test with an empty directory of its own for the files it writes, named after the suite, made
// before the test and removed after it. Base is ::testing::Test or a ::testing::TestWithParam.
template <typename Base = ::testing::Test>
class TempDirTest : public Base {
 protected:
  TempDirTest() : dir_(make_temp_dir(test_suite_stem())) {}
  ~TempDirTest() override {
    std::error_code ignored;
    std::filesystem::remove_all(dir_, ignored);
  }
  std::string path(const std::string& name) const { return (dir_ / name).string(); }

  const std::filesystem::path dir_;
};

// A test suite whose tests share one temporary directory, named after the suite, made before the
// first test and removed after the last. Suite derives from SuiteDirTest<Suite>, so that each
// suite keeps its own.
template <typename Suite>
class SuiteDirTest : public ::testing::Test {
 protected:
  static void SetUpTestSuite() { dir_ = make_temp_dir(test_suite_stem()); }
  static void TearDownTestSuite() { std::filesystem::remove_all(dir_); }
  static std::string path(const std::string& name) { return (dir_ / name).string(); }

  static inline std::filesystem::path dir_;
};

}  // namespace kdray::test
