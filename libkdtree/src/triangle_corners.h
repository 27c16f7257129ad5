// The leaf triangles' records made from the scene a piece at a time, for a writer that makes
// them as it writes (build_tree_file) rather than holding them all.
#pragma once

#include <kdray/scene.h>

#include <cstdint>

namespace kdray::detail {

// Bytes [begin, end) of the leaf-triangle array that leaf_triangles_of(scene, triangles, ...)
// makes, to out; made in parallel.
void leaf_triangle_bytes(const Scene& scene, const uint32_t* triangles, uint64_t begin, uint64_t end, char* out);

}  // namespace kdray::detail
