// The .kdtree file (formats/kdtree.md) on top of the shared section container.
#include <kdray/container_file.h>
#include <kdray/error.h>
#include <kdray/kdtree.h>

#include <kernels/kd_traverse.h>

#include <cereal/archives/portable_binary.hpp>

#include <xxhash.h>

#include <cmath>
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
            settings.perfect_splits);
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
    archive(settings.traversal_cost, settings.intersection_cost, settings.empty_bonus, settings.max_depth,
            settings.perfect_splits);
    binned = stream.peek() != std::char_traits<char>::eof();
    if (binned) archive(settings.binned_above, settings.bins);
  } catch (const std::exception&) {
    throw Error(path, "damaged parameters section");
  }
  // The exact sweep is written without the two fields: one tree, one encoding, one key.
  if (binned && settings.binned_above == 0) throw Error(path, "damaged parameters section");
  return settings;
}

// Checks that the nodes form one tree in the documented depth-first layout (near child next,
// far child right after the near subtree), no deeper than KD_MAX_TREE_DEPTH, with every leaf
// range inside the leaf-triangle array and every triangle index below `triangles`.
void validate_structure(const KdTree& tree, const std::string& path) {
  if (tree.nodes.empty()) throw Error(path, "damaged tree: no nodes");
  struct Pending {
    uint64_t node;
    uint32_t depth;
  };
  std::vector<Pending> stack{{0, 0}};
  uint64_t expected = 0;
  while (!stack.empty()) {
    const Pending item = stack.back();
    stack.pop_back();
    if (item.node != expected || item.node >= tree.nodes.size())
      throw Error(path, "damaged tree: node " + std::to_string(expected) + " is out of place");
    ++expected;
    const KdNode node = tree.nodes[item.node];
    if (kd_node_is_leaf(node)) {
      const uint64_t first = kd_leaf_first(node), count = kd_leaf_count(node);
      if (first + count > tree.leaf_triangles.size())
        throw Error(path, "damaged tree: leaf " + std::to_string(item.node) + " reaches past the leaf array");
      continue;
    }
    if (item.depth + 1 > KD_MAX_TREE_DEPTH)
      throw Error(path, "damaged tree: deeper than " + std::to_string(KD_MAX_TREE_DEPTH) + " levels");
    if (!std::isfinite(kd_node_split(node)))
      throw Error(path, "damaged tree: node " + std::to_string(item.node) + " has a non-finite split");
    const uint64_t far_child = kd_node_far_child(node);
    if (far_child <= item.node + 1 || far_child >= tree.nodes.size())
      throw Error(path, "damaged tree: node " + std::to_string(item.node) + " has an invalid far child");
    stack.push_back({far_child, item.depth + 1});
    stack.push_back({item.node + 1, item.depth + 1});
  }
  if (expected != tree.nodes.size()) throw Error(path, "damaged tree: unreachable nodes");
  for (uint32_t triangle : tree.leaf_triangles)
    if (triangle >= tree.stats.triangles)
      throw Error(path, "damaged tree: triangle index " + std::to_string(triangle) + " beyond the scene's " +
                            std::to_string(tree.stats.triangles));
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

}  // namespace

void write_tree(const std::string& path, const KdTree& tree) {
  const std::string parameters = encode_settings(tree.settings);
  const std::string statistics = to_portable_binary(tree.stats);
  const float bounds[6] = {tree.bounds.min.x, tree.bounds.min.y, tree.bounds.min.z,
                           tree.bounds.max.x, tree.bounds.max.y, tree.bounds.max.z};
  const uint64_t key = key_of(tree.geometry_hash, parameters);
  const std::vector<SectionData> sections = {
      {format::kTreeNodes, tree.nodes.data(), tree.nodes.size() * sizeof(KdNode)},
      {format::kTreeLeafTriangles, tree.leaf_triangles.data(), tree.leaf_triangles.size() * sizeof(uint32_t)},
      {format::kTreeParameters, parameters.data(), parameters.size()},
      {format::kTreeStatistics, statistics.data(), statistics.size()},
      {format::kTreeBounds, bounds, sizeof bounds},
      {format::kTreeKey, &key, sizeof key},
  };
  write_container(path, ContainerHeaderInfo{format::kTreeMagic, format::kTreeVersion, 0, tree.geometry_hash},
                  sections);
}

