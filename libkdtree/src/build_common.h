// The parts of tree building that the O(N log N) builder (build_events.cpp) and the
// O(N log^2 N) reference builder in tests/kdtree share, so that "same candidates, cost and
// termination" holds by construction and the tests check only the event bookkeeping:
// candidate bounds (perfect splits), the cost function, the sweep over sorted events, the
// classification of triangles, and the encoding of nodes into a subtree. The binned builder
// (build_binned.cpp) costs its candidates with the same function (consider_split).
#pragma once

#include <kdray/kdtree.h>
#include <kdray/scene.h>

#include <kernels/kd_types.h>

#include <algorithm>
#include <array>
#include <cstddef>
#include <cstdint>
#include <cstring>
#include <memory>
#include <new>
#include <utility>
#include <vector>

namespace kdray::detail {

struct Box3 {
  float min[3];
  float max[3];
};

double surface_area(const Box3& box);
Box3 box_of(const Bounds& bounds);

// The voxel on one side of a split plane.
Box3 below_plane(const Box3& voxel, int axis, float position);
Box3 above_plane(const Box3& voxel, int axis, float position);

// Bounds of triangle `triangle` of the scene inside `voxel`: the triangle clipped to the
// voxel (Sutherland-Hodgman in double, rounded outwards to float) with perfect splits, or its
// bounding box intersected with the voxel without. False when nothing is left.
bool triangle_bounds_in_voxel(const Scene& scene, uint32_t triangle, const Box3& voxel, bool perfect_splits,
                              Box3& out);

// The bounds of a triangle in both children of a split on `axis`, `child_voxels` below and above
// it (they differ from the parent voxel only on `axis`, where the first's max is the second's
// min, the split plane), false where it leaves nothing. With
// perfect splits, the triangle clipped by the parent voxel's planes once, then the polygon left
// by the split plane for each child (Sutherland-Hodgman in double, rounded outwards to float);
// without, its bounds in the parent voxel, `parent_bounds`, intersected with each child voxel.
struct StraddlerBounds {
  bool reaches[2];
  Box3 bounds[2];
};
StraddlerBounds straddler_bounds(const Scene& scene, uint32_t triangle, const Box3& parent_bounds,
                                 const Box3 (&child_voxels)[2], int axis, bool perfect_splits);

struct SplitChoice;

// Seed cost: lambda * (K_T + K_I * (P_L N_L + P_R N_R)), lambda = empty bonus when one side is
// empty and neither side is the whole voxel.
struct CostModel {
  double traversal;
  double intersection;
  double empty_bonus;
  // What the builders charge for each reference a split adds (straddlers counted on both sides),
  // per unit of the node's surface area: K_I x root area / N. The SAH alone takes any split
  // cheaper than the leaf, however little it saves for the references it duplicates; where
  // long thin triangles overlap deep, splits that save almost nothing double the references
  // level after level (a 1.2M-triangle stress mesh reached 66 per triangle). At this price, N
  // more references must lower the whole tree's cost by at least one triangle test per ray.
  // 0 (cost_model_of(settings)): references are free, for costing finished trees.
  double reference_price = 0;
  double split_cost(double p_left, double p_right, uint64_t n_left, uint64_t n_right) const;
  // split_cost for a split with triangles on both sides, where no empty bonus applies.
  double split_cost_both_sides(double p_left, double p_right, uint64_t n_left, uint64_t n_right) const {
    // Counts are below 2^62: the signed conversion is exact and cheaper than the unsigned one.
    return traversal + intersection * (p_left * static_cast<double>(static_cast<int64_t>(n_left)) +
                                       p_right * static_cast<double>(static_cast<int64_t>(n_right)));
  }
  double leaf_cost(uint64_t n) const { return intersection * static_cast<double>(n); }
  // Whether `split` of a node of `n` triangles in `voxel` is taken: it must cost less than the
  // leaf, by more than the price of the references it adds.
  bool split_pays(const SplitChoice& split, uint64_t n, const Box3& voxel) const;
};
CostModel cost_model_of(const BuildSettings& settings);
// The builders' cost model for a root `voxel` of `triangles` triangles, references priced.
CostModel cost_model_of(const BuildSettings& settings, const Box3& root_voxel, uint64_t triangles);

// One boundary of one triangle on one axis. Sorted by position, then type (end < planar <
// start: the sweep needs the ends first), then triangle, a total order, so sorted lists
// are unique and merging equals re-sorting. The type sits above the local triangle index in
// the packed word, so the packed words compare in that order as plain integers. 8 bytes: the
// events of a million triangles fit in cache-friendly arrays.
enum EventType : uint32_t { kEventEnd = 0, kEventPlanar = 1, kEventStart = 2 };
constexpr uint32_t kMaxLocalTriangles = (1u << 30) - 1u;
struct Event {
  float position;
  uint32_t packed;  // type << 30 | local triangle index
  uint32_t triangle() const { return packed & kMaxLocalTriangles; }
  EventType type() const { return static_cast<EventType>(packed >> 30); }
};
static_assert(sizeof(Event) == 8, "events are 8 bytes");
inline Event event_of(float position, uint32_t local, EventType type) {
  return Event{position, uint32_t{type} << 30 | local};
}
inline bool operator<(const Event& a, const Event& b) {
  if (a.position != b.position) return a.position < b.position;
  return a.packed < b.packed;
}

// Allocator whose value-less construction leaves the value uninitialised, so resize() of a
// scratch array that is overwritten anyway costs no zero fill.
template <typename T>
struct UninitialisedAllocator : std::allocator<T>, DefaultInitialisingConstruct {
  template <typename U>
  struct rebind {
    using other = UninitialisedAllocator<U>;
  };
  UninitialisedAllocator() = default;
  template <typename U>
  UninitialisedAllocator(const UninitialisedAllocator<U>&) noexcept {}
  using DefaultInitialisingConstruct::construct;
};
using EventArray = std::vector<Event, UninitialisedAllocator<Event>>;

// Appends the events of a triangle with `bounds` (local index `local`) on `axis`.
template <typename EventVector>
inline void append_events(EventVector& events, const Box3& bounds, int axis, uint32_t local) {
  if (bounds.min[axis] == bounds.max[axis]) {
    events.push_back(event_of(bounds.min[axis], local, kEventPlanar));
  } else {
    events.push_back(event_of(bounds.min[axis], local, kEventStart));
    events.push_back(event_of(bounds.max[axis], local, kEventEnd));
  }
}

// std::merge of two sorted event runs for operator<, ties to the first run: the first run's
// events are copied up to each of the second's in turn. Right for any lengths, and faster than
// choosing each output event's run where the second is the short one, as a node's re-clipped
// events are against those it kept in the small nodes that take most of a build (bench/LOG.md,
// "Tree build, eighth pass").
inline void merge_events(const Event* a, const Event* a_end, const Event* b, const Event* b_end, Event* out) {
  for (; b != b_end; ++b) {
    const Event next = *b;
    // a's events not above `next` (operator<, with bitwise operators) go first.
    while (a != a_end && !((next.position < a->position) |
                           ((next.position == a->position) & (next.packed < a->packed))))
      *out++ = *a++;
    *out++ = next;
  }
  std::copy(a, a_end, out);
}

struct SplitChoice {
  double cost = 0;
  int axis = -1;  // -1: no split found yet
  float position = 0;
  bool planar_left = false;
  // The triangles the cost counted on each side (before clipping drops a straddler that only
  // touches a side at a corner of its bounds).
  uint64_t n_left = 0, n_right = 0;
};

// Surface areas of the two children of a voxel split on one axis, as fractions of the voxel's:
// half the area of a child below position p is cross + (p - lo) * girth, the two faces across
// the axis plus the four along it.
struct SplitAreas {
  SplitAreas(const Box3& voxel, int axis) {
    const int u = (axis + 1) % 3, v = (axis + 2) % 3;
    const double extent_u = static_cast<double>(voxel.max[u]) - voxel.min[u];
    const double extent_v = static_cast<double>(voxel.max[v]) - voxel.min[v];
    cross = extent_u * extent_v;
    girth = extent_u + extent_v;
    lo = voxel.min[axis];
    hi = voxel.max[axis];
    half_area = cross + (hi - lo) * girth;
    inverse_half_area = 1.0 / half_area;
  }
  // False for a voxel without area, where no split can pay.
  bool has_area() const { return half_area > 0.0; }
  // A child that is the whole voxel gives exactly 1 (the empty bonus depends on it).
  double below(float position) const { return position == hi ? 1.0 : below_inside(position); }
  double above(float position) const { return position == lo ? 1.0 : above_inside(position); }
  // The same for a position strictly inside the voxel.
  double below_inside(float position) const { return (cross + (position - lo) * girth) * inverse_half_area; }
  double above_inside(float position) const { return (cross + (hi - position) * girth) * inverse_half_area; }

