// What kdinfo prints about one file: the same facts as JSON and as human-readable text.
#pragma once

#include <nlohmann/json.hpp>

#include <cstdarg>
#include <cstdio>
#include <string>

namespace kdinfo {

struct FileReport {
  nlohmann::json json;
  std::string text;
  bool intact = false;  // the whole file was read and every check passed
};

// printf into a std::string, for the human-readable reports.
inline std::string format(const char* pattern, ...) __attribute__((format(printf, 1, 2)));
inline std::string format(const char* pattern, ...) {
  char buffer[1024];
  va_list arguments;
  va_start(arguments, pattern);
  std::vsnprintf(buffer, sizeof buffer, pattern, arguments);
  va_end(arguments);
  return buffer;
}

// .kdscene files (scene_report.cpp). Throws kdray::Error when not even the header is usable.
FileReport describe_scene_file(const std::string& path);

// .kdtree files (tree_report.cpp). Throws kdray::Error when not even the header is usable.
FileReport describe_tree_file(const std::string& path);

// Whether a tree was built for a scene: compares the scene's content hash with the one the
// tree records (both reports must be intact).
FileReport describe_match(const FileReport& scene, const FileReport& tree);

}  // namespace kdinfo
