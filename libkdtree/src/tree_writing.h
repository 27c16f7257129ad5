// Writing a tree just built, its leaf blocks made from the scene as the file is written.
#pragma once

#include "leaf_blocks.h"

#include <kdray/kdtree.h>

#include <cstdint>
#include <string>

namespace kdray::detail {

// Writes `tree` as write_tree would with, in place of its own leaf blocks (unused), the blocks
// `plan` lays out for the scene triangles `triangles` (plan_leaf_blocks): they are made piece by
// piece as the file is written, so they are never held whole in memory beside it.
void write_tree_with_planned_blocks(const std::string& path, const KdTree& tree, const Scene& scene,
                                    const uint32_t* triangles, const LeafBlockPlan& plan);

}  // namespace kdray::detail
