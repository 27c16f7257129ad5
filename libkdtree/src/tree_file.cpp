// The .kdtree file (formats/kdtree.md) on top of the shared section container.
#include <kdray/container_file.h>
#include <kdray/error.h>
#include <kdray/kdtree.h>

#include "tree_writing.h"

#include <kernels/kd_traverse.h>

#include <cereal/archives/portable_binary.hpp>

#include <xxhash.h>

#include <tbb/parallel_invoke.h>

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <cstring>
#include <memory>
#include <sstream>
#include <string>
#include <vector>

namespace kdray {

template <class Archive>
void serialize(Archive& archive, TreeStats& stats) {
  archive(stats.triangles, stats.inner_nodes, stats.leaves, stats.empty_leaves, stats.leaf_references,
          stats.max_depth, stats.mean_leaf_depth, stats.mean_triangles_per_leaf, stats.references_per_triangle,
          stats.sah_cost);
}

namespace {

template <typename T>
std::string to_portable_binary(const T& value) {
  std::ostringstream stream;
  {
    cereal::PortableBinaryOutputArchive archive(stream);
    archive(const_cast<T&>(value));
  }
  return stream.str();
}

template <typename T>
T from_portable_binary(const std::string& bytes, const std::string& path, const char* what) {
  T value;
  try {
    std::istringstream stream(bytes);
    cereal::PortableBinaryInputArchive archive(stream);
    archive(value);
  } catch (const std::exception&) {
    throw Error(path, std::string("damaged ") + what + " section");
  }
  return value;
}

// Section 3: the five fields every tree has, then binned_above and bins for a binned tree
// only. A tree built by the exact sweep everywhere keeps the section, and so the key, it had
// before binning existed; a reader that knows only the five fields still reads a binned tree.
std::string encode_settings(const BuildSettings& settings) {
  std::ostringstream stream;
  {
    cereal::PortableBinaryOutputArchive archive(stream);
    archive(settings.traversal_cost, settings.intersection_cost, settings.empty_bonus, settings.max_depth,
            settings.perfect_splits, static_cast<uint8_t>(settings.leaf_layout));
    if (settings.binned_above != 0) archive(settings.binned_above, settings.bins);
  }
  return stream.str();
}

BuildSettings decode_settings(const std::string& bytes, const std::string& path) {
  BuildSettings settings;
  settings.binned_above = 0;
  bool binned = false;
  try {
    std::istringstream stream(bytes);
    cereal::PortableBinaryInputArchive archive(stream);
    uint8_t layout = 0;
    archive(settings.traversal_cost, settings.intersection_cost, settings.empty_bonus, settings.max_depth,
            settings.perfect_splits, layout);
    settings.leaf_layout = static_cast<LeafLayout>(layout);
    // A tree records the layout its leaves were written in, never "automatic".
    if (settings.leaf_layout != LeafLayout::grouped && settings.leaf_layout != LeafLayout::paged)
      throw Error(path, "damaged parameters section");
    binned = stream.peek() != std::char_traits<char>::eof();
    if (binned) archive(settings.binned_above, settings.bins);
  } catch (const std::exception&) {
    throw Error(path, "damaged parameters section");
  }
  // The exact sweep is written without the two fields: one tree, one encoding, one key.
  if (binned && settings.binned_above == 0) throw Error(path, "damaged parameters section");
  return settings;
}

// The words a leaf of `count` triangles claims at its block's start: a paged block's indices and
// corner numbers (its corners follow, checked by leaf_block_problem), a grouped block's groups.
uint64_t claimed_words(uint64_t count, bool grouped) {
  return grouped ? detail::grouped_block_words(count) : 2 * count;
}

// What is wrong with the block of a leaf of `count` (> 0) triangles at word `first` of the
// leaf-block array of `size` words (its claimed words inside it), or null: every triangle index
// below `triangles` and, in a paged block, bits 30 and 31 of every corner-number word zero and
// every corner it numbers inside the array. Nothing else matters to a traversal, which reads no
// other word (a grouped block's corners are any float bits, and the indices of the lanes that
// fill up its last group are never read).
const char* leaf_block_problem(const uint32_t* blocks, uint64_t size, uint64_t first, uint32_t count, bool grouped,
                               uint64_t triangles) {
  uint32_t largest_index = 0;
  if (grouped) {
    for (uint32_t i = 0; i < count; ++i)
      largest_index = std::max(largest_index, blocks[first + KD_LEAF_GROUP_WORDS * (i / 4) + i % 4]);
    return largest_index >= triangles ? "holds a triangle index beyond the scene's triangles" : nullptr;
  }
  const uint32_t* indices = blocks + first;
  const uint32_t* numbers = indices + count;
  uint32_t high_bits = 0;
  uint64_t corners_needed = 0;  // one past the highest corner numbered
  for (uint32_t i = 0; i < count; ++i) {
    largest_index = std::max(largest_index, indices[i]);
    const uint32_t word = numbers[i];
    high_bits |= word >> (3 * KD_LEAF_CORNER_BITS);
    const uint32_t highest = std::max({word & KD_LEAF_CORNER_MASK, (word >> KD_LEAF_CORNER_BITS) & KD_LEAF_CORNER_MASK,
                                       (word >> (2 * KD_LEAF_CORNER_BITS)) & KD_LEAF_CORNER_MASK});
    corners_needed = std::max(corners_needed, uint64_t{KD_LEAF_PAGE_CORNERS} * (i / KD_LEAF_PAGE_TRIANGLES) + highest + 1);
  }
  if (largest_index >= triangles) return "holds a triangle index beyond the scene's triangles";
  if (high_bits != 0) return "has a corner number word with its two top bits set";
  if (corners_needed > (size - first - 2 * uint64_t{count}) / 3) return "numbers a corner beyond the leaf blocks";
  return nullptr;
}

// A non-empty leaf met by the structure pass, its block still to check.
struct LeafSpan {
  uint64_t node;
  uint64_t first;  // the block's first word
  uint64_t count;  // its triangles
  bool grouped;    // its block's layout
};

// Checks that the nodes [begin, end) form one subtree whose root is `begin`, at `depth`, in the
// documented depth-first layout (the first child that is a node next, the above child right
// after the below subtree, empty children marked and absent), no deeper than KD_MAX_TREE_DEPTH,
// with every split finite and every leaf's block inside the leaf-block array and intact
// (leaf_block_problem). One pass in node order: each inner node with two children leaves its
// far child pending, each leaf must be followed by the nearest pending node. A load of millions
// of nodes runs it, so a node's checks are computed without branches and only a failure leaves
// the loop; the non-empty leaves are gathered, also without a branch, and their blocks checked a
// batch at a time, each fetched ahead of its check.
void validate_subtree_serially(const KdTree& tree, uint64_t begin, uint64_t end, uint32_t depth,
                               const std::string& path) {
  struct Pending {
    uint64_t node;
    uint32_t depth;
  };
  // The far children pending, deepest last, above a sentinel: after the subtree's last leaf
  // comes `end`. Their depths rise strictly and are at most KD_MAX_TREE_DEPTH, so they fit.
  Pending pending[KD_MAX_TREE_DEPTH + 2];
  pending[0] = {end, 0};
  uint32_t top = 1;  // entries in `pending`
  const uint32_t* blocks = tree.leaf_blocks.data();
  const uint64_t block_words = tree.leaf_blocks.size();
  constexpr size_t kBatch = 512;  // leaves whose blocks are checked together; 16 KiB, in L1
  LeafSpan spans[kBatch + 1];     // one more: every node writes the next entry, kept or not
  size_t span_count = 0;
  // The words the leaves claimed so far (claimed_words): blocks do not overlap, so these stay
  // within the array, which bounds the checks' work by the file's size (leaves that all claim
  // one large block would otherwise make it quadratic). Compared before each batch is checked.
  uint64_t words_claimed = 0;
  auto check_batch = [&] {
    if (words_claimed > block_words)
      throw Error(path, "damaged tree: its leaves claim more words than the leaf blocks hold");
    // The blocks lie in node order, a few cache lines apart, and the first read of each misses
    // every cache: the spans known in advance let it be fetched while earlier blocks are checked.
    constexpr size_t kAhead = 32;
    for (size_t s = 0; s < span_count; ++s) {
      if (s + kAhead < span_count) __builtin_prefetch(blocks + spans[s + kAhead].first);
      if (const char* problem = leaf_block_problem(blocks, block_words, spans[s].first,
                                                   static_cast<uint32_t>(spans[s].count), spans[s].grouped,
                                                   tree.stats.triangles))
        throw Error(path, "damaged tree: the block of leaf " + std::to_string(spans[s].node) + " " + problem);
    }
    span_count = 0;
  };
  const KdNode* nodes = tree.nodes.data();
  for (uint64_t index = begin; index < end; ++index) {
    const KdNode node = nodes[index];
    const uint32_t leaf = static_cast<uint32_t>(kd_node_is_leaf(node));
    const uint64_t count = kd_leaf_count(node);  // of a leaf
    const bool grouped = kd_leaf_grouped(node);   // of a leaf
    const uint64_t claimed = claimed_words(count, grouped);
    const uint64_t far = kd_node_far_child(node);  // of an inner node
    const Pending resume = pending[top - 1];
    const bool finite_split = (node.payload & 0x7f800000u) != 0x7f800000u;
    // As 0/1 integers combined with masks, so the compiler keeps them free of branches.
    const uint32_t leaf_mask = 0u - leaf;
    const uint32_t below_empty = static_cast<uint32_t>(kd_node_below_empty(node)) & ~leaf_mask & 1u;
    const uint32_t above_empty = static_cast<uint32_t>(kd_node_above_empty(node)) & ~leaf_mask & 1u;
    const uint32_t far_valid =
        (above_empty & static_cast<uint32_t>(far == 0)) |
        ((above_empty ^ 1u) & static_cast<uint32_t>(far < end) &
         ((below_empty & static_cast<uint32_t>(far == index + 1)) |
          ((below_empty ^ 1u) & static_cast<uint32_t>(far > index + 1))));
    const uint32_t inner_valid = far_valid & ((below_empty & above_empty) ^ 1u) &
                                 static_cast<uint32_t>(depth < KD_MAX_TREE_DEPTH) & static_cast<uint32_t>(finite_split);
    // A leaf of no triangles is a whole empty tree's root; elsewhere its parent marks it.
    const uint32_t leaf_valid = static_cast<uint32_t>(uint64_t{kd_leaf_first(node)} + claimed <= block_words) &
                                static_cast<uint32_t>(resume.node == index + 1) &
                                static_cast<uint32_t>(count != 0 || index == 0);
    const uint32_t valid = (leaf_valid & leaf_mask) | (inner_valid & ~leaf_mask);
    if (__builtin_expect(valid == 0, 0)) {
      const std::string at = "damaged tree: node " + std::to_string(index);
      if (!leaf && depth >= KD_MAX_TREE_DEPTH)
        throw Error(path, "damaged tree: deeper than " + std::to_string(KD_MAX_TREE_DEPTH) + " levels");
      if (!leaf && !finite_split) throw Error(path, at + " has a non-finite split");
      if (!leaf && below_empty && above_empty) throw Error(path, at + " marks both its children empty");
      if (!leaf) throw Error(path, at + " has an invalid far child");
      if (count == 0 && resume.node == index + 1) throw Error(path, at + " is an empty leaf below the root");
      if (resume.node == index + 1)
        throw Error(path, "damaged tree: leaf " + std::to_string(index) + " reaches past the leaf blocks");
      if (resume.node == tree.nodes.size()) throw Error(path, "damaged tree: unreachable nodes");
      throw Error(path, "damaged tree: node " + std::to_string(resume.node) + " is out of place");
    }
    const uint64_t kept = uint64_t{leaf} & static_cast<uint64_t>(count != 0);
    spans[span_count] = {index, kd_leaf_first(node), count, grouped};
    span_count += kept;
    words_claimed += claimed & (0 - kept);
    if (span_count == kBatch) check_batch();
    // An inner node with two children leaves the far one pending; one with a single child goes on
    // into it, the next node; a leaf resumes at the nearest pending node.
    const uint32_t pushed = (leaf ^ 1u) & (below_empty ^ 1u) & (above_empty ^ 1u);
    pending[top] = {far, depth + 1};  // kept only when pushed
    top = top + pushed - leaf;
    depth = (resume.depth & leaf_mask) | ((depth + 1) & ~leaf_mask);
  }
  check_batch();
}

// The same for a large subtree: its root's two subtrees are independent ranges of the array,
// [begin + 1, far) and [far, end), so they are checked in parallel down to a size worth a task.
void validate_subtree(const KdTree& tree, uint64_t begin, uint64_t end, uint32_t depth, const std::string& path) {
  constexpr uint64_t kSerialNodes = uint64_t{1} << 18;
  const KdNode root = tree.nodes[begin];
  const uint64_t far = kd_node_far_child(root);
  const bool splits = end - begin > kSerialNodes && !kd_node_is_leaf(root) && !kd_node_below_empty(root) &&
                      !kd_node_above_empty(root) && far > begin + 1 && far < end && depth < KD_MAX_TREE_DEPTH &&
                      std::isfinite(kd_node_split(root));
  if (!splits) {
    validate_subtree_serially(tree, begin, end, depth, path);
    return;
  }
  tbb::parallel_invoke([&] { validate_subtree(tree, begin + 1, far, depth + 1, path); },
                       [&] { validate_subtree(tree, far, end, depth + 1, path); });
}

// The key over (size, bytes) parts: the geometry hash, the encoded settings (section 3's bytes)
// and the format version (formats/kdtree.md).
uint64_t key_of(uint64_t geometry_hash, const std::string& encoded_settings) {
  std::unique_ptr<XXH3_state_t, decltype(&XXH3_freeState)> state(XXH3_createState(), &XXH3_freeState);
  XXH3_64bits_reset(state.get());
  auto feed = [&](const void* data, uint64_t size) {
    XXH3_64bits_update(state.get(), &size, sizeof size);
    XXH3_64bits_update(state.get(), data, size);
  };
  const uint32_t version = format::kTreeVersion;
  feed(&geometry_hash, sizeof geometry_hash);
  feed(encoded_settings.data(), encoded_settings.size());
  feed(&version, sizeof version);
  return XXH3_64bits_digest(state.get());
}

// Writes `tree` with `leaf_blocks` as its leaf-block section.
void write_tree_sections(const std::string& path, const KdTree& tree, SectionData leaf_blocks) {
  const std::string parameters = encode_settings(tree.settings);
  const std::string statistics = to_portable_binary(tree.stats);
  const float bounds[6] = {tree.bounds.min.x, tree.bounds.min.y, tree.bounds.min.z,
                           tree.bounds.max.x, tree.bounds.max.y, tree.bounds.max.z};
  const uint64_t key = key_of(tree.geometry_hash, parameters);
  const std::vector<SectionData> sections = {
      {format::kTreeNodes, tree.nodes.data(), tree.nodes.size() * sizeof(KdNode)},
      {format::kTreeParameters, parameters.data(), parameters.size()},
      {format::kTreeStatistics, statistics.data(), statistics.size()},
      {format::kTreeBounds, bounds, sizeof bounds},
      {format::kTreeKey, &key, sizeof key},
      std::move(leaf_blocks),
  };
  write_container(path, ContainerHeaderInfo{format::kTreeMagic, format::kTreeVersion, 0, tree.geometry_hash},
                  sections);
}

}  // namespace

void write_tree(const std::string& path, const KdTree& tree) {
  write_tree_sections(path, tree,
                      {format::kTreeLeafBlocks, tree.leaf_blocks.data(), tree.leaf_blocks.size() * sizeof(uint32_t)});
}

void detail::write_tree_with_planned_blocks(const std::string& path, const KdTree& tree, const Scene& scene,
                                            const uint32_t* triangles, const LeafBlockPlan& plan) {
  write_tree_sections(path, tree,
                      {format::kTreeLeafBlocks, nullptr, plan.size_words() * sizeof(uint32_t),
                       [&](uint64_t begin, uint64_t end, char* out) {
                         detail::leaf_block_bytes(scene, triangles, plan, begin, end, out);
                       }});
}

uint64_t tree_key(uint64_t geometry_hash, const BuildSettings& settings) {
  return key_of(geometry_hash, encode_settings(settings));
}

namespace {

// The tree of a mapped version 6 file, its arrays viewing the mapping, checked throughout.
KdTree tree_of(const MappedContainer& file, const std::string& path) {
  const uint32_t version = file.contents.header.version;
  if (version < format::kTreeVersion)
    throw Error(path, "a version " + std::to_string(version) +
                          " tree, which this build no longer reads (version 6 leaves name their block's layout "
                          "in their headers): rebuild it with kdbuild");
  KdTree tree;
  std::string parameters, statistics;
  float bounds[6] = {};
  uint64_t key = 0;
  uint32_t seen = 0;
  for (const format::SectionEntry& section : file.contents.sections) {
    const uint32_t id = section.id;
    const char* bytes = file.bytes + section.offset;
    const uint64_t size = section.size;
    if (id < 32) {
      if (seen & (1u << id)) throw Error(path, "damaged file: section " + std::to_string(id) + " twice");
      seen |= 1u << id;
    }
    auto elements = [&](uint64_t element, const char* what) {
      if (size % element != 0) throw Error(path, std::string("damaged ") + what + " section: odd size");
      return size / element;
    };
    switch (id) {
      case format::kTreeNodes:
        tree.nodes = {file.mapping, reinterpret_cast<const KdNode*>(bytes), elements(sizeof(KdNode), "node")};
        break;
      case format::kTreeLeafBlocks:
        tree.leaf_blocks = {file.mapping, reinterpret_cast<const uint32_t*>(bytes), elements(sizeof(uint32_t), "leaf-block")};
        break;
      case format::kTreeParameters: parameters.assign(bytes, size); break;
      case format::kTreeStatistics: statistics.assign(bytes, size); break;
      case format::kTreeBounds:
        if (size != sizeof bounds) throw Error(path, "damaged bounds section");
        std::memcpy(bounds, bytes, sizeof bounds);
        break;
      case format::kTreeKey:
        if (size != sizeof key) throw Error(path, "damaged key section");
        std::memcpy(&key, bytes, sizeof key);
        break;
      default: break;  // a section a newer writer added: not ours to read
    }
  }
  constexpr uint32_t kRequired = 1u << format::kTreeNodes | 1u << format::kTreeParameters |
                                 1u << format::kTreeStatistics | 1u << format::kTreeBounds |
                                 1u << format::kTreeKey | 1u << format::kTreeLeafBlocks;
  if ((seen & kRequired) != kRequired) throw Error(path, "damaged file: a required section is missing");
  if (key != key_of(file.contents.header.content_hash, parameters))
    throw Error(path, "damaged tree: its key " + hash_hex(key) + " does not match its geometry and build settings");
  tree.geometry_hash = file.contents.header.content_hash;
  tree.key = key;
  tree.settings = decode_settings(parameters, path);
  tree.stats = from_portable_binary<TreeStats>(statistics, path, "statistics");
  tree.bounds = Bounds{{bounds[0], bounds[1], bounds[2]}, {bounds[3], bounds[4], bounds[5]}};
  if (tree.nodes.empty()) throw Error(path, "damaged tree: no nodes");
  validate_subtree(tree, 0, tree.nodes.size(), 0, path);
  return tree;
}

}  // namespace

KdTree read_tree(const std::string& path) {
  // The file is mapped and the tree's two arrays view it. The structure and the leaf blocks are
  // checked while the checksum is computed, and nothing is used before both pass.
  KdTree tree;
  map_container(path, format::kTreeMagic, format::kTreeVersion, "kdtree",
                [&](const MappedContainer& file) { tree = tree_of(file, path); });
  return tree;
}

void check_tree_matches_scene(const KdTree& tree, const std::string& tree_path, const SceneGeometry& scene,
                              const std::string& scene_path) {
  if (tree.geometry_hash != scene.geometry_hash)
    throw Error(tree_path, "stale tree: built for geometry " + hash_hex(tree.geometry_hash) + ", but " + scene_path +
                               " has geometry " + hash_hex(scene.geometry_hash) + ": rebuild with kdbuild");
  if (tree.stats.triangles != scene.triangles)
    throw Error(tree_path, "tree is for " + std::to_string(tree.stats.triangles) + " triangles, but " + scene_path +
                               " has " + std::to_string(scene.triangles));
}

}  // namespace kdray
