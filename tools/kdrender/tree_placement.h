// Where the host traces a frame's tree: copied out of its file onto huge pages when the rays
// repay the copy (kdray::copy_tree_for_rays), as kdtrace does, or where the file is mapped.
#pragma once

#include "frame_options.h"

#include <kdray/kdtree.h>

#include <nlohmann/json.hpp>

#include <cstdint>

namespace kdrender {

// The rays a frame traces at most on the host (--device host: pixels x samples x (bounces + 1),
// a side left to the camera counted at the default size), 0 on an OpenCL device.
uint64_t host_rays_of(const Frame& frame);

// Copies the tree for `host_rays` on the host when they repay it (none: no copy). The seconds
// the copy took, -1 for none.
double place_tree_for_host(kdray::KdTree& tree, uint64_t host_rays, unsigned threads);

// The tree's place in a --json report: "tree_memory" ("copied" or "file mapping") and, after a
// copy, "tree_copy_seconds".
void add_tree_memory(nlohmann::json& report, double copy_seconds);

}  // namespace kdrender
