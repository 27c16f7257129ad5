// What kdinfo prints about one file: the same facts as JSON and as human-readable text.
#pragma once

#include <nlohmann/json.hpp>

#include <string>

namespace kdinfo {

struct FileReport {
  nlohmann::json json;
  std::string text;
  bool intact = false;  // the whole file was read and every check passed
};

// .kdscene files (scene_report.cpp). Throws kdray::Error when not even the header is usable.
FileReport describe_scene_file(const std::string& path);

}  // namespace kdinfo
