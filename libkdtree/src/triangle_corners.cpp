// Triangles' corners copied from the scene's positions: the leaf triangles a tree's leaves are
// ranges of (KdLeafTriangle, kernels/kd_types.h), whole or a byte range at a time, and the
// shading copy in triangle order.
#include "triangle_corners.h"

#include <kdray/kdtree.h>
#include <kdray/traverse.h>

#include <kernels/kd_scene_view.h>

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include <algorithm>
#include <cstring>

namespace kdray {
namespace {

// The corners a, b, c of `triangle`, x, y, z each, into corners[0..8].
void copy_corners(const Scene& scene, size_t triangle, float* corners) {
  for (size_t corner = 0; corner < 3; ++corner) {
    const Vec3& p = scene.positions[scene.indices[3 * triangle + corner]];
    corners[3 * corner + 0] = p.x;
    corners[3 * corner + 1] = p.y;
    corners[3 * corner + 2] = p.z;
  }
}

// Runs fill(i) for i in [0, count), in parallel.
template <typename Fill>
void fill_in_parallel(size_t count, const Fill& fill) {
  tbb::parallel_for(tbb::blocked_range<size_t>(0, count, 16384), [&](const tbb::blocked_range<size_t>& range) {
    for (size_t i = range.begin(); i < range.end(); ++i) fill(i);
  });
}

KdLeafTriangle leaf_triangle(const Scene& scene, uint32_t triangle) {
  KdLeafTriangle entry;
  copy_corners(scene, triangle, entry.corners);
  entry.triangle = triangle;
  return entry;
}

}  // namespace

namespace detail {

void leaf_triangle_bytes(const Scene& scene, const uint32_t* triangles, uint64_t begin, uint64_t end, char* out) {
  constexpr uint64_t kRecord = sizeof(KdLeafTriangle);
  // The records wholly inside [begin, end), then the parts of the one or two it cuts.
  const uint64_t first_whole = (begin + kRecord - 1) / kRecord, end_whole = end / kRecord;
  auto part_of = [&](uint64_t record) {
    const KdLeafTriangle entry = leaf_triangle(scene, triangles[record]);
    const uint64_t from = std::max(begin, record * kRecord), to = std::min(end, (record + 1) * kRecord);
    std::memcpy(out + (from - begin), reinterpret_cast<const char*>(&entry) + (from - record * kRecord), to - from);
  };
  if (begin >= end) return;
  if (first_whole >= end_whole) {  // no whole record: one or two parts
    part_of(begin / kRecord);
    if ((end - 1) / kRecord != begin / kRecord) part_of((end - 1) / kRecord);
    return;
  }
  if (begin % kRecord != 0) part_of(begin / kRecord);
  char* whole = out + (first_whole * kRecord - begin);
  fill_in_parallel(end_whole - first_whole, [&](size_t i) {
    const KdLeafTriangle entry = leaf_triangle(scene, triangles[first_whole + i]);
    std::memcpy(whole + i * kRecord, &entry, kRecord);
  });
  if (end % kRecord != 0) part_of(end_whole);
}

}  // namespace detail

TraversalArray<KdLeafTriangle> leaf_triangles_of(const Scene& scene, const uint32_t* triangles, size_t count) {
  TraversalArray<KdLeafTriangle> entries(count);
  detail::leaf_triangle_bytes(scene, triangles, 0, count * sizeof(KdLeafTriangle),
                              reinterpret_cast<char*>(entries.data()));
  return entries;
}

TraversalArray<float> gather_triangle_vertices(const Scene& scene) {
  TraversalArray<float> vertices(scene.triangle_count() * KD_TRIANGLE_FLOATS);
  fill_in_parallel(scene.triangle_count(),
                   [&](size_t triangle) { copy_corners(scene, triangle, vertices.data() + triangle * KD_TRIANGLE_FLOATS); });
  return vertices;
}

}  // namespace kdray
