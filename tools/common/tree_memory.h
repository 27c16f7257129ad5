// Where a host traversal reads a tree (kdtrace, kdrender): copied out of its file onto huge pages
// first when the rays repay the copy (kdray::copy_tree_for_rays), or where the file is mapped;
// and how --json says which.
#pragma once

#include <kdray/clock.h>
#include <kdray/kdtree.h>
#include <kdray/traverse.h>

#include <nlohmann/json.hpp>

#include <cstdint>

namespace kdray::tool {

// Copies `tree` for `rays` rays on the host when they repay the copy (no rays: no copy). The
// seconds the copy took, -1 for none.
inline double copy_tree_if_repaid(KdTree& tree, uint64_t rays, unsigned threads) {
  if (rays == 0) return -1;
  const auto start = Clock::now();
  return copy_tree_for_rays(tree, rays, threads) ? seconds_since(start) : -1;
}

// "tree_memory" ("copied" or "file mapping") and, after a copy, "tree_copy_seconds".
inline void add_tree_memory(nlohmann::json& report, double copy_seconds) {
  report["tree_memory"] = copy_seconds >= 0 ? "copied" : "file mapping";
  if (copy_seconds >= 0) report["tree_copy_seconds"] = copy_seconds;
}

}  // namespace kdray::tool
