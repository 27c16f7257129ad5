#include "build_pieces.h"

#include <kdray/error.h>

#include <tbb/parallel_for.h>

#include <cstring>
#include <utility>
#include <vector>

namespace kdray::detail {
namespace {

// A piece built by one thread and where its nodes and leaf references go in the joined arrays.
struct Placement {
  const Subtree* serial;
  uint64_t node_base;
  uint64_t leaf_base;
};

// Lays the pieces out depth first: the inner nodes of the parallel levels (few), and where each
// serial piece goes, to be copied in parallel. A piece without nodes holds no triangle: its
// parent marks that child empty (kernels/kd_types.h), as Subtree::add_inner does.
class Layout {
 public:
  void place(const Piece& piece) {
    if (piece.axis < 0) {
      if (piece.serial.nodes.empty()) return;
      placements_.push_back({&piece.serial, nodes_, leaves_});
      nodes_ += piece.serial.nodes.size();
      leaves_ += piece.serial.leaf_triangles.size();
      return;
    }
    uint32_t bits;
    std::memcpy(&bits, &piece.position, sizeof bits);
    const uint64_t inner = nodes_++;
    const size_t slot = inner_nodes_.size();
    inner_nodes_.push_back({inner, KdNode{bits, static_cast<uint32_t>(piece.axis)}});
    place(*piece.below);
    const uint64_t far_child = nodes_;
    place(*piece.above);
    const bool below_empty = far_child == inner + 1, above_empty = far_child == nodes_;
    if (below_empty && above_empty) {
      inner_nodes_.pop_back();
      --nodes_;
      return;
    }
    // Checked before the shift, so that an oversized tree cannot wrap into a valid index.
    if (far_child > KD_MAX_CHILD_INDEX) throw Error("", "the tree is too large for 28-bit child indices");
    KdNode& node = inner_nodes_[slot].node;
    node.header |= (above_empty ? KD_ABOVE_EMPTY : static_cast<uint32_t>(far_child) << KD_CHILD_SHIFT) |
                   (below_empty ? KD_BELOW_EMPTY : 0u);
  }

  uint64_t nodes() const { return nodes_; }
  uint64_t leaves() const { return leaves_; }
  const std::vector<Placement>& placements() const { return placements_; }

  void write_inner_nodes(Subtree& out) const {
    for (const InnerNode& inner : inner_nodes_) out.nodes[inner.index] = inner.node;
  }

 private:
  struct InnerNode {
    uint64_t index;
    KdNode node;
  };
  uint64_t nodes_ = 0, leaves_ = 0;
  std::vector<Placement> placements_;
  std::vector<InnerNode> inner_nodes_;
};

}  // namespace

Subtree flatten(Piece&& root) {
  if (root.axis < 0) return std::move(root.serial);
  Subtree out;
  Layout layout;
  layout.place(root);
  if (layout.nodes() > KD_MAX_CHILD_INDEX || layout.leaves() > UINT32_MAX)
    throw Error("", "the tree is too large for 32-bit indices");
  out.nodes.resize(layout.nodes());
  out.leaf_triangles.resize(layout.leaves());
  layout.write_inner_nodes(out);
  // Each serial piece's indices are shifted by where it lands; pieces do not overlap, so they
  // are copied in parallel.
  const std::vector<Placement>& placements = layout.placements();
  tbb::parallel_for(size_t{0}, placements.size(), [&](size_t i) {
    const Placement& placement = placements[i];
    const Subtree& serial = *placement.serial;
    KdNode* nodes = out.nodes.data() + placement.node_base;
    const uint32_t node_shift = static_cast<uint32_t>(placement.node_base) << KD_CHILD_SHIFT;
    const uint32_t leaf_shift = static_cast<uint32_t>(placement.leaf_base);
    for (size_t n = 0; n < serial.nodes.size(); ++n) {
      KdNode node = serial.nodes[n];
      if (kd_node_is_leaf(node))
        node.payload += leaf_shift;
      else if (!kd_node_above_empty(node))
        node.header += node_shift;
      nodes[n] = node;
    }
    std::copy(serial.leaf_triangles.begin(), serial.leaf_triangles.end(),
              out.leaf_triangles.begin() + static_cast<std::ptrdiff_t>(placement.leaf_base));
  });
  return out;
}

}  // namespace kdray::detail
