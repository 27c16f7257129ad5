#include "build_pieces.h"

#include <utility>

namespace kdray::detail {
namespace {

void count_sizes(const Piece& piece, size_t& nodes, size_t& references) {
  if (piece.axis < 0) {
    nodes += piece.serial.nodes.size();
    references += piece.serial.leaf_triangles.size();
    return;
  }
  ++nodes;
  count_sizes(*piece.below, nodes, references);
  count_sizes(*piece.above, nodes, references);
}

void append_piece(const Piece& piece, Subtree& out) {
  if (piece.axis < 0) {
    out.append(piece.serial);
    return;
  }
  out.add_inner(piece.axis, piece.position, [&] { append_piece(*piece.below, out); },
                [&] { append_piece(*piece.above, out); });
}

}  // namespace

Subtree flatten(Piece&& root) {
  if (root.axis < 0) return std::move(root.serial);
  size_t nodes = 0, references = 0;
  count_sizes(root, nodes, references);
  Subtree out;
  out.nodes.reserve(nodes);
  out.leaf_triangles.reserve(references);
  append_piece(root, out);
  return out;
}

}  // namespace kdray::detail
