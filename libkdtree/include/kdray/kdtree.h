// The SAH k-d tree: build settings, the tree itself, its statistics and the .kdtree file
// (formats/kdtree.md).
#pragma once

#include <kdray/error.h>
#include <kdray/scene.h>
#include <kdray/traversal_array.h>

#include <kernels/kd_types.h>

#include <cstdint>
#include <functional>
#include <string>
#include <vector>

namespace kdray {

// How a leaf's block lays out its triangles (kernels/kd_types.h): grouped, four triangles'
// corners by axis (one load a coordinate of four, about twice the bytes), or paged (each
// distinct corner once, numbered). Automatic: grouped for scenes of up to
// BuildSettings::kGroupedLeavesUpTo triangles, paged above, where a tree twice the size costs
// every load, cache and build its bytes for gains within the noise (bench/LOG.md, "`.kdtree`
// version 6").
enum class LeafLayout : uint8_t { automatic = 0, grouped = 1, paged = 2 };

// Everything that decides the shape of the tree; recorded in the .kdtree file. The names and
// defaults are those of the SAH k-d tree literature (formats/kdtree.md).
struct BuildSettings {
  static constexpr float kDefaultTraversalCost = 15.0f;     // K_T
  static constexpr float kDefaultIntersectionCost = 20.0f;  // K_I
  static constexpr float kDefaultEmptyBonus = 0.8f;         // lambda when one side is empty
  static constexpr uint32_t kAutoMaxDepthCap = 48;          // cap of 8 + log2 N
  static constexpr uint32_t kMaxDepthLimit = KD_MAX_TREE_DEPTH;  // the full traversal stack
  static constexpr uint32_t kDefaultBinnedAbove = 32768;  // nodes of more triangles are binned
  static constexpr uint32_t kDefaultBins = 256;           // per axis
  static constexpr uint32_t kMaxBins = 1u << 16;
  static constexpr uint64_t kGroupedLeavesUpTo = uint64_t{1} << 18;  // LeafLayout::automatic

  float traversal_cost = kDefaultTraversalCost;
  float intersection_cost = kDefaultIntersectionCost;
  float empty_bonus = kDefaultEmptyBonus;
  // 0: automatic, 8 + log2 N capped at kAutoMaxDepthCap (N: the scene's triangles). A tree
  // records the limit it was built with, never 0 (trees written before that record 0).
  uint32_t max_depth = 0;
  bool perfect_splits = true;  // false: candidate planes from unclipped triangle bounds
  // Nodes of more than binned_above triangles choose their split among the bins - 1 evenly
  // spaced planes of each axis, counted in bins (Shevtsov, Soupikov and Kapustin 2007), which
  // is fast; smaller nodes take the exact sweep over every candidate plane. 0: the exact sweep
  // everywhere (kdbuild --exact).
  uint32_t binned_above = kDefaultBinnedAbove;
  uint32_t bins = kDefaultBins;
  LeafLayout leaf_layout = LeafLayout::automatic;

