// The binned top of the tree (min-max binning, Shevtsov, Soupikov and Kapustin 2007): a node
// of more than settings.binned_above triangles chooses its split among settings.bins - 1 evenly
// spaced planes per axis, counted from its triangles' bounds in one parallel pass, instead of
// sorting and sweeping all of its events. Nodes at or below the threshold go to the exact
// sweep, which then sorts only their own events.
#pragma once

#include "build_context.h"
#include "build_pieces.h"

#include <vector>

namespace kdray::detail {

struct BinnedNode {
  Box3 voxel;
  uint32_t depth = 0;
  std::vector<uint32_t> triangles;  // in increasing index order
  std::vector<Box3> bounds;         // per triangle: its bounds in the voxel
};

// Whether a node of `triangles` triangles is binned.
inline bool binned(const BuildSettings& settings, size_t triangles) {
  return settings.binned_above != 0 && triangles > settings.binned_above;
}

// Builds the subtree of `node` into `out`: binned while it is large, exact below.
void build_binned_subtree(BuildContext& context, BinnedNode& node, Piece& out);

}  // namespace kdray::detail