  double cross, girth, lo, hi, half_area, inverse_half_area;
};

// Costs the split at `position` of `axis`, with `n_left` triangles only below or across it,
// `n_right` only above or across it and `planar` lying in it (tried on both sides), and keeps
// it in `best` when it is strictly cheaper (ties keep the earlier candidate).
inline void consider_split(const CostModel& cost, const SplitAreas& areas, int axis, float position,
                           uint64_t n_left, uint64_t n_right, uint64_t planar, SplitChoice& best) {
  const double p_left = areas.below(position);
  const double p_right = areas.above(position);
  double split_cost;
  bool planar_left;
  if (planar == 0) {
    // Both sides give the same number; comparing it with itself keeps what two calls give
    // (true unless it is NaN).
    split_cost = cost.split_cost(p_left, p_right, n_left, n_right);
    planar_left = split_cost <= split_cost;
  } else {
    const double planar_left_cost = cost.split_cost(p_left, p_right, n_left + planar, n_right);
    const double planar_right_cost = cost.split_cost(p_left, p_right, n_left, n_right + planar);
    planar_left = planar_left_cost <= planar_right_cost;
    split_cost = planar_left ? planar_left_cost : planar_right_cost;
  }
  if (best.axis < 0 || split_cost < best.cost)
    best = SplitChoice{split_cost, axis, position, planar_left, n_left + (planar_left ? planar : 0),
                       n_right + (planar_left ? 0 : planar)};
}

// Sweeps the sorted events of one axis of a voxel holding `triangles` triangles and keeps the
// cheapest split in `best` (a strictly lower cost replaces it: ties keep the earlier axis and
// position). Triangles lying in the plane are tried on both sides.
void sweep_axis(const Event* events, size_t count, int axis, const Box3& voxel, uint64_t triangles,
                const CostModel& cost, SplitChoice& best);

// The child that `split` of a node of `n` triangles gives all of them to, whole (0 below, 1
// above), or -1 when both get some. That child's triangles, bounds and events are then the
// node's, in the same order, and the other child is an empty leaf: many splits of a tree's
// lower levels cut off empty space like this, and their nodes need not be divided.
inline int side_taking_all(const SplitChoice& split, uint64_t n) {
  if (split.n_left == n && split.n_right == 0) return 0;
  if (split.n_right == n && split.n_left == 0) return 1;
  return -1;
}

// A builder's node (its voxel and depth; its arrays stay) made its child on `side` (0 below, 1
// above) of `split`, the side taking all its triangles (side_taking_all).
template <typename Node>
void become_child(Node& node, const SplitChoice& split, int side) {
  node.voxel = side == 0 ? below_plane(node.voxel, split.axis, split.position)
                         : above_plane(node.voxel, split.axis, split.position);
  ++node.depth;
}

enum Side : uint8_t { kBothSides = 0, kLeftOnly = 1, kRightOnly = 2, kNeitherSide = 3 };

// Sides of each local triangle for `split`, from the events of the split axis (Wald & Havran):
// a triangle ending on or below the plane goes left, one starting on or above it right, one in
// the plane to the chosen side; all others straddle and go to both. `sides` must hold
// kBothSides for every triangle: each event adds its side's bit to it, at most one per triangle.
void classify(const Event* events, size_t count, const SplitChoice& split, uint8_t* sides);

// How a divided node renumbers the kept events of a triangle that only one child gets: an
// event whose packed word is how much lower the triangle's local index is in that child, and
// whose position bits are zero.
inline Event event_renumbering(size_t local, size_t child_local) {
  return Event{0.0f, static_cast<uint32_t>(local - child_local)};
}

// Sends each event whose triangle reaches one child only (`sides`) to that child, renumbered
// (`renumberings`), in order: `left` and `right` advance past what they get. Each event is
// renumbered as one 8-byte integer: the renumbering's position bits are zero and the local
// index does not go below zero, so no borrow crosses between the two halves, whichever half
// the position is in. It does not branch on the side (the sides of neighbouring events are
// unpredictable): every event is written to both outputs, and each advances only over its own.
inline void split_kept_events(const Event* events, size_t count, const uint8_t* sides, const Event* renumberings,
                              Event*& left, Event*& right) {
  Event* l = left;
  Event* r = right;
  for (size_t e = 0; e < count; ++e) {
    const uint32_t local = events[e].triangle();
    uint64_t event_bits, renumbering_bits;
    std::memcpy(&event_bits, &events[e], sizeof event_bits);
    std::memcpy(&renumbering_bits, &renumberings[local], sizeof renumbering_bits);
    const uint64_t moved = event_bits - renumbering_bits;
    std::memcpy(l, &moved, sizeof moved);
    std::memcpy(r, &moved, sizeof moved);
    const uint32_t side = sides[local];
    l += side & kLeftOnly;
    r += side >> 1;
  }
  left = l;
  right = r;
}

// A tree or subtree under construction: nodes in depth-first order, near (below) child next,
// and the leaf-triangle array. Indices are relative to this subtree. A leaf of no triangles adds
// no node: its parent's header says that child is empty (kernels/kd_types.h), and a subtree
// that holds no triangle at all (no nodes) is such an empty child.
struct Subtree {
  TraversalArray<KdNode> nodes;
  TraversalArray<uint32_t> leaf_triangles;

