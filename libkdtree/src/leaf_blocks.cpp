// Leaf blocks (kernels/kd_types.h): each non-empty leaf's triangles, paged (indices, corner
// numbers and distinct corners) or grouped (four triangles' indices and corners by axis),
// planned once for their sizes and made where they go.
#include "leaf_blocks.h"

#include <kdray/error.h>

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>
#include <tbb/enumerable_thread_specific.h>

#include <algorithm>
#include <cstring>

namespace kdray {
namespace detail {
namespace {

// A page's distinct corners: its distinct scene vertices in the order its triangles first meet
// them (corners of equal position but different vertices are stored twice; meshes rarely have
// them). Found through a small open-addressed table rather than by searching the corners so
// far, which costs tens of comparisons a corner once a leaf holds a few triangles; the table
// is emptied by a new stamp, not cleared.
class PageCorners {
 public:
  void clear() {
    vertices.clear();
    if (++stamp_ == 0) {  // after 2^32 pages: stamps from the last round could match
      std::fill(std::begin(stamps_), std::end(stamps_), 0u);
      stamp_ = 1;
    }
  }

  // The vertex's corner number on this page, the next one when it is new.
  uint32_t number(uint32_t vertex) {
    uint32_t slot = (vertex * 0x9E3779B1u) >> (32 - kSlotBits);
    while (stamps_[slot] == stamp_) {
      if (vertices[numbers_[slot]] == vertex) return numbers_[slot];
      slot = (slot + 1) & (kSlots - 1);
    }
    stamps_[slot] = stamp_;
    numbers_[slot] = static_cast<uint16_t>(vertices.size());
    vertices.push_back(vertex);
    return numbers_[slot];
  }

  std::vector<uint32_t> vertices;  // the page's distinct vertices, by corner number

