// What kdinfo prints about one file: the same facts as JSON and as human-readable text.
#pragma once

#include <nlohmann/json.hpp>

#include <kdray/clock.h>
#include <kdray/error.h>

#include "text_format.h"

#include <cstdio>
#include <string>

namespace kdinfo {

struct FileReport {
  nlohmann::json json;
  std::string text;
  bool intact = false;  // the whole file was read and every check passed
  std::string problem;  // when not intact and the cause is known: "<file>: <what>", for stderr
};

using kdray::tool::format;

// Loads the whole file with `load` (which reads and verifies it), times that, and adds the
// facts `describe` draws from the loaded object, the load time and the verdict to `report`;
// `details_text` turns the facts into human-readable lines. A kdray::Error from the load marks
// the file damaged.
template <typename Load, typename Describe, typename DetailsText>
void add_verified_details(FileReport& report, const char* checks, Load&& load, Describe&& describe,
                          DetailsText&& details_text) {
  try {
    const auto start = kdray::Clock::now();
    const auto loaded = load();
    const double load_seconds = kdray::seconds_since(start);
    const nlohmann::json details = describe(loaded);
    report.json.update(details);
    report.json["load_seconds"] = load_seconds;
    report.json["intact"] = true;
    report.text += details_text(details) + format("intact     yes (%s verified, loaded in %.3f s)\n", checks, load_seconds);
    report.intact = true;
  } catch (const kdray::Error& error) {
    report.json["intact"] = false;
    report.json["problem"] = error.what();
    report.problem = error.what();
    report.text += std::string("intact     NO: ") + error.what() + "\n";
  }
}

// .kdscene files (scene_report.cpp). Throws kdray::Error when not even the header is usable.
FileReport describe_scene_file(const std::string& path);

// .kdtree files (tree_report.cpp). Throws kdray::Error when not even the header is usable.
FileReport describe_tree_file(const std::string& path);

// A tree cache folder (cache_report.cpp): its entries, most recently used first.
FileReport describe_cache(const std::string& folder);

// Whether a tree was built for a scene: compares the scene's geometry hash (for a version 1
// tree, its content hash) with the one the tree records (both reports must be intact).
FileReport describe_match(const FileReport& scene, const FileReport& tree);

}  // namespace kdinfo
