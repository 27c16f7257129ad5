// The leaf-block array (kernels/kd_types.h) planned for a built tree's leaves and made a byte
// range at a time, for a writer that makes the blocks as it writes them (build_tree_file) as
// well as for the array in memory (leaf_blocks_of).
#pragma once

#include <kdray/kdtree.h>
#include <kdray/scene.h>

#include <cstdint>
#include <vector>

namespace kdray::detail {

// Where each non-empty leaf's block goes, in node order.
struct LeafBlockPlan {
  std::vector<uint32_t> entries;  // the leaf's first entry of the builder's triangle array
  std::vector<uint32_t> counts;   // its triangles
  std::vector<uint64_t> words;    // its block's first word; then one more, the array's size
  bool grouped = false;           // the layout (kernels/kd_types.h)
  uint64_t size_words() const { return words.back(); }
};

// The size in words of a grouped block of `count` triangles (kernels/kd_types.h).
uint64_t grouped_block_words(uint64_t count);

// Plans the blocks of the leaves of `nodes`, whose payloads are still their first entries of
// `triangles` (the builder's array of scene triangle indices), in `layout` (grouped or paged),
// and sets each leaf's payload to its block's first word (an empty leaf's to where the next
// block starts) and its header's layout bit. Throws kdray::Error when the array would outgrow
// the 32-bit payloads.
LeafBlockPlan plan_leaf_blocks(const Scene& scene, TraversalArray<KdNode>& nodes, const uint32_t* triangles,
                               LeafLayout layout);

// Bytes [begin, end) of the planned leaf-block array, to out; made in parallel.
void leaf_block_bytes(const Scene& scene, const uint32_t* triangles, const LeafBlockPlan& plan, uint64_t begin,
                      uint64_t end, char* out);

}  // namespace kdray::detail
