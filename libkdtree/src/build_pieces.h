// The parallel levels of a tree under construction: each of their subtrees is built into its
// own arrays, and the pieces are joined into one node array once, at the end, in a fixed order
// (below before above), so the bytes do not depend on which thread built what.
#pragma once

#include "build_common.h"

#include <memory>

namespace kdray::detail {

// An inner node with its two pieces, or (axis -1) a subtree built by one thread.
struct Piece {
  int axis = -1;
  float position = 0;
  std::unique_ptr<Piece> below, above;
  Subtree serial;
};

// Joins the pieces into one subtree, depth first.
Subtree flatten(Piece&& root);

}  // namespace kdray::detail
