// A folder of prebuilt trees, keyed by exactly what a tree depends on: the scene's geometry
// hash, the build settings and the tree format version (tree_key). A scene whose materials,
// textures, lights or cameras change keeps its tree.
//
// Layout (formats/kdtree.md, "Tree cache"): KEY.kdtree, the tree, whose modification time is its
// last use; KEY.scenes, the scene files it was built or found for, one per line. Entries are
// written to a temporary file and renamed into place without replacing an existing entry, so
// builders of one key running at once never tear or mix an entry: the first wins and the others'
// work is discarded. Every use verifies the entry's checksum; a damaged entry is removed (with a
// warning) and counts as a miss. A hit is copied out (reflinked where the file system shares
// blocks), never hard-linked, so editing an output cannot touch the cache.
#pragma once

#include <kdray/kdtree.h>

#include <cstdint>
#include <ctime>
#include <functional>
#include <optional>
#include <string>
#include <vector>

namespace kdray {

struct CacheEntry {
  uint64_t key = 0;
  std::string tree_path;            // FOLDER/KEY.kdtree
  uint64_t bytes = 0;               // the tree and its list of scenes
  std::timespec last_use{};         // the tree file's modification time
  std::vector<std::string> scenes;  // absolute paths of the scene files it served
};

// Receives warnings (a damaged entry removed) as one line each.
using CacheWarning = std::function<void(const std::string& message)>;

class TreeCache {
 public:
  // Creates the folder if needed. Throws kdray::Error naming it when that fails.
  explicit TreeCache(std::string folder, CacheWarning warn = {});

  const std::string& folder() const { return folder_; }
  std::string tree_path(uint64_t key) const;

  // The tree of `key`, read and verified from its entry, or nothing when there is no intact entry.
  // A hit marks the entry used now and records `scene_path` among its scenes.
  std::optional<KdTree> load(uint64_t key, const std::string& scene_path);

  // Copies the entry of `key` to `output` atomically (a reflink where possible, else a copy) and
  // verifies the copy's checksum; returns the tree, or nothing when there is no intact entry.
  std::optional<KdTree> copy_out(uint64_t key, const std::string& output, const std::string& scene_path);

  // Builds the tree of `scene` for `settings` into the entry of `key` (build_tree_file) unless an
  // entry is already there by then (a concurrent builder won; its tree has the same bytes), and
  // returns it. Throws kdray::Error naming `scene_path` when the built tree's key is not `key`
  // (the scene's recorded geometry hash is not that of its triangles); nothing is stored then.
  KdTree build(uint64_t key, const Scene& scene, const std::string& scene_path, const BuildSettings& settings,
               const BuildControl& control);

  // Every entry, most recently used first. Temporary files of writers at work are not entries.
  std::vector<CacheEntry> entries() const;

  // Removes least recently used entries until the rest total at most `max_bytes`, never the
  // entry of `keep` (the one just used). Returns the removed entries, oldest first.
  std::vector<CacheEntry> evict(uint64_t max_bytes, uint64_t keep);

 private:
  std::string scenes_path(uint64_t key) const;  // KEY.scenes: the scenes an entry served
  void mark_used(uint64_t key, const std::string& scene_path);
  void remove_damaged(uint64_t key, const std::string& problem);

  std::string folder_;
  CacheWarning warn_;
};

// What cached_tree did.
struct CachedTree {
  KdTree tree;
  bool hit = false;
  std::string entry;  // the entry's tree path
};

// The tree of `scene` (read from `scene_path`) for `settings`: from the cache on a hit, else
// built and stored. When `output` is not empty the tree is also written there, copied from the
// entry.
CachedTree cached_tree(TreeCache& cache, const Scene& scene, const std::string& scene_path,
                       const BuildSettings& settings, const BuildControl& control = {},
                       const std::string& output = {});

// The scene at `scene_path` and the tree a tool uses with it: read from `tree_path` (both files
// at once) and checked against the scene, or, when `cache_folder` is given instead, found in
// that cache or built there with the default settings.
struct SceneAndTree {
  Scene scene;
  KdTree tree;
};
SceneAndTree read_scene_and_tree(const std::string& scene_path, const std::string& tree_path,
                                 const std::string& cache_folder, const CacheWarning& warn);

// The tree at `tree_path` for a tool that traces it without the scene's arrays (the tree holds
// its triangles' corners): checked against the geometry of the scene at `scene_path`
// (read_scene_geometry), both files read at once.
KdTree read_tree_for_scene(const std::string& scene_path, const std::string& tree_path);

}  // namespace kdray
