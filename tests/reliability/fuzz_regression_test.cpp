// Inputs the fuzzers found (inputs/, named after what they caught): each must be rejected with
// a kdray::Error naming the file, never a crash, a hang or a huge allocation.
#include <kdray/error.h>
#include <kdray/image_io.h>
#include <kdray/import.h>
#include <kdray/kdtree.h>
#include <kdray/ray_files.h>
#include <kdray/scene_file.h>

#include <gtest/gtest.h>

#include <filesystem>
#include <functional>
#include <map>

#include <sys/resource.h>
#include <sys/wait.h>
#include <unistd.h>

namespace kdray {
namespace {

namespace fs = std::filesystem;

// The reader for each kind of regression input, by extension.
const std::map<std::string, std::function<void(const std::string&)>> kReaders = {
    {".kdscene", [](const std::string& path) { read_scene(path); }},
    {".kdtree", [](const std::string& path) { read_tree(path); }},
    {".rays", [](const std::string& path) { read_rays(path); }},
    {".hits", [](const std::string& path) { read_hits(path); }},
    {".exr", [](const std::string& path) { read_film_exr(path); }},
    {".obj", [](const std::string& path) { import_scene(path, ImportOptions{}); }},
    {".ply", [](const std::string& path) { import_scene(path, ImportOptions{}); }},
};

TEST(FuzzRegression, EveryKeptInputIsRejectedCleanly) {
  size_t checked = 0;
  for (const auto& entry : fs::directory_iterator(KDRAY_RELIABILITY_INPUTS)) {
    const std::string path = entry.path().string();
    const auto reader = kReaders.find(entry.path().extension().string());
    if (reader == kReaders.end()) continue;  // companion files (an OBJ's .mtl)
    SCOPED_TRACE(path);
    try {
      reader->second(path);
      ADD_FAILURE() << "accepted";
    } catch (const Error& error) {
      EXPECT_NE(std::string(error.what()).find(path), std::string::npos) << error.what();
    }
    ++checked;
  }
  EXPECT_GT(checked, 0u);
}

// Rejecting is not enough: an input that made a library allocate gigabytes before it failed
// (OpenEXR reading a string attribute whose size field claimed 2 GB) must be refused before that.
// Each reader runs in a child so that its peak resident memory can be measured alone.
TEST(FuzzRegression, EveryKeptInputIsRejectedWithinBoundedMemory) {
  constexpr long kMaxResidentKilobytes = 768 * 1024;  // the sanitizers' shadow and quarantine included
  for (const auto& entry : fs::directory_iterator(KDRAY_RELIABILITY_INPUTS)) {
    const std::string path = entry.path().string();
    const auto reader = kReaders.find(entry.path().extension().string());
    if (reader == kReaders.end()) continue;
    SCOPED_TRACE(path);
    const pid_t child = ::fork();
    ASSERT_GE(child, 0);
    if (child == 0) {
      try {
        reader->second(path);
      } catch (...) {
      }
      ::_exit(0);
    }
    int status = 0;
    struct rusage usage {};
    ASSERT_EQ(::wait4(child, &status, 0, &usage), child);
    EXPECT_TRUE(WIFEXITED(status) && WEXITSTATUS(status) == 0) << "status " << status;
    EXPECT_LT(usage.ru_maxrss, kMaxResidentKilobytes) << "peak resident kilobytes";
  }
}

}  // namespace
}  // namespace kdray
