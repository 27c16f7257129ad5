// The exact SAH builder (Wald & Havran 2006) for one subtree: its node's events are sorted once
// per axis; each split divides the sorted lists in one pass and merges in the few re-clipped
// events of straddling triangles, so no node below re-sorts.
#pragma once

#include "build_context.h"
#include "build_pieces.h"

#include <vector>

namespace kdray::detail {

struct NodeWork {
  Box3 voxel;
  uint32_t depth = 0;
  std::vector<uint32_t> triangles;  // scene triangle per local index
  std::vector<Box3> bounds;         // per local index, kept without perfect splits only: the bounds in this voxel
  EventArray events[3];             // sorted
};

// The node of `triangles` (in increasing index order) whose bounds in `voxel` are `bounds`,
// with its events sorted on each axis (in parallel for a large node). `bounds` is taken by
// value, so that a caller who moves them in frees them here when perfect splits drop them.
NodeWork node_with_events(const Box3& voxel, uint32_t depth, std::vector<uint32_t>&& triangles,
                          std::vector<Box3> bounds, bool perfect_splits);

// Builds the subtree of `work` into `out`; large nodes build their children in parallel.
void build_exact_subtree(BuildContext& context, NodeWork& work, Piece& out);

}  // namespace kdray::detail
