// The tree cache: keys, hits and misses, damaged entries, concurrent builders, eviction, and
// reading the previous format versions.
#include "test_scenes.h"

#include <kdray/atomic_file.h>
#include <kdray/container_file.h>
#include <kdray/scene_file.h>
#include <kdray/tree_cache.h>

#include <test_corpus.h>

#include <gtest/gtest.h>

#include <cstring>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <thread>

#include <sys/stat.h>

namespace kdray {
namespace {

namespace fs = std::filesystem;

class TreeCacheTest : public test::TempDirTest<> {
 protected:
  void SetUp() override { scene_ = test::box_room(); }
  TreeCache cache() { return TreeCache(path("cache"), [this](const std::string& line) { warnings_.push_back(line); }); }

  static std::vector<char> bytes_of(const std::string& file) {
    std::ifstream in(file, std::ios::binary);
    return std::vector<char>(std::istreambuf_iterator<char>(in), {});
  }
  // Entry files of the cache folder other than KEY.kdtree and KEY.scenes (temporaries left behind).
  std::vector<std::string> stray_files() const {
    std::vector<std::string> stray;
    for (const fs::directory_entry& entry : fs::directory_iterator(path("cache"))) {
      const std::string name = entry.path().filename().string();
      if (name.size() != 16 + entry.path().extension().string().size() ||
          (entry.path().extension() != ".kdtree" && entry.path().extension() != ".scenes"))
        stray.push_back(name);
    }
    return stray;
  }

  static bool same_tree(const KdTree& a, const KdTree& b) { return test::same_tree_bytes(a, b); }

