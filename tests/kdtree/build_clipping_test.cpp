// A straddling triangle's bounds in the two children of a split (straddler_bounds), which clips it
// by the parent voxel's planes once and then by the split plane for each child: they hold every
// point of the triangle inside the child, and they are what clipping the triangle to each child
// voxel from scratch (triangle_bounds_in_voxel) gives, up to one float step where the two orders
// of the same planes round differently.
#include "build_common.h"
#include "test_scenes.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <random>
#include <vector>

namespace kdray {
namespace {

using namespace kdray::detail;

struct Case {
  Scene scene;
  std::vector<Box3> voxels;
  std::vector<int> axes;
  std::vector<float> positions;
};

// Triangles from slivers to fat ones at random places in [-1, 1]^3, each with a parent voxel
// around part of it and a split plane through its bounds in that voxel.
Case straddling_cases(size_t count, uint32_t seed) {
  std::mt19937 random(seed);
  std::uniform_real_distribution<float> unit(-1.0f, 1.0f), fraction(0.05f, 0.95f);
  std::vector<float> corners;
  Case result;
  for (size_t i = 0; i < count; ++i) {
    float a[3], b[3], c[3];
    const float width = i % 3 == 0 ? 0.01f : 1.0f;  // every third a sliver
    for (int k = 0; k < 3; ++k) {
      a[k] = unit(random);
      b[k] = unit(random);
      c[k] = a[k] + width * (unit(random) - a[k]);
    }
    corners.insert(corners.end(), {a[0], a[1], a[2], b[0], b[1], b[2], c[0], c[1], c[2]});
    Box3 voxel;
    for (int k = 0; k < 3; ++k) {
      const float lo = std::min({a[k], b[k], c[k]}), hi = std::max({a[k], b[k], c[k]});
      voxel.min[k] = lo + (hi - lo) * (fraction(random) - 0.3f);
      voxel.max[k] = voxel.min[k] + (hi - lo) * fraction(random);
    }
    result.voxels.push_back(voxel);
    result.axes.push_back(static_cast<int>(i % 3));
    result.positions.push_back(0.0f);
  }
  result.scene = test::from_triangles(corners);
  for (size_t i = 0; i < count; ++i) {
    Box3 in_voxel;
    if (!triangle_bounds_in_voxel(result.scene, static_cast<uint32_t>(i), result.voxels[i], true, in_voxel)) continue;
    const int axis = result.axes[i];
    result.positions[i] = in_voxel.min[axis] + (in_voxel.max[axis] - in_voxel.min[axis]) * fraction(random);
  }
  return result;
}

// Case t's split: its child voxels and the straddler's bounds in them; false when the triangle
// does not straddle the split inside its voxel.
struct Split {
  Box3 children[2];
  StraddlerBounds straddler;
};
bool split_of(const Case& cases, uint32_t t, Split& split) {
  Box3 parent_bounds;
  if (!triangle_bounds_in_voxel(cases.scene, t, cases.voxels[t], true, parent_bounds)) return false;
  const int axis = cases.axes[t];
  const float position = cases.positions[t];
  if (!(parent_bounds.min[axis] < position && position < parent_bounds.max[axis])) return false;
  split.children[0] = below_plane(cases.voxels[t], axis, position);
  split.children[1] = above_plane(cases.voxels[t], axis, position);
  split.straddler = straddler_bounds(cases.scene, t, parent_bounds, split.children, axis, true);
  return true;
}

bool within_one_step(float a, float b) {
  return std::nextafter(a, -INFINITY) <= b && b <= std::nextafter(a, INFINITY);
}

TEST(KdBuildClipping, StraddlersBoundsAreEachChildsClippedTriangle) {
  const Case cases = straddling_cases(3000, 7);
  size_t straddlers = 0, clipped_sides = 0;
  for (uint32_t t = 0; t < cases.voxels.size(); ++t) {
    Split split;
    if (!split_of(cases, t, split)) continue;
    ++straddlers;
    const StraddlerBounds& straddler = split.straddler;
    for (int c = 0; c < 2; ++c) {
      Box3 from_scratch;
      const bool reaches = triangle_bounds_in_voxel(cases.scene, t, split.children[c], true, from_scratch);
      ASSERT_EQ(straddler.reaches[c], reaches) << "triangle " << t << " child " << c;
      if (!reaches) continue;
      ++clipped_sides;
      for (int k = 0; k < 3; ++k) {
        EXPECT_TRUE(within_one_step(straddler.bounds[c].min[k], from_scratch.min[k])) << "triangle " << t;
        EXPECT_TRUE(within_one_step(straddler.bounds[c].max[k], from_scratch.max[k])) << "triangle " << t;
      }
    }
  }
  EXPECT_GT(straddlers, 1500u) << "most cases should straddle";
  EXPECT_GT(clipped_sides, 2 * straddlers - 100);
}

// A triangle inside its parent voxel meets only the split plane, in the children as from
// scratch: the same points, so the same bounds bit for bit. The split plane runs through the
// middle corner in every fourth case (a corner on the plane belongs to both sides).
TEST(KdBuildClipping, StraddlersInsideTheParentVoxelAreEachChildsClippedTriangleExactly) {
  std::mt19937 random(5);
  std::uniform_real_distribution<float> unit(-1.0f, 1.0f), fraction(0.0f, 1.0f);
  std::vector<float> corners;
  std::vector<Box3> voxels;
  std::vector<float> positions;
  const size_t count = 4000;
  for (size_t i = 0; i < count; ++i) {
    float p[3][3];
    for (auto& corner : p)
      for (float& x : corner) x = i % 5 == 0 ? std::round(unit(random) * 4) / 4 : unit(random);  // some on a grid
    Box3 voxel;
    for (int k = 0; k < 3; ++k) {
      const float lo = std::min({p[0][k], p[1][k], p[2][k]}), hi = std::max({p[0][k], p[1][k], p[2][k]});
      const bool tight = i % 3 == 0;  // the voxel is the triangle's box
      voxel.min[k] = tight ? lo : lo - fraction(random);
      voxel.max[k] = tight ? hi : hi + fraction(random);
    }
    const int axis = static_cast<int>(i % 3);
    float sorted[3] = {p[0][axis], p[1][axis], p[2][axis]};
    std::sort(sorted, sorted + 3);
    positions.push_back(i % 4 == 0 ? sorted[1] : sorted[0] + (sorted[2] - sorted[0]) * fraction(random));
    voxels.push_back(voxel);
    for (auto& corner : p) corners.insert(corners.end(), corner, corner + 3);
  }
  const Scene scene = test::from_triangles(corners);
  size_t straddlers = 0, on_plane = 0;
  for (uint32_t t = 0; t < count; ++t) {
    const int axis = static_cast<int>(t % 3);
    Box3 parent_bounds;
    ASSERT_TRUE(triangle_bounds_in_voxel(scene, t, voxels[t], true, parent_bounds));
    if (!(parent_bounds.min[axis] < positions[t] && positions[t] < parent_bounds.max[axis])) continue;
    ++straddlers;
    on_plane += t % 4 == 0;
    const Box3 children[2] = {below_plane(voxels[t], axis, positions[t]), above_plane(voxels[t], axis, positions[t])};
    const StraddlerBounds straddler = straddler_bounds(scene, t, parent_bounds, children, axis, true);
    for (int c = 0; c < 2; ++c) {
      Box3 from_scratch;
      const bool reaches = triangle_bounds_in_voxel(scene, t, children[c], true, from_scratch);
      ASSERT_EQ(straddler.reaches[c], reaches) << "triangle " << t << " child " << c;
      for (int k = 0; k < 3; ++k) {
        EXPECT_EQ(std::memcmp(&straddler.bounds[c].min[k], &from_scratch.min[k], sizeof(float)), 0) << "triangle " << t;
        EXPECT_EQ(std::memcmp(&straddler.bounds[c].max[k], &from_scratch.max[k], sizeof(float)), 0) << "triangle " << t;
      }
    }
  }
  EXPECT_GT(straddlers, 3000u);
  EXPECT_GT(on_plane, 500u);
}

TEST(KdBuildClipping, StraddlersBoundsHoldTheTriangleInsideEachChild) {
  const Case cases = straddling_cases(1000, 11);
  constexpr int kSteps = 40;
  for (uint32_t t = 0; t < cases.voxels.size(); ++t) {
    Split split;
    if (!split_of(cases, t, split)) continue;
    const Box3* children = split.children;
    const StraddlerBounds& straddler = split.straddler;
    const Vec3* p[3];
    for (int corner = 0; corner < 3; ++corner) p[corner] = &cases.scene.positions[cases.scene.indices[3 * t + corner]];
    // Points of the triangle on a barycentric grid, in double: each one inside a child voxel
    // must lie in that child's bounds.
    for (int i = 0; i <= kSteps; ++i)
      for (int j = 0; i + j <= kSteps; ++j) {
        const double u = double(i) / kSteps, v = double(j) / kSteps, w = 1.0 - u - v;
        const double point[3] = {w * p[0]->x + u * p[1]->x + v * p[2]->x, w * p[0]->y + u * p[1]->y + v * p[2]->y,
                                 w * p[0]->z + u * p[1]->z + v * p[2]->z};
        for (int c = 0; c < 2; ++c) {
          bool inside = true;
          for (int k = 0; k < 3; ++k) inside = inside && point[k] >= children[c].min[k] && point[k] <= children[c].max[k];
          if (!inside) continue;
          ASSERT_TRUE(straddler.reaches[c]) << "triangle " << t << " child " << c;
          for (int k = 0; k < 3; ++k) {
            EXPECT_GE(point[k], straddler.bounds[c].min[k]) << "triangle " << t << " child " << c << " axis " << k;
            EXPECT_LE(point[k], straddler.bounds[c].max[k]) << "triangle " << t << " child " << c << " axis " << k;
          }
        }
      }
  }
}

}  // namespace
}  // namespace kdray
