#include "build_report.h"

#include <kdray/container_file.h>

#include "process_stats.h"
#include "text_format.h"
#include "tree_json.h"

#include <cstdio>
#include <filesystem>
#include <string>

namespace kdbuild {
namespace {

using kdray::tool::format;

// The written tree's size: the output's, or the cache entry's when there is no output.
uint64_t tree_bytes(const Report& r) {
  std::error_code error;
  const uint64_t bytes = std::filesystem::file_size(r.tree_path.empty() ? r.cache_entry : r.tree_path, error);
  return error ? 0 : bytes;
}

}  // namespace

nlohmann::json report_json(const Report& r) {
  nlohmann::json out = kdray::tool::tree_stats_json(r.tree);
  out.update({{"scene", r.scene_path}, {"tree", r.tree_path}, {"scene_hash", kdray::hash_hex(r.scene_hash)},
              {"geometry_hash", kdray::hash_hex(r.tree.geometry_hash)}, {"key", kdray::hash_hex(r.tree.key)},
              {"load_seconds", r.load_seconds}, {"peak_memory_mib", kdray::tool::peak_memory_mib()},
              {"tree_bytes", tree_bytes(r)}});
  if (!r.cache.empty()) {
    out["cache"] = r.cache;
    out["cache_entry"] = r.cache_entry;
    out["cache_seconds"] = r.build_seconds;  // hit: checksum and copy; miss: build, store and copy
    nlohmann::json evicted = nlohmann::json::array();
    for (const kdray::CacheEntry& entry : r.evicted) evicted.push_back(kdray::hash_hex(entry.key));
    out["evicted"] = evicted;
  }
  if (r.cache != "hit") {
    out["build_seconds"] = r.build_seconds;
    out["build_cpu_seconds"] = r.build_cpu_seconds;
    out["write_seconds"] = r.write_seconds;
    out["phase_seconds"] = {{"load", r.load_seconds}, {"prepare", r.phases.prepare}, {"events", r.phases.events},
                            {"subdivide", r.phases.subdivide}, {"assemble", r.phases.assemble},
                            {"statistics", r.phases.statistics}, {"write", r.write_seconds}};
  }
  return out;
}

std::string report_text(const Report& r) {
  const kdray::TreeStats& s = r.tree.stats;
  const uint64_t bytes = tree_bytes(r);
  std::string text = r.scene_path + " -> " + (r.tree_path.empty() ? r.cache_entry : r.tree_path) + "\n";
  if (!r.cache.empty())
    text += format("  cache                    %s, %s (key %s)\n", r.cache.c_str(), r.cache_entry.c_str(),
                   kdray::hash_hex(r.tree.key).c_str());
  for (const kdray::CacheEntry& entry : r.evicted)
    text += format("  evicted                  %s (%llu bytes)\n", entry.tree_path.c_str(),
                   static_cast<unsigned long long>(entry.bytes));
  const double empty_share = s.leaves ? 100.0 * static_cast<double>(s.empty_leaves) / s.leaves : 0.0;
  text += format("  triangles                %llu\n", static_cast<unsigned long long>(s.triangles));
  text += format("  SAH cost                 %.3f\n", s.sah_cost);
  text += format("  inner nodes              %llu\n", static_cast<unsigned long long>(s.inner_nodes));
  text += format("  leaves                   %llu (%llu empty, %.1f%%)\n", static_cast<unsigned long long>(s.leaves),
                 static_cast<unsigned long long>(s.empty_leaves), empty_share);
  const uint32_t limit = r.tree.settings.max_depth;
  text += format("  leaf depth               max %u, mean %.2f (limit %s)\n", s.max_depth, s.mean_leaf_depth,
                 limit != 0 ? std::to_string(limit).c_str() : "automatic");
  text += format("  triangles per leaf       %.2f (non-empty leaves)\n", s.mean_triangles_per_leaf);
  text += format("  references per triangle  %.3f\n", s.references_per_triangle);
  if (r.cache == "hit") {
    text += format("  checked and copied       %.3f s (scene load %.3f s)\n", r.build_seconds, r.load_seconds);
  } else {
    text += format("  build                    %.3f s, %.3f s CPU (scene load %.3f s)\n", r.build_seconds,
                   r.build_cpu_seconds, r.load_seconds);
    text += format("  phases                   prepare %.3f, events %.3f, subdivide %.3f, assemble %.3f, statistics "
                   "%.3f, write %.3f s\n",
                   r.phases.prepare, r.phases.events, r.phases.subdivide, r.phases.assemble, r.phases.statistics,
                   r.write_seconds);
  }
  text += format("  peak memory              %.1f MiB (scene, build and tree)\n", kdray::tool::peak_memory_mib());
  text += format("  tree size                %.1f MiB (%llu nodes)\n", static_cast<double>(bytes) / (1024.0 * 1024.0),
                 static_cast<unsigned long long>(r.tree.stats.inner_nodes + r.tree.stats.leaves));
  return text;
}

}  // namespace kdbuild
