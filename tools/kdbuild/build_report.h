// What kdbuild reports about a build (or a cache hit), as text or JSON.
#pragma once

#include <kdray/kdtree.h>
#include <kdray/tree_cache.h>

#include <nlohmann/json.hpp>

#include <string>
#include <vector>

namespace kdbuild {

struct Report {
  std::string scene_path, tree_path;  // tree_path may be empty with a cache
  kdray::TreeSummary tree;
  uint64_t scene_hash = 0;
  double load_seconds = 0, build_seconds = 0, build_cpu_seconds = 0, write_seconds = 0;
  kdray::BuildTimings phases;
  std::string cache;        // "hit", "miss", or empty without a cache
  std::string cache_entry;  // the entry's tree path
  std::vector<kdray::CacheEntry> evicted;
};

nlohmann::json report_json(const Report& report);
std::string report_text(const Report& report);

}  // namespace kdbuild