  void add_leaf(const uint32_t* triangles, size_t count);
  // Adds an inner node with one empty child; the other, on `side` (0 below, 1 above), is the
  // subtree added after it (which may begin with more such nodes). Returns the node's index, for
  // finish_one_sided once that subtree is added; nodes added so are finished latest first.
  // The same nodes as add_inner's with one build function empty.
  size_t add_one_sided(int axis, float position) { return add_inner_node(axis, position); }
  void finish_one_sided(size_t inner, int side) { finish_inner_node(inner, side == 0 ? nodes.size() : inner + 1); }
  // Adds an inner node, then the near child's subtree (build_near() appends it) and the far
  // child's (build_far()), recording where the far one starts and which of them are empty.
  template <typename BuildNear, typename BuildFar>
  void add_inner(int axis, float position, const BuildNear& build_near, const BuildFar& build_far) {
    const size_t inner = add_inner_node(axis, position);
    build_near();
    const size_t far_child = nodes.size();
    build_far();
    finish_inner_node(inner, far_child);
  }
 private:
  // Adds an inner node whose children are not known yet; returns its index.
  size_t add_inner_node(int axis, float position);
  // Sets the far child and the empty-child bits of the inner node at `inner`, whose far
  // subtree starts at `far_child`; a node with both children empty is removed again.
  void finish_inner_node(size_t inner, size_t far_child);
};

// Room for the two children, at `depth`, of a node that a depth-first build splits: per thread
// and per depth, its arrays keep their capacity from node to node, so that building allocates
// nothing once it is warm. A depth's room is made when a build first reaches it, so a thread
// holds room only for the depths it builds at (the small-node path's fixed arrays are 40 KB a
// depth, and it runs only deep in the tree).
template <typename Node>
std::array<Node, 2>& children_at_depth(uint32_t depth) {
  thread_local std::vector<std::unique_ptr<std::array<Node, 2>>> children(BuildSettings::kMaxDepthLimit + 2);
  std::unique_ptr<std::array<Node, 2>>& room = children[depth];
  if (!room) room = std::make_unique<std::array<Node, 2>>();
  return *room;
}

// Nodes of at most this many triangles are built by build_small_subtree, whose fixed arrays
// cost less per node than the general path's vectors: 128 measured shorter than 32 or 64
// (bench/LOG.md, "Tree build, fifth pass"), and 256 shorter than 128 once the sweep found its
// runs without branches ("Tree build, sixth pass").
constexpr size_t kSmallNodeTriangles = 256;

// The sweep's two passes over the events of one axis of a small node (build_small.cpp), kept
// apart: find() finds the runs of equal positions and the counts through each, and cost()
// costs them for a voxel as sweep_axis does. A node that becomes its own child (become_child)
// keeps its events, so the runs found once are costed again for each voxel it shrinks to.
class AxisRuns {
 public:
  // At most this many events: two per triangle of a small node.
  static constexpr size_t kMaxEvents = 2 * kSmallNodeTriangles;

