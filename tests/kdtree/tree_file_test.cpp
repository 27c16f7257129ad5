// The .kdtree file: round trip, damage, structural validation and stale trees.
#include "test_scenes.h"
#include "leaf_blocks.h"

#include <kdray/container_file.h>
#include <kdray/kdtree.h>
#include <kdray/traverse.h>

#include <test_corpus.h>

#include <gtest/gtest.h>

#include <cstring>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <utility>
#include <vector>

namespace kdray {
namespace {

class KdTreeFile : public test::TempDirTest<> {
 protected:
  void SetUp() override {
    scene_ = test::icosphere_scene(2, {0, 0, 0}, 1);
    tree_ = build_kdtree(scene_, BuildSettings{});
  }

  std::vector<char> bytes_of(const std::string& file) const {
    std::ifstream in(file, std::ios::binary);
    return std::vector<char>(std::istreambuf_iterator<char>(in), {});
  }
  void write_bytes(const std::string& file, const std::vector<char>& bytes) const {
    std::ofstream out(file, std::ios::binary | std::ios::trunc);
    out.write(bytes.data(), static_cast<std::streamsize>(bytes.size()));
  }
  std::string read_error(const std::string& file) const {
    try {
      read_tree(file);
    } catch (const Error& error) {
      return error.what();
    }
    return "";
  }

