// Locating shared corpus files and built tools from tests.
#pragma once

#include <gtest/gtest.h>

#include <cstdlib>
#include <filesystem>
#include <string>

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

// A fresh empty directory under the system temp dir, removed by the fixture's owner.
inline std::filesystem::path make_temp_dir(const std::string& stem) {
  auto base = std::filesystem::temp_directory_path() / ("kdray-" + stem + "-XXXXXX");
  std::string pattern = base.string();
  if (mkdtemp(pattern.data()) == nullptr) throw std::runtime_error("mkdtemp failed");
  return pattern;
}

}  // namespace kdray::test