  // Finds the runs of `count` (at most kMaxEvents) sorted events, which must outlive this.
  void find(const Event* events, size_t count);
  // What sweep_axis(events, count, axis, voxel, triangles, cost, best) does.
  void cost(int axis, const Box3& voxel, uint64_t triangles, const CostModel& cost, SplitChoice& best) const;

 private:
  const Event* events_ = nullptr;
  size_t count_ = 0;
  size_t runs_ = 0;  // slots in use, slot 0 included
  uint64_t run_counts_[kMaxEvents + 1];
  uint32_t run_last_[kMaxEvents + 1];
};

struct SmallBuildParameters {
  CostModel cost;
  uint32_t max_depth;
  bool perfect_splits;
};

// Builds the subtree of a node of at most kSmallNodeTriangles triangles (`triangles`, with
// the sorted events of each axis) into `out`, in fixed-size per-thread storage. It builds the
// tree the general event builder would build from the same node.
void build_small_subtree(const Scene& scene, const SmallBuildParameters& parameters, const Box3& voxel,
                         uint32_t depth, const uint32_t* triangles, size_t count, const Event* const events[3],
                         const size_t event_counts[3], Subtree& out);

// Throws kdray::Error for settings out of range.
void validate_settings(const BuildSettings& settings);

// The root of both builders: the triangles with finite vertices (in index order), their
// bounding boxes and the root voxel around them (all zeros without triangles).
struct RootWork {
  Box3 voxel;
  std::vector<uint32_t> triangles;
  std::vector<Box3> bounds;
};
RootWork prepare_root(const Scene& scene);

// The tree of the finished `nodes` with its bounds, settings, scene hash and statistics; its
// leaf blocks are left empty.
KdTree describe_tree(const Scene& scene, const BuildSettings& settings, const Box3& voxel,
                     TraversalArray<KdNode>&& nodes);

// Wraps a finished subtree into a KdTree: describe_tree, with the leaf blocks made
// (leaf_blocks_of).
KdTree finish_tree(const Scene& scene, const BuildSettings& settings, const Box3& voxel, Subtree&& built);

}  // namespace kdray::detail
