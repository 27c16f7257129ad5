// The sweep over one axis's sorted events (sweep_axis, and a small node's AxisRuns) against
// costing every candidate plane from the triangles' bounds directly: the same cheapest split,
// cost, side of the planar triangles and counts, bit for bit. The cases include long runs of
// equal positions at the voxel's faces and inside it, planar triangles, and -0 beside +0 (one
// run, recorded as its first event's).
#include "build_common.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cstring>
#include <random>
#include <string>
#include <vector>

namespace kdray {
namespace {

using namespace kdray::detail;

// The split the sweep should find: every distinct position in event order, costed with
// consider_split from counts taken over all bounds.
SplitChoice every_plane(const std::vector<Box3>& bounds, const std::vector<Event>& events, int axis,
                        const Box3& voxel, const CostModel& cost, SplitChoice best) {
  const SplitAreas areas(voxel, axis);
  for (size_t i = 0; i < events.size(); ++i) {
    if (i > 0 && events[i].position == events[i - 1].position) continue;
    const float p = events[i].position;
    uint64_t left = 0, right = 0, planar = 0;
    for (const Box3& b : bounds) {
      const float lo = b.min[axis], hi = b.max[axis];
      if (lo == hi) {
        planar += lo == p;
        left += lo < p;
        right += lo > p;
      } else {
        left += lo < p;
        right += hi > p;
      }
    }
    consider_split(cost, areas, axis, p, left, right, planar, best);
  }
  return best;
}

// `count` boxes in the voxel [-1, 1] on the axis; `runs` of them start or end on a few shared
// positions (the faces, 0 as -0 and +0, one inside), some of them planar.
std::vector<Box3> boxes(size_t count, uint32_t seed, int axis) {
  std::mt19937 random(seed);
  std::uniform_real_distribution<float> unit(-1.0f, 1.0f);
  const float shared[] = {-1.0f, 1.0f, 0.0f, -0.0f, 0.25f};
  std::vector<Box3> result(count);
  for (size_t i = 0; i < count; ++i) {
    Box3& b = result[i];
    for (int k = 0; k < 3; ++k) {
      b.min[k] = -1.0f;
      b.max[k] = 1.0f;
    }
    float lo = unit(random), hi = unit(random);
    if (random() % 3 == 0) lo = shared[random() % 5];
    if (random() % 3 == 0) hi = shared[random() % 5];
    if (random() % 7 == 0) hi = lo;  // planar
    if (hi < lo) std::swap(lo, hi);
    b.min[axis] = lo;
    b.max[axis] = hi;
  }
  return result;
}

void expect_same_split(const SplitChoice& found, const SplitChoice& expected) {
  EXPECT_EQ(found.axis, expected.axis);
  EXPECT_EQ(found.cost, expected.cost);
  EXPECT_EQ(std::memcmp(&found.position, &expected.position, sizeof(float)), 0);  // -0 is not +0
  EXPECT_EQ(found.planar_left, expected.planar_left);
  EXPECT_EQ(found.n_left, expected.n_left);
  EXPECT_EQ(found.n_right, expected.n_right);
}

// Sweeps the events of `bounds` on `axis` after `earlier` (the best of the axes swept before)
// and expects the split that costing every plane finds, bit for bit; returns that split.
SplitChoice expect_the_split_of_every_plane(const std::vector<Box3>& bounds, int axis, const Box3& voxel,
                                            const CostModel& cost, const SplitChoice& earlier = SplitChoice{}) {
  std::vector<Event> events;
  for (size_t i = 0; i < bounds.size(); ++i) append_events(events, bounds[i], axis, static_cast<uint32_t>(i));
  std::sort(events.begin(), events.end());
  SplitChoice swept = earlier;
  sweep_axis(events.data(), events.size(), axis, voxel, bounds.size(), cost, swept);
  const SplitChoice expected = every_plane(bounds, events, axis, voxel, cost, earlier);
  expect_same_split(swept, expected);
  // A small node's runs, found once and costed for the voxel and again for a smaller one (as a
  // node that becomes its own child does), choose as sweeping that voxel's events does.
  if (events.size() <= AxisRuns::kMaxEvents) {
    AxisRuns runs;
    runs.find(events.data(), events.size());
    SplitChoice costed = earlier;
    runs.cost(axis, voxel, bounds.size(), cost, costed);
    expect_same_split(costed, expected);
    const int across = (axis + 1) % 3;
    Box3 smaller = voxel;
    smaller.max[across] = voxel.min[across] + 0.25f * (voxel.max[across] - voxel.min[across]);
    SplitChoice costed_smaller = earlier;
    runs.cost(axis, smaller, bounds.size(), cost, costed_smaller);
    expect_same_split(costed_smaller, every_plane(bounds, events, axis, smaller, cost, earlier));
    // And shrunk along the axis to its first event, as a split that cuts off the empty space
    // below does: a face of the voxel on the first run (a child area of exactly 1).
    Box3 cut = voxel;
    cut.min[axis] = events.front().position;
    SplitChoice costed_cut = earlier;
    runs.cost(axis, cut, bounds.size(), cost, costed_cut);
    expect_same_split(costed_cut, every_plane(bounds, events, axis, cut, cost, earlier));
  }
  return expected;
}

TEST(SweepAxis, FindsTheSplitThatCostingEveryPlaneFinds) {
  const Box3 voxel{{-1, -1, -1}, {1, 1, 1}};
  const CostModel cost{15.0, 20.0, 0.8};
  for (uint32_t seed = 1; seed <= 40; ++seed) {
    const int axis = static_cast<int>(seed % 3);
    // From a handful of boxes to thousands, with long runs of shared positions.
    const size_t count = seed % 4 == 0 ? 3 : 50 * seed;
    SCOPED_TRACE("seed " + std::to_string(seed));
    expect_the_split_of_every_plane(boxes(count, seed, axis), axis, voxel, cost);
  }
}

// The sweep skips groups of runs whose costs cannot go below the best so far: after an earlier
// axis's best a little above, equal to and below this axis's cheapest, it still finds every
// cheaper split, and keeps the earlier one on a tie.
TEST(SweepAxis, FindsEveryCheaperSplitAfterAnEarlierAxisBest) {
  const Box3 voxel{{-1, -1, -1}, {1, 1, 1}};
  const CostModel cost{15.0, 20.0, 0.8};
  for (uint32_t seed = 1; seed <= 400; ++seed) {
    const int axis = static_cast<int>(seed % 3);
    // Mostly a few boxes, whose runs' costs differ most from one to the next.
    const std::vector<Box3> bounds = boxes(seed % 40 == 0 ? 2 * seed : 4 + seed % 37, seed, axis);
    const SplitChoice cheapest = expect_the_split_of_every_plane(bounds, axis, voxel, cost);
    for (double factor : {0.5, 1.0, 1.0 + 1e-12, 1.001, 1.01, 1.1, 1.5}) {
      SCOPED_TRACE("seed " + std::to_string(seed) + ", an earlier best at " + std::to_string(factor) + "x");
      const SplitChoice earlier{cheapest.cost * factor, (axis + 1) % 3, 0.125f, true, 1, 1};
      const SplitChoice found = expect_the_split_of_every_plane(bounds, axis, voxel, cost, earlier);
      if (factor <= 1.0) {
        EXPECT_EQ(found.axis, earlier.axis);
      }
    }
  }
}

// The sweep takes its events 256 at a time: runs of equal positions that end just before, at and
// after a chunk's edge, middle and last runs that span edges, and event counts around multiples
// of the chunk.
TEST(SweepAxis, FindsTheSameSplitWithRunsAcrossChunkEdges) {
  const Box3 voxel{{0, 0, 0}, {1, 1, 1}};
  const CostModel cost{15.0, 20.0, 0.8};
  std::mt19937 random(3);
  std::uniform_real_distribution<float> low(0.05f, 0.45f), high(0.55f, 0.95f);
  for (size_t lead : {0, 1, 127, 128, 129, 254, 255, 256, 257})
    for (size_t run : {1, 130, 256, 300})
      for (bool long_last_run : {false, true}) {
        std::vector<Box3> bounds;
        auto add = [&](float lo, float hi) { bounds.push_back(Box3{{lo, 0, 0}, {hi, 1, 1}}); };
        for (size_t i = 0; i < lead; ++i) add(low(random), high(random));
        for (size_t i = 0; i < run; ++i) add(0.5f, high(random));  // a middle run of starts at 0.5
        if (long_last_run)
          for (size_t i = 0; i < 200; ++i) add(low(random), 0.97f);  // ends at 0.97, after every other
        SCOPED_TRACE(std::to_string(lead) + " leading boxes, a run of " + std::to_string(run) +
                     (long_last_run ? ", a long last run" : ""));
        expect_the_split_of_every_plane(bounds, 0, voxel, cost);
      }
}

// A long first run above empty space at the bottom of the voxel: its split cuts off that space
// (the empty bonus applies), which only the first and last runs are costed for.
TEST(SweepAxis, CostsALongFirstRunWithTheEmptyBonus) {
  const Box3 voxel{{0, 0, 0}, {1, 1, 1}};
  const CostModel cost{15.0, 20.0, 0.5};
  std::vector<Box3> bounds(600, Box3{{0.2f, 0, 0}, {0.3f, 1, 1}});
  bounds.push_back(Box3{{0.9f, 0, 0}, {1, 1, 1}});
  const SplitChoice expected = expect_the_split_of_every_plane(bounds, 0, voxel, cost);
  EXPECT_EQ(expected.position, 0.2f);  // the case is the one meant: the empty part is cut off
}

}  // namespace
}  // namespace kdray