  Scene scene_;
  std::vector<std::string> warnings_;
};

TEST_F(TreeCacheTest, TheKeyCoversGeometrySettingsAndNothingElse) {
  const uint64_t key = tree_key(scene_.geometry_hash, BuildSettings{}.resolved(scene_.triangle_count()));
  Scene recoloured = scene_;
  recoloured.materials[0].base_color = {0.1f, 0.2f, 0.3f};
  recoloured.cameras.push_back(default_camera(scene_bounds(recoloured)));
  recoloured.content_hash = compute_content_hash(recoloured);
  ASSERT_NE(recoloured.content_hash, scene_.content_hash);
  EXPECT_EQ(compute_geometry_hash(recoloured), scene_.geometry_hash);

  Scene moved = scene_;
  moved.positions[0].x += 0.25f;
  EXPECT_NE(compute_geometry_hash(moved), scene_.geometry_hash);
  Scene rewired = scene_;
  std::swap(rewired.indices[0], rewired.indices[1]);
  EXPECT_NE(compute_geometry_hash(rewired), scene_.geometry_hash);

  BuildSettings costly;
  costly.traversal_cost = 30;
  EXPECT_NE(tree_key(scene_.geometry_hash, costly.resolved(scene_.triangle_count())), key);
  BuildSettings coarse;
  coarse.perfect_splits = false;
  EXPECT_NE(tree_key(scene_.geometry_hash, coarse.resolved(scene_.triangle_count())), key);

  const KdTree tree = build_kdtree(scene_, BuildSettings{});
  EXPECT_EQ(tree.geometry_hash, scene_.geometry_hash);
  EXPECT_EQ(tree.key, key);
}

TEST_F(TreeCacheTest, AMissBuildsAndStoresAHitReadsTheSameTree) {
  TreeCache trees = cache();
  const CachedTree first = cached_tree(trees, scene_, path("room.kdscene"), BuildSettings{});
  EXPECT_FALSE(first.hit);
  EXPECT_EQ(first.entry, trees.tree_path(first.tree.key));
  const CachedTree second = cached_tree(trees, scene_, path("room.kdscene"), BuildSettings{});
  EXPECT_TRUE(second.hit);
  EXPECT_TRUE(same_tree(second.tree, first.tree));
  ASSERT_EQ(trees.entries().size(), 1u);
  EXPECT_EQ(trees.entries()[0].scenes, std::vector<std::string>{path("room.kdscene")});
  EXPECT_TRUE(warnings_.empty());
  EXPECT_TRUE(stray_files().empty());
}

TEST_F(TreeCacheTest, AMaterialChangeHitsAndTheTreeServesTheNewScene) {
  TreeCache trees = cache();
  cached_tree(trees, scene_, path("room.kdscene"), BuildSettings{});
  Scene recoloured = scene_;
  recoloured.materials[0].emission = {5, 5, 5};
  recoloured.content_hash = compute_content_hash(recoloured);
  const CachedTree again = cached_tree(trees, recoloured, path("recoloured.kdscene"), BuildSettings{});
  EXPECT_TRUE(again.hit);
  EXPECT_NO_THROW(check_tree_matches_scene(again.tree, again.entry, geometry_of(recoloured), "recoloured.kdscene"));
  ASSERT_EQ(trees.entries().size(), 1u);
  EXPECT_EQ(trees.entries()[0].scenes.size(), 2u);
}

TEST_F(TreeCacheTest, AGeometryOrSettingsChangeMisses) {
  TreeCache trees = cache();
  cached_tree(trees, scene_, path("room.kdscene"), BuildSettings{});
  Scene moved = scene_;
  moved.positions[3].y += 0.5f;
  moved.geometry_hash = compute_geometry_hash(moved);
  EXPECT_FALSE(cached_tree(trees, moved, path("moved.kdscene"), BuildSettings{}).hit);
  BuildSettings costly;
  costly.intersection_cost = 40;
  EXPECT_FALSE(cached_tree(trees, scene_, path("room.kdscene"), costly).hit);
  EXPECT_EQ(trees.entries().size(), 3u);
}

TEST_F(TreeCacheTest, ADamagedEntryIsRemovedWithAWarningAndRebuilt) {
  TreeCache trees = cache();
  const CachedTree built = cached_tree(trees, scene_, path("room.kdscene"), BuildSettings{});
  std::vector<char> bytes = bytes_of(built.entry);
  bytes[bytes.size() - 5] ^= 0x40;
  std::ofstream(built.entry, std::ios::binary | std::ios::trunc).write(bytes.data(), std::streamsize(bytes.size()));

  const CachedTree rebuilt = cached_tree(trees, scene_, path("room.kdscene"), BuildSettings{}, {}, path("out.kdtree"));
  EXPECT_FALSE(rebuilt.hit);
  ASSERT_EQ(warnings_.size(), 1u);
  EXPECT_NE(warnings_[0].find("damaged cache entry"), std::string::npos) << warnings_[0];
  EXPECT_NE(warnings_[0].find("checksum"), std::string::npos) << warnings_[0];
  EXPECT_NO_THROW(read_tree(built.entry));
  EXPECT_EQ(bytes_of(path("out.kdtree")), bytes_of(built.entry));
  EXPECT_TRUE(cached_tree(trees, scene_, path("room.kdscene"), BuildSettings{}).hit);
}

TEST_F(TreeCacheTest, AnEntryUnderAnotherKeysNameIsDamage) {
  TreeCache trees = cache();
  const CachedTree built = cached_tree(trees, scene_, path("room.kdscene"), BuildSettings{});
  BuildSettings costly;
  costly.traversal_cost = 30;
  fs::copy_file(built.entry, trees.tree_path(tree_key(scene_.geometry_hash, costly.resolved(scene_.triangle_count()))));
  EXPECT_FALSE(cached_tree(trees, scene_, path("room.kdscene"), costly).hit);
  ASSERT_EQ(warnings_.size(), 1u);
  EXPECT_NE(warnings_[0].find("holds the tree of key"), std::string::npos) << warnings_[0];
}

TEST_F(TreeCacheTest, AHitIsACopyNotAHardLink) {
  TreeCache trees = cache();
  const CachedTree built = cached_tree(trees, scene_, path("room.kdscene"), BuildSettings{});
  const CachedTree copied = cached_tree(trees, scene_, path("room.kdscene"), BuildSettings{}, {}, path("out.kdtree"));
  ASSERT_TRUE(copied.hit);
  struct stat entry {}, output {};
  ASSERT_EQ(::stat(built.entry.c_str(), &entry), 0);
  ASSERT_EQ(::stat(path("out.kdtree").c_str(), &output), 0);
  EXPECT_NE(entry.st_ino, output.st_ino);
  EXPECT_EQ(entry.st_nlink, 1u);
  const std::vector<char> original = bytes_of(built.entry);
  std::ofstream(path("out.kdtree"), std::ios::binary | std::ios::app) << "edited";
  EXPECT_EQ(bytes_of(built.entry), original);
}

TEST_F(TreeCacheTest, ConcurrentBuildersOfOneKeyLeaveOneIntactEntry) {
  const Scene big = test::triangle_soup(20000, 7);
  std::vector<std::thread> builders;
  std::vector<CachedTree> results(4);
  for (size_t i = 0; i < results.size(); ++i)
    builders.emplace_back([&, i] {
      TreeCache trees(path("cache"));
      results[i] = cached_tree(trees, big, path("soup.kdscene"), BuildSettings{}, {1, {}, nullptr},
                               path("out" + std::to_string(i) + ".kdtree"));
    });
  for (std::thread& builder : builders) builder.join();
  TreeCache trees = cache();
  ASSERT_EQ(trees.entries().size(), 1u);
  const std::vector<char> entry = bytes_of(trees.entries()[0].tree_path);
  EXPECT_NO_THROW(read_tree(trees.entries()[0].tree_path));
  for (size_t i = 0; i < results.size(); ++i) EXPECT_EQ(bytes_of(path("out" + std::to_string(i) + ".kdtree")), entry);
  EXPECT_TRUE(stray_files().empty());
}

TEST_F(TreeCacheTest, TheFirstOfTwoWritersOfATargetWins) {
  AtomicFile first(path("target")), second(path("target"));
  std::ofstream(first.temporary_path()) << "first";
  std::ofstream(second.temporary_path()) << "second";
  EXPECT_TRUE(first.commit_unless_exists());
  EXPECT_FALSE(second.commit_unless_exists());
  EXPECT_EQ(std::string(bytes_of(path("target")).data(), 5), "first");
  EXPECT_FALSE(fs::exists(second.temporary_path()));
}

TEST_F(TreeCacheTest, AHitMarksTheEntryUsed) {
  TreeCache trees = cache();
  const CachedTree built = cached_tree(trees, scene_, path("room.kdscene"), BuildSettings{});
  const auto old_time = fs::file_time_type::clock::now() - std::chrono::hours(24);
  fs::last_write_time(built.entry, old_time);
  ASSERT_TRUE(cached_tree(trees, scene_, path("room.kdscene"), BuildSettings{}).hit);
  EXPECT_GT(fs::last_write_time(built.entry), old_time);
}

TEST_F(TreeCacheTest, EvictionRemovesTheLeastRecentlyUsedFirstButNeverTheKeptEntry) {
  TreeCache trees = cache();
  struct Made {
    uint64_t key;
    std::string tree_path;
  };
  std::vector<Made> made;
  for (float size : {1.0f, 2.0f, 3.0f, 4.0f}) {
    Scene sphere = test::icosphere_scene(2, {0, 0, 0}, size);
    const CachedTree built = cached_tree(trees, sphere, path("sphere.kdscene"), BuildSettings{});
    made.push_back({built.tree.key, built.entry});
  }
  // Last uses, oldest first: entry 2, 0, 3, 1.
  const auto now = fs::file_time_type::clock::now();
  const int hours_ago[] = {3, 1, 4, 2};
  for (size_t i = 0; i < made.size(); ++i) fs::last_write_time(made[i].tree_path, now - std::chrono::hours(hours_ago[i]));
  const std::vector<CacheEntry> listed = trees.entries();
  ASSERT_EQ(listed.size(), 4u);
  EXPECT_EQ(listed[0].key, made[1].key);
  EXPECT_EQ(listed[3].key, made[2].key);

  uint64_t total = 0;
  for (const CacheEntry& entry : listed) total += entry.bytes;
  // Room for all but about two entries; the oldest (2) is the one being used, so it stays.
  const std::vector<CacheEntry> removed = trees.evict(total - listed[3].bytes - listed[2].bytes, made[2].key);
  ASSERT_EQ(removed.size(), 2u);
  EXPECT_EQ(removed[0].key, made[0].key);
  EXPECT_EQ(removed[1].key, made[3].key);
  EXPECT_FALSE(fs::exists(made[0].tree_path));
  EXPECT_TRUE(fs::exists(made[2].tree_path));
  EXPECT_EQ(trees.entries().size(), 2u);
}

// Trees before version 6 hold their leaves, their empty leaves or their leaf headers in another
// form: they are refused with the file and what to do, and a scene file of an earlier version is
// still read.
TEST_F(TreeCacheTest, PreviousTreeVersionsAreRefusedWithARebuildMessage) {
  const std::string fixtures = std::string(KDRAY_SOURCE_DIR) + "/tests/kdtree/fixtures/";
  const Scene scene = read_scene(fixtures + "cornell-box-v2.kdscene");
  EXPECT_EQ(scene.geometry_hash, compute_geometry_hash(scene));
  for (const char* name : {"cornell-box-v1.kdtree", "cornell-box-v2.kdtree", "cornell-box-v3.kdtree",
                           "cornell-box-v4.kdtree", "cornell-box-v5.kdtree"}) {
    try {
      read_tree(fixtures + name);
      ADD_FAILURE() << name << " was read";
    } catch (const Error& error) {
      const std::string message = error.what();
      EXPECT_NE(message.find(name), std::string::npos) << message;
      EXPECT_NE(message.find(std::string("a version ") + name[13] + " tree"), std::string::npos) << message;
      EXPECT_NE(message.find("rebuild it with kdbuild"), std::string::npos) << message;
    }
  }
}

}  // namespace
}  // namespace kdray