 private:
  // At least twice a page's most corners (3 KD_LEAF_PAGE_TRIANGLES), so probes stay short.
  static constexpr uint32_t kSlotBits = 11;
  static constexpr uint32_t kSlots = 1u << kSlotBits;
  static_assert(kSlots >= 2 * 3 * KD_LEAF_PAGE_TRIANGLES, "the corner table is too small for a page");
  uint32_t stamps_[kSlots] = {};
  uint16_t numbers_[kSlots];
  uint32_t stamp_ = 0;
};

// Numbers the corners of the leaf's triangles [page_start, page_end), one page: `corners`
// becomes the page's and, where `numbers` is given, numbers[i] triangle i's corner-number word.
void number_page(const Scene& scene, const uint32_t* triangles, uint32_t page_start, uint32_t page_end,
                 PageCorners& corners, uint32_t* numbers) {
  corners.clear();
  for (uint32_t i = page_start; i < page_end; ++i) {
    uint32_t word = 0;
    for (uint32_t corner = 0; corner < 3; ++corner)
      word |= corners.number(scene.indices[3 * size_t{triangles[i]} + corner])
              << (KD_LEAF_CORNER_BITS * corner);
    if (numbers) numbers[i] = word;
  }
}

// The size in words of the block of the leaf of `count` triangles `triangles[0, count)`: every
// page but the last fills its KD_LEAF_PAGE_CORNERS corners.
uint64_t block_words(const Scene& scene, const uint32_t* triangles, uint32_t count,
                     PageCorners& corners) {
  const uint32_t last_page = (count - 1) / KD_LEAF_PAGE_TRIANGLES;
  number_page(scene, triangles, last_page * KD_LEAF_PAGE_TRIANGLES, count, corners, nullptr);
  return 2 * uint64_t{count} + 3 * (uint64_t{KD_LEAF_PAGE_CORNERS} * last_page + corners.vertices.size());
}

// The grouped block of the leaf of `count` triangles `triangles[0, count)` to out; the last
// group is filled up with its first triangle.
void make_grouped_block(const Scene& scene, const uint32_t* triangles, uint32_t count, char* out) {
  for (uint32_t first = 0; first < count; first += 4, out += 4 * KD_LEAF_GROUP_WORDS) {
    float corners[36];
    uint32_t indices[4];
    for (uint32_t lane = 0; lane < 4; ++lane) {
      const uint32_t triangle = triangles[first + lane < count ? first + lane : first];
      indices[lane] = triangle;
      for (uint32_t corner = 0; corner < 3; ++corner) {
        const Vec3& p = scene.positions[scene.indices[3 * size_t{triangle} + corner]];
        corners[12 * corner + lane] = p.x;
        corners[12 * corner + 4 + lane] = p.y;
        corners[12 * corner + 8 + lane] = p.z;
      }
    }
    std::memcpy(out, indices, sizeof indices);
    std::memcpy(out + sizeof indices, corners, sizeof corners);
  }
}

// The paged block itself, `size` words (block_words), to out; the padding of full pages is zeros.
void make_block(const Scene& scene, const uint32_t* triangles, uint32_t count, uint64_t size,
                PageCorners& corners, std::vector<uint32_t>& numbers, char* out) {
  std::memset(out, 0, 4 * size);
  std::memcpy(out, triangles, 4 * size_t{count});
  numbers.resize(count);
  for (uint32_t page_start = 0; page_start < count; page_start += KD_LEAF_PAGE_TRIANGLES) {
    number_page(scene, triangles, page_start, std::min(count, page_start + KD_LEAF_PAGE_TRIANGLES), corners,
                numbers.data());
    const uint64_t page_first = 2 * uint64_t{count} + 3 * uint64_t{KD_LEAF_PAGE_CORNERS} * (page_start / KD_LEAF_PAGE_TRIANGLES);
    for (size_t k = 0; k < corners.vertices.size(); ++k)
      std::memcpy(out + 4 * (page_first + 3 * k), &scene.positions[corners.vertices[k]], 3 * sizeof(float));
  }
  std::memcpy(out + 4 * size_t{count}, numbers.data(), 4 * size_t{count});
}

}  // namespace

uint64_t grouped_block_words(uint64_t count) { return KD_LEAF_GROUP_WORDS * ((count + 3) / 4); }

LeafBlockPlan plan_leaf_blocks(const Scene& scene, TraversalArray<KdNode>& nodes, const uint32_t* triangles,
                               LeafLayout layout) {
  if (layout == LeafLayout::automatic) throw Error("", "plan_leaf_blocks: the leaf layout must be resolved");
  LeafBlockPlan plan;
  plan.grouped = layout == LeafLayout::grouped;
  for (const KdNode& node : nodes)
    if (kd_node_is_leaf(node) && kd_leaf_count(node) > 0) {
      plan.entries.push_back(kd_leaf_first(node));
      plan.counts.push_back(kd_leaf_count(node));
    }
  const size_t leaves = plan.counts.size();
  plan.words.resize(leaves + 1);
  tbb::parallel_for(tbb::blocked_range<size_t>(0, leaves, 1024), [&](const tbb::blocked_range<size_t>& range) {
    PageCorners corners;
    for (size_t leaf = range.begin(); leaf < range.end(); ++leaf)
      plan.words[leaf + 1] = plan.grouped
                                 ? grouped_block_words(plan.counts[leaf])
                                 : block_words(scene, triangles + plan.entries[leaf], plan.counts[leaf], corners);
  });
  for (size_t leaf = 0; leaf < leaves; ++leaf) plan.words[leaf + 1] += plan.words[leaf];
  if (plan.size_words() > UINT32_MAX)
    throw Error("", "the tree's leaf blocks would take " + std::to_string(plan.size_words()) +
                        " words, more than the 32-bit leaf payloads can address");
  // Payloads in node order: each leaf's block start; the one empty leaf (an empty scene's root)
  // the next block's.
  size_t next_leaf = 0;
  for (size_t n = 0; n < nodes.size(); ++n) {
    if (!kd_node_is_leaf(nodes[n])) continue;
    const uint32_t count = kd_leaf_count(nodes[n]);
    nodes[n] = kd_leaf_node(static_cast<uint32_t>(plan.words[next_leaf]), count, plan.grouped && count > 0);
    if (count > 0) ++next_leaf;
  }
  return plan;
}

void leaf_block_bytes(const Scene& scene, const uint32_t* triangles, const LeafBlockPlan& plan, uint64_t begin,
                      uint64_t end, char* out) {
  if (begin >= end) return;
  // The leaves whose blocks meet [begin, end): from the one holding `begin` to the one holding end - 1.
  const auto& words = plan.words;
  const size_t first = static_cast<size_t>(std::upper_bound(words.begin(), words.end(), begin / 4) - words.begin()) - 1;
  const size_t last = static_cast<size_t>(std::upper_bound(words.begin(), words.end(), (end - 1) / 4) - words.begin());
  // A block wholly inside the range is made where it goes; one the range cuts, in a scratch
  // block first.
  struct Scratch {
    PageCorners corners;
    std::vector<uint32_t> numbers;
    std::vector<char> block;
  };
  tbb::enumerable_thread_specific<Scratch> scratches;
  tbb::parallel_for(tbb::blocked_range<size_t>(first, last, 256), [&](const tbb::blocked_range<size_t>& range) {
    Scratch& scratch = scratches.local();
    for (size_t leaf = range.begin(); leaf < range.end(); ++leaf) {
      const uint64_t block_begin = 4 * words[leaf], block_end = 4 * words[leaf + 1];
      const uint64_t size = words[leaf + 1] - words[leaf];
      const uint32_t* leaf_triangles = triangles + plan.entries[leaf];
      auto make = [&](char* to) {
        if (plan.grouped)
          make_grouped_block(scene, leaf_triangles, plan.counts[leaf], to);
        else
          make_block(scene, leaf_triangles, plan.counts[leaf], size, scratch.corners, scratch.numbers, to);
      };
      if (block_begin >= begin && block_end <= end) {
        make(out + (block_begin - begin));
        continue;
      }
      scratch.block.resize(4 * size);
      make(scratch.block.data());
      const uint64_t from = std::max(begin, block_begin), to = std::min(end, block_end);
      std::memcpy(out + (from - begin), scratch.block.data() + (from - block_begin), to - from);
    }
  });
}

}  // namespace detail

TraversalArray<uint32_t> leaf_blocks_of(const Scene& scene, TraversalArray<KdNode>& nodes, const uint32_t* triangles,
                                        LeafLayout layout) {
  const detail::LeafBlockPlan plan = detail::plan_leaf_blocks(scene, nodes, triangles, layout);
  TraversalArray<uint32_t> blocks(plan.size_words());
  detail::leaf_block_bytes(scene, triangles, plan, 0, 4 * plan.size_words(), reinterpret_cast<char*>(blocks.data()));
  return blocks;
}

}  // namespace kdray