uint64_t tree_key(uint64_t geometry_hash, const BuildSettings& settings) {
  return key_of(geometry_hash, encode_settings(settings));
}

KdTree read_tree(const std::string& path) {
  KdTree tree;
  std::string parameters, statistics;
  float bounds[6] = {};
  uint64_t key = 0;
  uint32_t seen = 0;
  auto element_count = [&](uint64_t size, uint64_t element, const char* what) {
    if (size % element != 0) throw Error(path, std::string("damaged ") + what + " section: odd size");
    return size / element;
  };
  const ContainerContents contents =
      read_container(path, format::kTreeMagic, format::kTreeVersion, "kdtree", [&](uint32_t id, uint64_t size) -> void* {
        if (id >= format::kTreeNodes && id <= format::kTreeKey) {
          if (seen & (1u << id)) throw Error(path, "damaged file: section " + std::to_string(id) + " twice");
          seen |= 1u << id;
        }
        switch (id) {
          case format::kTreeNodes:
            tree.nodes.resize(element_count(size, sizeof(KdNode), "node"));
            return tree.nodes.data();
          case format::kTreeLeafTriangles:
            tree.leaf_triangles.resize(element_count(size, sizeof(uint32_t), "leaf-triangle"));
            return tree.leaf_triangles.data();
          case format::kTreeParameters:
            parameters.resize(size);
            return parameters.data();
          case format::kTreeStatistics:
            statistics.resize(size);
            return statistics.data();
          case format::kTreeBounds:
            if (size != sizeof bounds) throw Error(path, "damaged bounds section");
            return bounds;
          case format::kTreeKey:
            if (size != sizeof key) throw Error(path, "damaged key section");
            return &key;
          default:
            return nullptr;
        }
      });
  const uint32_t version = contents.header.version;
  // Sections 1-5, and the key from version 2 on.
  const uint32_t required = version >= 2 ? 0x7eu : 0x3eu;
  if ((seen & required) != required) throw Error(path, "damaged file: a required section is missing");
  if (version >= 2) {
    if (key != key_of(contents.header.content_hash, parameters))
      throw Error(path, "damaged tree: its key " + hash_hex(key) + " does not match its geometry and build settings");
    tree.geometry_hash = contents.header.content_hash;
    tree.key = key;
  } else {
    tree.v1_scene_hash = contents.header.content_hash;
  }
  tree.settings = decode_settings(parameters, path);
  tree.stats = from_portable_binary<TreeStats>(statistics, path, "statistics");
  tree.bounds = Bounds{{bounds[0], bounds[1], bounds[2]}, {bounds[3], bounds[4], bounds[5]}};
  validate_structure(tree, path);
  return tree;
}

void check_tree_matches_scene(const KdTree& tree, const std::string& tree_path, const Scene& scene,
                              const std::string& scene_path) {
  if (tree.v1_scene_hash != 0 && tree.v1_scene_hash != scene.content_hash)
    throw Error(tree_path, "stale tree: built for scene " + hash_hex(tree.v1_scene_hash) + ", but " + scene_path +
                               " has " + hash_hex(scene.content_hash) + ": rebuild with kdbuild");
  if (tree.v1_scene_hash == 0 && tree.geometry_hash != scene.geometry_hash)
    throw Error(tree_path, "stale tree: built for geometry " + hash_hex(tree.geometry_hash) + ", but " + scene_path +
                               " has geometry " + hash_hex(scene.geometry_hash) + ": rebuild with kdbuild");
  if (tree.stats.triangles != scene.triangle_count())
    throw Error(tree_path, "tree is for " + std::to_string(tree.stats.triangles) + " triangles, but " + scene_path +
                               " has " + std::to_string(scene.triangle_count()));
  for (uint32_t triangle : tree.leaf_triangles)
    if (triangle >= scene.triangle_count())
      throw Error(tree_path, "triangle index " + std::to_string(triangle) + " beyond " + scene_path);
}

}  // namespace kdray