  Scene scene_;
  KdTree tree_;
};

TEST_F(KdTreeFile, RoundTripKeepsEverything) {
  BuildSettings settings;
  settings.traversal_cost = 10;
  settings.max_depth = 12;
  settings.perfect_splits = false;
  const KdTree tree = build_kdtree(scene_, settings);
  write_tree(path("a.kdtree"), tree);
  const KdTree back = read_tree(path("a.kdtree"));
  EXPECT_EQ(back.geometry_hash, scene_.geometry_hash);
  EXPECT_EQ(back.key, tree_key(scene_.geometry_hash, settings.resolved(scene_.triangle_count())));
  ASSERT_EQ(back.nodes.size(), tree.nodes.size());
  EXPECT_EQ(0, std::memcmp(back.nodes.data(), tree.nodes.data(), tree.nodes.size() * sizeof(KdNode)));
  EXPECT_TRUE(test::same_tree_bytes(back, tree));
  EXPECT_TRUE(back.nodes.mapped() && back.leaf_blocks.mapped()) << "a read tree views its file";
  EXPECT_EQ(back.settings.traversal_cost, 10.0f);
  EXPECT_EQ(back.settings.max_depth, 12u);
  EXPECT_FALSE(back.settings.perfect_splits);
  EXPECT_EQ(back.settings.leaf_layout, LeafLayout::grouped) << "a small scene's automatic layout, recorded";
  EXPECT_EQ(back.stats.sah_cost, tree.stats.sah_cost);
  EXPECT_EQ(back.stats.leaves, tree.stats.leaves);
  EXPECT_EQ(back.bounds.max.y, tree.bounds.max.y);
  EXPECT_NO_THROW(check_tree_matches_scene(back, "a.kdtree", geometry_of(scene_), "s.kdscene"));
}

// build_tree_file makes the leaf blocks as it writes them, a 1 MiB piece of the file at a time,
// blocks cut at the pieces' edges: the file must be the one write_tree writes.
TEST_F(KdTreeFile, BuiltStraightIntoItsFileIsTheFileWriteTreeWrites) {
  const Scene scene = test::icosphere_scene(6, {0, 0, 0}, 1);  // 81,920 triangles
  for (LeafLayout layout : {LeafLayout::grouped, LeafLayout::paged}) {
    BuildSettings settings;
    settings.leaf_layout = layout;
    BuildTimings timings;
    const TreeSummary built = build_tree_file(scene, path("straight.kdtree"), settings, BuildControl{2, {}, &timings});
    const KdTree in_memory = build_kdtree(scene, settings);
    write_tree(path("written.kdtree"), in_memory);
    ASSERT_GT(in_memory.leaf_blocks.size() * sizeof(uint32_t), uint64_t{2} << 20) << "blocks cut by a piece's end";
    EXPECT_TRUE(bytes_of(path("straight.kdtree")) == bytes_of(path("written.kdtree")));
    EXPECT_EQ(built.key, in_memory.key);
    EXPECT_EQ(built.stats.leaf_references, test::leaf_triangle_indices(in_memory).size());
    EXPECT_EQ(built.stats.sah_cost, in_memory.stats.sah_cost);
    EXPECT_GT(timings.write, 0.0);
  }
}

// The blocks' bytes in any range, as a writer asks for them: inside one block, across the
// boundary of two, and whole blocks with parts at either end; one paged leaf of two pages, and
// grouped leaves whose last group is filled up.
class LeafBlockBytes : public KdTreeFile, public ::testing::WithParamInterface<LeafLayout> {};

TEST_P(LeafBlockBytes, OfAnyRangeAreThoseOfTheWholeArray) {
  const LeafLayout layout = GetParam();
  ASSERT_GT(scene_.triangle_count(), 300u);
  std::vector<uint32_t> triangles;
  for (uint32_t t = 0; t < 300; ++t) triangles.push_back(t);
  // A split on x at 0 (far child 2), then leaves of triangles [0, 21) and [21, 300).
  TraversalArray<KdNode> nodes = {KdNode{0, 2u << KD_CHILD_SHIFT}, kd_leaf_node(0, 21, 0), kd_leaf_node(21, 279, 0)};
  TraversalArray<KdNode> planned = nodes;
  const TraversalArray<uint32_t> whole = leaf_blocks_of(scene_, nodes, triangles.data(), layout);
  const detail::LeafBlockPlan plan = detail::plan_leaf_blocks(scene_, planned, triangles.data(), layout);
  EXPECT_EQ(0, std::memcmp(nodes.data(), planned.data(), nodes.size() * sizeof(KdNode)));
  ASSERT_EQ(plan.size_words(), whole.size());
  EXPECT_EQ(nodes[2].payload, plan.words[1]);
  const char* bytes = reinterpret_cast<const char*>(whole.data());
  const uint64_t size = whole.size() * sizeof(uint32_t), second = 4 * plan.words[1];
  for (const auto& [begin, end] : std::vector<std::pair<uint64_t, uint64_t>>{
           {0, size}, {0, 1}, {3, 17}, {second - 4, second + 8}, {second - 1, second + 1}, {second, size},
           {13, size - 7}, {size - 1, size}, {77, 77}}) {
    std::vector<char> made(end - begin + 1, 'x');
    detail::leaf_block_bytes(scene_, triangles.data(), plan, begin, end, made.data());
    EXPECT_EQ(0, std::memcmp(made.data(), bytes + begin, end - begin)) << begin << ".." << end;
    EXPECT_EQ(made.back(), 'x') << begin << ".." << end << ": nothing written past the range";
  }
  for (const KdNode& leaf : {nodes[1], nodes[2]}) {
    EXPECT_EQ(kd_leaf_grouped(leaf), layout == LeafLayout::grouped);
    const uint32_t* block = whole.data() + kd_leaf_first(leaf);
    for (uint32_t i = 0; i < kd_leaf_count(leaf); ++i)
      EXPECT_EQ(kd_leaf_index(block, kd_leaf_grouped(leaf), i), triangles[(leaf.payload == 0 ? 0 : 21) + i]);
  }
  if (layout == LeafLayout::grouped) {
    // The first leaf's 21 triangles in 6 groups, the last of one triangle and three copies of it;
    // the second leaf's 279 in 70.
    EXPECT_EQ(plan.words[1], 6u * KD_LEAF_GROUP_WORDS);
    EXPECT_EQ(whole.size(), 76u * KD_LEAF_GROUP_WORDS);
    const uint32_t* last = whole.data() + 5 * KD_LEAF_GROUP_WORDS;
    EXPECT_EQ(last[1], last[0]);
    EXPECT_EQ(last[3], last[0]);
    const float* corners = reinterpret_cast<const float*>(last + 4);
    const Vec3& b = scene_.positions[scene_.indices[3 * size_t{triangles[20]} + 1]];
    EXPECT_EQ(corners[12 + 4 * 1 + 0], b.y) << "coordinate y of corner b, lane 0";
    EXPECT_EQ(corners[12 + 4 * 1 + 2], b.y) << "a filled-up lane repeats it";
    return;
  }
  // The second leaf's 279 triangles number their corners in two pages, the first padded to
  // KD_LEAF_PAGE_CORNERS corners: its block is 2 x 279 words, then 1024 + N corners.
  const uint64_t corner_words = whole.size() - plan.words[1] - 2 * 279;
  EXPECT_EQ(corner_words % 3, 0u);
  EXPECT_GT(corner_words / 3, uint64_t{KD_LEAF_PAGE_CORNERS});
}

INSTANTIATE_TEST_SUITE_P(Layouts, LeafBlockBytes, ::testing::Values(LeafLayout::paged, LeafLayout::grouped),
                         [](const auto& info) { return info.param == LeafLayout::paged ? "Paged" : "Grouped"; });

TEST_F(KdTreeFile, BinningIsRecordedAndAnExactTreeKeepsItsKey) {
  BuildSettings binned, exact;
  binned.binned_above = 20;
  binned.bins = 32;
  exact.binned_above = 0;
  write_tree(path("binned.kdtree"), build_kdtree(scene_, binned));
  write_tree(path("exact.kdtree"), build_kdtree(scene_, exact));
  const KdTree binned_back = read_tree(path("binned.kdtree"));
  EXPECT_EQ(binned_back.settings.binned_above, 20u);
  EXPECT_EQ(binned_back.settings.bins, 32u);
  EXPECT_EQ(binned_back.key, tree_key(scene_.geometry_hash, binned.resolved(scene_.triangle_count())));
  EXPECT_EQ(read_tree(path("exact.kdtree")).settings.binned_above, 0u);
  EXPECT_NE(tree_key(1, binned), tree_key(1, exact));
  // The key of a fixed geometry and settings, so that a change to the encoding or the key shows
  // (version 2 gave 0x4237eda0fa487d3c, version 3 0xb7c5220bd88d19c5, version 4
  // 0xbefeff730f16f7ce, version 5 0xc1c8e505256988a8, all before the leaf layout was recorded).
  exact.leaf_layout = LeafLayout::paged;
  EXPECT_EQ(tree_key(0x0123456789abcdefull, exact), 0x9c60b6fac1c79659ull);
  BuildSettings grouped = exact;
  grouped.leaf_layout = LeafLayout::grouped;
  EXPECT_NE(tree_key(1, grouped), tree_key(1, exact));
}

// A read tree views its file's pages: a writer replacing the file (by rename, as every writer
// does) leaves the tree that was read as it was, and changing a read tree changes a copy.
TEST_F(KdTreeFile, AReadTreeOutlivesItsFileBeingReplaced) {
  write_tree(path("a.kdtree"), tree_);
  KdTree back = read_tree(path("a.kdtree"));
  const KdTree other = build_kdtree(test::icosphere_scene(3, {0, 0, 0}, 1), BuildSettings{});
  write_tree(path("a.kdtree"), other);
  EXPECT_TRUE(test::same_tree_bytes(back, tree_));
  EXPECT_TRUE(test::same_tree_bytes(read_tree(path("a.kdtree")), other));
  back.nodes.own()[0].payload ^= 1u;
  EXPECT_FALSE(back.nodes.mapped());
  EXPECT_TRUE(back.leaf_blocks.mapped());
  EXPECT_TRUE(test::same_tree_bytes(read_tree(path("a.kdtree")), other));
}

// A read tree is copied out of its file for rays enough to repay the copy, and only then; the
// copy is the same tree, and one in memory already is not copied again.
TEST_F(KdTreeFile, AReadTreeIsCopiedOutOfItsFileForManyRays) {
  write_tree(path("a.kdtree"), tree_);
  KdTree tree = read_tree(path("a.kdtree"));
  const uint64_t bytes = tree.nodes.size() * sizeof(KdNode) + tree.leaf_blocks.size() * sizeof(uint32_t);
  const size_t enough = bytes / kTreeBytesPerRay;
  ASSERT_GT(enough, 1u);
  EXPECT_FALSE(copy_tree_for_rays(tree, enough - 1));
  EXPECT_TRUE(tree.nodes.mapped());
  EXPECT_TRUE(tree.leaf_blocks.mapped());
  for (unsigned threads : {1u, 2u}) {
    KdTree copied = read_tree(path("a.kdtree"));
    EXPECT_TRUE(copy_tree_for_rays(copied, enough, threads));
    EXPECT_FALSE(copied.nodes.mapped());
    EXPECT_FALSE(copied.leaf_blocks.mapped());
    EXPECT_TRUE(test::same_tree_bytes(copied, tree_));
    EXPECT_FALSE(copy_tree_for_rays(copied, SIZE_MAX)) << "a tree in memory already";
  }
}

TEST_F(KdTreeFile, SameTreeGivesTheSameBytes) {
  write_tree(path("a.kdtree"), tree_);
  write_tree(path("b.kdtree"), build_kdtree(scene_, BuildSettings{}, BuildControl{1, {}}));
  EXPECT_EQ(bytes_of(path("a.kdtree")), bytes_of(path("b.kdtree")));
}

TEST_F(KdTreeFile, FlippedPayloadByteIsRejected) {
  write_tree(path("a.kdtree"), tree_);
  std::vector<char> bytes = bytes_of(path("a.kdtree"));
  bytes[bytes.size() - 5] ^= 0x10;
  write_bytes(path("a.kdtree"), bytes);
  EXPECT_NE(read_error(path("a.kdtree")).find("checksum"), std::string::npos) << read_error(path("a.kdtree"));
}

TEST_F(KdTreeFile, TruncatedFileIsRejected) {
  write_tree(path("a.kdtree"), tree_);
  std::vector<char> bytes = bytes_of(path("a.kdtree"));
  bytes.resize(bytes.size() / 2);
  write_bytes(path("a.kdtree"), bytes);
  EXPECT_NE(read_error(path("a.kdtree")), "");
}

TEST_F(KdTreeFile, SceneFileIsNotATree) {
  write_bytes(path("a.kdtree"), std::vector<char>{'K', 'D', 'S', 'C', 'E', 'N', 'E', '\0', 1, 2, 3});
  EXPECT_NE(read_error(path("a.kdtree")).find("a.kdtree"), std::string::npos);
  EXPECT_NE(read_error(path("missing.kdtree")), "");
}

// Structural damage with a valid checksum: what a buggy writer could produce.
TEST_F(KdTreeFile, InvalidStructureIsRejected) {
  auto expect_rejected = [&](KdTree tree, const char* what, const char* expected) {
    write_tree(path("bad.kdtree"), tree);
    const std::string error = read_error(path("bad.kdtree"));
    EXPECT_NE(error.find(expected), std::string::npos) << what << ": " << error;
  };
  ASSERT_FALSE(kd_node_is_leaf(tree_.nodes[0]));
  ASSERT_FALSE(kd_node_below_empty(tree_.nodes[0]) || kd_node_above_empty(tree_.nodes[0]));
  KdTree tree = tree_;
  tree.nodes.own()[0].header = static_cast<uint32_t>(tree.nodes.size() + 5) << KD_CHILD_SHIFT | kd_node_axis(tree.nodes[0]);
  expect_rejected(tree, "far child out of range", "far child");
  tree = tree_;
  tree.nodes.own()[0].header = 1u << KD_CHILD_SHIFT | kd_node_axis(tree.nodes[0]);
  expect_rejected(tree, "far child = near child", "far child");
  tree = tree_;
  tree.nodes.own()[0].header |= KD_ABOVE_EMPTY;
  expect_rejected(tree, "an empty above child with a far child", "far child");
  tree = tree_;
  tree.nodes.own()[0].header |= KD_BELOW_EMPTY;
  expect_rejected(tree, "an empty below child with the far child not next", "far child");
  tree = tree_;
  tree.nodes.own()[0].header = KD_BELOW_EMPTY | KD_ABOVE_EMPTY | kd_node_axis(tree.nodes[0]);
  expect_rejected(tree, "both children empty", "both its children empty");
  tree = tree_;
  for (KdNode& node : tree.nodes.own())
    if (kd_node_is_leaf(node)) {
      node.header = KD_LEAF_TAG;
      break;
    }
  expect_rejected(tree, "an empty leaf below the root", "empty leaf below the root");
  tree = tree_;
  for (KdNode& node : tree.nodes.own())
    if (kd_node_is_leaf(node) && kd_leaf_count(node) > 0) {
      node.payload = static_cast<uint32_t>(tree.leaf_blocks.size() - 1);
      break;
    }
  expect_rejected(tree, "leaf block past the array", "past the leaf blocks");
  tree = tree_;
  tree.nodes.own().push_back(tree.nodes[tree.nodes.size() - 1]);
  expect_rejected(tree, "extra node", "unreachable");
  tree = tree_;
  tree.nodes.own().clear();
  expect_rejected(tree, "no nodes", "no nodes");
}

// Every block is checked, wherever it lies in the array: a triangle index beyond the scene's and
// the top bits of a corner-number word in the first leaf, one in the middle and the last, and a
// corner numbered beyond the array in the last (a traversal reads nothing else, so a number
// that stays inside the array is the checksum's to catch). A grouped block: its last triangle's
// index, in the last group.
TEST_F(KdTreeFile, EveryLeafBlockIsChecked) {
  const Scene scene = test::icosphere_scene(5, {0, 0, 0}, 1);
  BuildSettings paged;
  paged.leaf_layout = LeafLayout::paged;
  const KdTree intact = build_kdtree(scene, paged);
  std::vector<KdNode> leaves;
  for (const KdNode& node : intact.nodes)
    if (kd_node_is_leaf(node) && kd_leaf_count(node) > 0) leaves.push_back(node);
  ASSERT_GT(leaves.size(), 100u);
  for (const KdNode& leaf : {leaves.front(), leaves[leaves.size() / 2], leaves.back()}) {
    const uint32_t first = kd_leaf_first(leaf), count = kd_leaf_count(leaf);
    auto expect_found = [&](uint32_t word, uint32_t value, const char* expected) {
      KdTree tree = intact;
      tree.leaf_blocks.own()[word] = value;
      write_tree(path("bad.kdtree"), tree);
      const std::string error = read_error(path("bad.kdtree"));
      EXPECT_NE(error.find(expected), std::string::npos) << "word " << word << ": " << error;
    };
    expect_found(first + count - 1, static_cast<uint32_t>(scene.triangle_count()), "triangle index");
    expect_found(first + 2 * count - 1, 1u << 31, "top bits");
    if (first == kd_leaf_first(leaves.back()))
      expect_found(first + count, KD_LEAF_CORNER_MASK << (2 * KD_LEAF_CORNER_BITS), "corner beyond");
  }
  const KdTree grouped = build_kdtree(scene, BuildSettings{});
  leaves.clear();
  for (const KdNode& node : grouped.nodes)
    if (kd_node_is_leaf(node) && kd_leaf_count(node) > 0) leaves.push_back(node);
  for (const KdNode& leaf : {leaves.front(), leaves[leaves.size() / 2], leaves.back()}) {
    ASSERT_TRUE(kd_leaf_grouped(leaf));
    const uint32_t last = kd_leaf_count(leaf) - 1;
    KdTree tree = grouped;
    tree.leaf_blocks.own()[kd_leaf_first(leaf) + KD_LEAF_GROUP_WORDS * (last / 4) + last % 4] =
        static_cast<uint32_t>(scene.triangle_count());
    write_tree(path("bad.kdtree"), tree);
    const std::string error = read_error(path("bad.kdtree"));
    EXPECT_NE(error.find("triangle index"), std::string::npos) << error;
  }
}

// Leaves that all claim the same large block: their checks would cost the block's size each, so
// the reader stops once the leaves claim more words than the array holds.
TEST_F(KdTreeFile, LeavesClaimingOneBlockAreRejected) {
  KdTree tree = tree_;
  const uint32_t count = 200;  // each leaf a valid block of one page, all at word 0
  ASSERT_GT(tree.leaf_blocks.size(), 2 * count + 3);
  ASSERT_GT(tree.stats.leaves * 2 * count, tree.leaf_blocks.size());
  for (KdNode& node : tree.nodes.own())
    if (kd_node_is_leaf(node)) node = kd_leaf_node(0, count, 0);
  TraversalArray<uint32_t>& words = tree.leaf_blocks.own();
  for (uint32_t i = 0; i < count; ++i) words[i] = 0, words[count + i] = 0;
  write_tree(path("claims.kdtree"), tree);
  EXPECT_NE(read_error(path("claims.kdtree")).find("claim more words"), std::string::npos)
      << read_error(path("claims.kdtree"));
}

// A file damaged in its structure and in its bytes: the checksum is what the reader reports.
TEST_F(KdTreeFile, AChecksumMismatchIsReportedBeforeWhatTheChecksBesideItFound) {
  KdTree tree = tree_;
  tree.nodes.own()[0].header = static_cast<uint32_t>(tree.nodes.size() + 5) << KD_CHILD_SHIFT | kd_node_axis(tree.nodes[0]);
  write_tree(path("a.kdtree"), tree);
  std::vector<char> bytes = bytes_of(path("a.kdtree"));
  bytes[bytes.size() - 5] ^= 0x10;
  write_bytes(path("a.kdtree"), bytes);
  EXPECT_NE(read_error(path("a.kdtree")).find("checksum"), std::string::npos) << read_error(path("a.kdtree"));
}

// A leaf of triangle 0 whose block (appended to the tree's) is valid: its index, its corner
// numbers 0, 1, 2 and three corners.
KdNode add_one_triangle_leaf(KdTree& tree) {
  TraversalArray<uint32_t>& words = tree.leaf_blocks.own();
  const uint32_t first = static_cast<uint32_t>(words.size());
  words.push_back(0);
  words.push_back(0u | 1u << KD_LEAF_CORNER_BITS | 2u << (2 * KD_LEAF_CORNER_BITS));
  const float corners[9] = {0, 0, 0, 1, 0, 0, 0, 1, 0};
  for (float corner : corners) {
    uint32_t bits;
    std::memcpy(&bits, &corner, sizeof bits);
    words.push_back(bits);
  }
  return kd_leaf_node(first, 1, 0);
}

// A tree of about 1.6 million nodes, large enough that a reader checks its subtrees in parallel
// pieces: 2^15 leaves of one triangle under a complete tree of 15 levels, each at the end of a
// chain of 48 inner nodes with one empty child (alternately above and below). Damage deep in
// either half must still be found.
KdTree large_tree() {
  constexpr uint32_t kLevels = 15, kChain = 48;
  KdTree tree;
  tree.stats.triangles = 1;
  tree.settings.leaf_layout = LeafLayout::paged;  // add_one_triangle_leaf's blocks
  struct Builder {
    KdTree& tree;
    void add(uint32_t depth) {
      const uint32_t index = static_cast<uint32_t>(tree.nodes.size());
      if (depth == kLevels + kChain) {
        tree.nodes.own().push_back(add_one_triangle_leaf(tree));
        return;
      }
      if (depth >= kLevels) {
        tree.nodes.own().push_back(KdNode{0, (depth % 2 ? KD_ABOVE_EMPTY : KD_BELOW_EMPTY) | depth % 3});
        add(depth + 1);
        if (depth % 2 == 0) tree.nodes.own()[index].header |= (index + 1) << KD_CHILD_SHIFT;
        return;
      }
      tree.nodes.own().push_back(KdNode{0, depth % 3});
      add(depth + 1);
      tree.nodes.own()[index].header |= static_cast<uint32_t>(tree.nodes.size()) << KD_CHILD_SHIFT;
      add(depth + 1);
    }
  } builder{tree};
  builder.add(0);
  return tree;
}

TEST_F(KdTreeFile, LargeTreesAreCheckedThroughout) {
  const KdTree intact = large_tree();
  write_tree(path("intact.kdtree"), intact);
  EXPECT_EQ(read_error(path("intact.kdtree")), "");
  auto two_children = [&](size_t index) {
    const KdNode node = intact.nodes[index];
    return !kd_node_is_leaf(node) && !kd_node_below_empty(node) && !kd_node_above_empty(node);
  };
  size_t in_near_half = intact.nodes.size() / 4, in_far_half = intact.nodes.size() - 3;
  while (!two_children(in_near_half)) ++in_near_half;
  while (!two_children(in_far_half)) --in_far_half;
  ASSERT_GT(in_far_half, intact.nodes.size() / 2);
  for (const size_t damaged : {in_near_half, in_far_half}) {
    KdTree tree = intact;
    tree.nodes.own()[damaged].header =
        static_cast<uint32_t>(damaged + 1) << KD_CHILD_SHIFT | kd_node_axis(tree.nodes[damaged]);
    write_tree(path("damaged.kdtree"), tree);
    EXPECT_NE(read_error(path("damaged.kdtree")).find("node " + std::to_string(damaged) + " has an invalid far child"),
              std::string::npos)
        << read_error(path("damaged.kdtree"));
    tree = intact;
    tree.nodes.own()[damaged] = add_one_triangle_leaf(tree);  // a leaf where an inner node was: its subtree is left over
    write_tree(path("damaged.kdtree"), tree);
    EXPECT_NE(read_error(path("damaged.kdtree")), "") << "inner node " << damaged << " made a leaf";
  }
}

TEST_F(KdTreeFile, TreeDeeperThanTheFullStackIsRejected) {
  // A chain of 70 inner nodes, each with an empty above child, then a leaf: depth 70.
  KdTree tree;
  tree.stats.triangles = 1;
  tree.settings.leaf_layout = LeafLayout::paged;  // add_one_triangle_leaf's blocks
  for (uint32_t level = 0; level < 70; ++level) tree.nodes.own().push_back(KdNode{0, KD_ABOVE_EMPTY});
  tree.nodes.own().push_back(add_one_triangle_leaf(tree));
  write_tree(path("deep.kdtree"), tree);
  EXPECT_NE(read_error(path("deep.kdtree")).find("deeper"), std::string::npos) << read_error(path("deep.kdtree"));
  tree.nodes.own().erase(tree.nodes.own().begin(), tree.nodes.own().begin() + (70 - KD_MAX_TREE_DEPTH));
  write_tree(path("deepest.kdtree"), tree);
  EXPECT_EQ(read_error(path("deepest.kdtree")), "") << "a leaf at depth " << KD_MAX_TREE_DEPTH;
}

TEST_F(KdTreeFile, AKeyThatDoesNotMatchTheSettingsIsDamage) {
  write_tree(path("a.kdtree"), tree_);
  std::vector<char> bytes = bytes_of(path("a.kdtree"));
  // The header's geometry hash lies outside the checksum: changing it breaks the key instead.
  bytes[24] ^= 1;
  write_bytes(path("b.kdtree"), bytes);
  EXPECT_NE(read_error(path("b.kdtree")).find("does not match its geometry and build settings"), std::string::npos)
      << read_error(path("b.kdtree"));
}

TEST_F(KdTreeFile, StaleTreeNamesBothHashes) {
  const Scene other = test::icosphere_scene(2, {0, 0, 0}, 2);
  try {
    check_tree_matches_scene(tree_, "t.kdtree", geometry_of(other), "other.kdscene");
    FAIL() << "a stale tree was accepted";
  } catch (const Error& error) {
    const std::string message = error.what();
    EXPECT_NE(message.find("stale tree"), std::string::npos) << message;
    EXPECT_NE(message.find(hash_hex(scene_.geometry_hash)), std::string::npos) << message;
    EXPECT_NE(message.find(hash_hex(other.geometry_hash)), std::string::npos) << message;
    EXPECT_NE(message.find("other.kdscene"), std::string::npos) << message;
    EXPECT_NE(message.find("rebuild with kdbuild"), std::string::npos) << message;
  }
}

}  // namespace
}  // namespace kdray
