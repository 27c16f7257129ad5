// Writing a tree just built, its leaf triangles made from the scene as the file is written.
#pragma once

#include <kdray/kdtree.h>

#include <cstdint>
#include <string>

namespace kdray::detail {

// Writes `tree` as write_tree would with, in place of its own leaf-triangle array (unused), the
// leaf triangles of the scene triangles triangles[0, count): their records are made piece by piece
// as the file is written, so they are never held whole in memory beside it.
void write_tree_of_scene_triangles(const std::string& path, const KdTree& tree, const Scene& scene,
                                   const uint32_t* triangles, uint64_t count);

}  // namespace kdray::detail