  // These settings with the automatic depth limit and leaf layout made explicit for a scene of
  // `triangles` triangles: what the tree built from them records, and what its key names.
  BuildSettings resolved(uint64_t triangles) const;
};

// Structure and quality of a built tree. Deterministic: recorded in the file, so it holds no
// timings (the bytes of a tree must not depend on the machine or thread count).
struct TreeStats {
  uint64_t triangles = 0;          // triangles of the scene
  uint64_t inner_nodes = 0;
  uint64_t leaves = 0;
  uint64_t empty_leaves = 0;
  uint64_t leaf_references = 0;    // triangles of all leaves (a triangle counts in each of its leaves)
  uint32_t max_depth = 0;          // of any leaf, root = 0
  double mean_leaf_depth = 0;
  double mean_triangles_per_leaf = 0;  // over non-empty leaves
  double references_per_triangle = 0;
  // The builder's cost of the whole tree, C(root) with C = lambda (K_T + P_L C_L + P_R C_R) for
  // an inner node and K_I N for a leaf (formats/kdtree.md).
  double sah_cost = 0;
};

// What a tree is apart from its two arrays.
struct TreeSummary {
  Bounds bounds;  // the root voxel
  BuildSettings settings;
  TreeStats stats;
  // What it was built from: the scene's geometry hash and, with the settings and the format
  // version, the tree's key (tree_key; the name of its tree cache entry).
  uint64_t geometry_hash = 0;
  uint64_t key = 0;
};

struct KdTree : TreeSummary {
  TreeArray<KdNode> nodes;                  // root first; see kernels/kd_types.h
  TreeArray<uint32_t> leaf_blocks;  // a block of words per non-empty leaf (kernels/kd_types.h)
};

// The key of the tree of a scene with this geometry hash built with these settings: XXH3-64 over
// the geometry hash, the encoded settings and the tree format version (formats/kdtree.md). A built
// tree's settings are resolved (BuildSettings::resolved), so its key is that of the resolved ones.
uint64_t tree_key(uint64_t geometry_hash, const BuildSettings& settings);

// Called with the fraction of triangles placed in finished subtrees (0..1), from any thread,
// serialised by the builder.
using BuildProgress = std::function<void(double fraction)>;

// Wall seconds of the phases of one build (machine-dependent, so never part of the tree).
struct BuildTimings {
  double prepare = 0;   // triangle bounds and the root voxel
  double events = 0;    // the root's events, sorted on each axis (0 when the root is binned)
  double subdivide = 0; // choosing splits and dividing nodes down to the leaves (with the events
                        // of the exact subtrees below binned nodes)
  double assemble = 0;  // joining the subtrees built in parallel into one node array
  double statistics = 0;
  double write = 0;  // build_tree_file: the file written, its leaf blocks made as it goes
};

struct BuildControl {
  unsigned threads = 0;  // 0: all hardware threads; the tree is the same for any count
  BuildProgress progress;
  BuildTimings* timings = nullptr;  // filled in when set
};

// Builds the tree for scene (its geometry hash and key are computed from its arrays). Triangles
// with non-finite vertices are left out. Throws kdray::Error for settings out of range.
KdTree build_kdtree(const Scene& scene, const BuildSettings& settings, const BuildControl& control = {});

// The same tree written to `path` (atomically) as write_tree writes it, its leaf blocks made
// from the scene as the file is written rather than held in memory beside it: a build's peak
// memory is the builder's. read_tree(path) reads the tree. Throws kdray::Error.
TreeSummary build_tree_file(const Scene& scene, const std::string& path, const BuildSettings& settings,
                            const BuildControl& control = {});

// The leaf-block array (kernels/kd_types.h) of the leaves of `nodes`, whose payloads are their
// first entries of `triangles`, an array of the scene's triangle indices that the leaves are
// ranges of (the builder's), in `layout` (grouped or paged); sets each leaf's payload to its
// block's first word and its header's layout bit. Throws kdray::Error when the array would
// outgrow the 32-bit payloads.
TraversalArray<uint32_t> leaf_blocks_of(const Scene& scene, TraversalArray<KdNode>& nodes, const uint32_t* triangles,
                                        LeafLayout layout);

// Statistics of a tree, from its nodes (its leaf blocks need not be there).
TreeStats compute_tree_stats(const KdTree& tree, uint64_t scene_triangles);

// Writes atomically. Throws kdray::Error.
void write_tree(const std::string& path, const KdTree& tree);

// Reads and validates a .kdtree: checksum, then every node, child and leaf range, so that
// traversal can trust it. The tree's arrays view the mapped file (TreeArray). Throws
// kdray::Error naming the file; trees of versions before 4 are refused ("rebuild").
KdTree read_tree(const std::string& path);

// Throws kdray::Error when the tree was built for other geometry ("stale tree: built for
// geometry <hash>, but <scene path> has geometry <hash>: rebuild with kdbuild") or is for
// another triangle count (its triangle indices were checked against its own count when it was
// read or built). The scene's geometry: geometry_of(scene), or read_scene_geometry(scene_path).
void check_tree_matches_scene(const KdTree& tree, const std::string& tree_path, const SceneGeometry& scene,
                              const std::string& scene_path);

}  // namespace kdray
