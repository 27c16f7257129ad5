// A tree's build settings and statistics in the JSON vocabulary every tool uses (README.md),
// the same in kdbuild's report and kdinfo's description. Tools that link libkdtree include it.
#pragma once

#include <kdray/kdtree.h>

#include <nlohmann/json.hpp>

namespace kdray::tool {

// The names of the leaf layouts, as kdbuild's --leaf-layout takes them and the JSON reports them.
inline const char* leaf_layout_name(LeafLayout layout) {
  switch (layout) {
    case LeafLayout::grouped: return "grouped";
    case LeafLayout::paged: return "paged";
    case LeafLayout::automatic: break;
  }
  return "auto";
}

inline nlohmann::json tree_stats_json(const TreeSummary& tree) {
  const BuildSettings& settings = tree.settings;
  const TreeStats& stats = tree.stats;
  return {
      {"build_settings",
       {{"kt", settings.traversal_cost},
        {"ki", settings.intersection_cost},
        {"empty_bonus", settings.empty_bonus},
        {"max_depth", settings.max_depth},  // as recorded; 0: automatic, in trees written before limits were recorded
        {"depth_limit", settings.max_depth != 0 ? nlohmann::json(settings.max_depth) : nlohmann::json(nullptr)},
        {"perfect_splits", settings.perfect_splits},
        {"binned_above", settings.binned_above},  // 0: the exact sweep everywhere
        {"bins", settings.bins},
        {"leaf_layout", leaf_layout_name(settings.leaf_layout)}}},
      {"triangles", stats.triangles},
      {"sah_cost", stats.sah_cost},
      {"nodes", stats.inner_nodes + stats.leaves},
      {"inner_nodes", stats.inner_nodes},
      {"leaves", stats.leaves},
      {"empty_leaves", stats.empty_leaves},
      {"max_leaf_depth", stats.max_depth},
      {"mean_leaf_depth", stats.mean_leaf_depth},
      {"mean_triangles_per_leaf", stats.mean_triangles_per_leaf},
      {"references_per_triangle", stats.references_per_triangle},
  };
}

}  // namespace kdray::tool
