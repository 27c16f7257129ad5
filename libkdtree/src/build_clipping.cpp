// Triangles clipped to voxels for the builders: the bounds of a triangle's part inside a voxel
// (build_common.h declares them).
#include "build_common.h"

#include <algorithm>
#include <cmath>
#include <cstring>
#include <limits>

namespace kdray::detail {
namespace {

// Largest polygon Sutherland-Hodgman can produce from a triangle and six planes: 3 + 6.
constexpr int kMaxClipVertices = 9;

struct Polygon {
  double points[kMaxClipVertices + 1][3];
  int size = 0;
};

// Keeps the part of `in` with coordinate `axis` >= bound (kKeepAbove) or <= bound.
// Returns false (and leaves `out` alone) when all of `in` is kept: clipping would copy it
// unchanged, point for point. The side is a template parameter and each point's test is made
// once: this runs for every straddling triangle of every node.
template <bool kKeepAbove>
bool clip_polygon(const Polygon& in, int axis, double bound, Polygon& out) {
  auto inside = [axis, bound](const double* point) { return kKeepAbove ? point[axis] >= bound : point[axis] <= bound; };
  bool all_inside = true;
  for (int i = 0; i < in.size; ++i) all_inside &= inside(in.points[i]);
  if (all_inside) return false;
  out.size = 0;
  bool p_inside = inside(in.points[0]);
  for (int i = 0; i < in.size; ++i) {
    const double* p = in.points[i];
    const double* q = in.points[i + 1 == in.size ? 0 : i + 1];
    const bool q_inside = inside(q);
    if (p_inside) {
      std::copy(p, p + 3, out.points[out.size]);
      ++out.size;
    }
    if (p_inside != q_inside) {
      const double t = (bound - p[axis]) / (q[axis] - p[axis]);
      double* x = out.points[out.size];
      for (int k = 0; k < 3; ++k) x[k] = p[k] + t * (q[k] - p[k]);
      x[axis] = bound;  // exactly on the plane, whatever the rounding of t
      ++out.size;
    }
    p_inside = q_inside;
  }
  return true;
}

// std::nextafter(value, INFINITY) (`up`) or (value, -INFINITY) for a value that is not NaN
// (nor -INFINITY going down, nor INFINITY going up): the neighbouring bit pattern, without a
// call into libm for every rounded bound.
float next_float(float value, bool up) {
  if (value == 0.0f) return up ? std::numeric_limits<float>::denorm_min() : -std::numeric_limits<float>::denorm_min();
  uint32_t bits;
  std::memcpy(&bits, &value, sizeof bits);
  // Away from zero is one pattern up for a positive value and for a negative one alike.
  bits = (value > 0.0f) == up ? bits + 1 : bits - 1;
  std::memcpy(&value, &bits, sizeof bits);
  return value;
}

float round_down(double value) {
  float rounded = static_cast<float>(value);
  return static_cast<double>(rounded) > value ? next_float(rounded, false) : rounded;
}
float round_up(double value) {
  float rounded = static_cast<float>(value);
  return static_cast<double>(rounded) < value ? next_float(rounded, true) : rounded;
}

bool intersect_boxes(const Box3& a, const Box3& b, Box3& out) {
  for (int k = 0; k < 3; ++k) {
    out.min[k] = std::max(a.min[k], b.min[k]);
    out.max[k] = std::min(a.max[k], b.max[k]);
    if (out.min[k] > out.max[k]) return false;
  }
  return true;
}

const Vec3& vertex(const Scene& scene, uint32_t triangle, int corner) {
  return scene.positions[scene.indices[3 * static_cast<size_t>(triangle) + corner]];
}


struct Corners {
  const float* point[3];
};

Corners corners_of(const Scene& scene, uint32_t triangle) {
  return Corners{{&vertex(scene, triangle, 0).x, &vertex(scene, triangle, 1).x, &vertex(scene, triangle, 2).x}};
}

Box3 bounding_box(const Corners& corners) {
  Box3 box;
  for (int k = 0; k < 3; ++k) {
    box.min[k] = INFINITY;
    box.max[k] = -INFINITY;
  }
  for (const float* p : corners.point)
    for (int k = 0; k < 3; ++k) {
      box.min[k] = std::min(box.min[k], p[k]);
      box.max[k] = std::max(box.max[k], p[k]);
    }
  return box;
}

bool contains(const Box3& voxel, const Box3& box) {
  bool inside = true;
  for (int k = 0; k < 3; ++k) inside = inside && box.min[k] >= voxel.min[k] && box.max[k] <= voxel.max[k];
  return inside;
}

// True when `inner` is above `outer` by more than clipping can move a coordinate: each plane
// clipped rounds a new point's other coordinates by a few units in the last place of the
// largest of them, and a triangle meets at most six planes; 2^-40 of the magnitude (plus a
// little for subnormal magnitudes) is far more than that.
bool clearly_above(float inner, float outer) {
  const double magnitude = std::max(std::fabs(inner), std::fabs(outer));
  return static_cast<double>(inner) - outer >= magnitude * 0x1p-40 + 0x1p-1000;
}

// The bounds of the points a clip leaves, in the order it leaves them: std::min and std::max
// keep the first of equal values (-0 and +0), so the order is part of the result.
class PointBounds {
 public:
  void add(const double* point) {
    for (int k = 0; k < 3; ++k) {
      lo_[k] = empty_ ? point[k] : std::min(lo_[k], point[k]);
      hi_[k] = empty_ ? point[k] : std::max(hi_[k], point[k]);
    }
    empty_ = false;
  }
  bool empty() const { return empty_; }
  // The bounds rounded outwards to float, within `voxel`.
  bool in(const Box3& voxel, Box3& out) const {
    Box3 clipped_box;
    for (int k = 0; k < 3; ++k) {
      clipped_box.min[k] = round_down(lo_[k]);
      clipped_box.max[k] = round_up(hi_[k]);
    }
    return intersect_boxes(clipped_box, voxel, out);
  }

 private:
  double lo_[3], hi_[3];
  bool empty_ = true;
};

// A triangle clipped to a voxel's planes axis by axis, x to z, min before max (Sutherland-
// Hodgman in double). Planes that keep the whole polygon are skipped: those that keep the
// triangle's bounding box with room to spare without looking at the points (the polygon lies
// within the box, up to the rounding of the clipping), the others when a look at the points
// finds all of them inside. The current polygon alternates between the two buffers.
class ClippedPolygon {
 public:
  ClippedPolygon(const Corners& corners, const Box3& triangle_box) : triangle_box_(triangle_box) {
    buffers_[0].size = 3;
    for (int corner = 0; corner < 3; ++corner)
      for (int k = 0; k < 3; ++k) buffers_[0].points[corner][k] = corners.point[corner][k];
  }
  ClippedPolygon(const ClippedPolygon&) = delete;
  ClippedPolygon& operator=(const ClippedPolygon&) = delete;

  // Clips by the two planes of `axis` of `voxel`; false when nothing is left.
  bool clip_axis(const Box3& voxel, int axis) {
    clip_min(voxel, axis);
    clip_max(voxel, axis);
    return !empty();
  }
  // Clips by the lower plane of `axis` of `voxel` (keeping what is above it), or the upper.
  void clip_min(const Box3& voxel, int axis) {
    if (!clearly_above(triangle_box_.min[axis], voxel.min[axis]) &&
        clip_polygon<true>(buffers_[current_], axis, voxel.min[axis], buffers_[1 - current_]))
      current_ = 1 - current_;
  }
  void clip_max(const Box3& voxel, int axis) {
    if (!clearly_above(voxel.max[axis], triangle_box_.max[axis]) &&
        clip_polygon<false>(buffers_[current_], axis, voxel.max[axis], buffers_[1 - current_]))
      current_ = 1 - current_;
  }
  bool empty() const { return buffers_[current_].size == 0; }

  // The bounds of the polygon's parts below and above `bound` on `axis`: of the points that
  // clip_polygon<false> (below) and clip_polygon<true> (above) of it leave, in the order they
  // leave them (all of them where a side keeps the whole polygon), without writing either
  // polygon; a point where an edge crosses the plane is computed once for both sides.
  void bounds_of_halves(int axis, double bound, PointBounds (&halves)[2]) const {
    const Polygon& polygon = buffers_[current_];
    for (int i = 0; i < polygon.size; ++i) {
      const double* p = polygon.points[i];
      const double* q = polygon.points[i + 1 == polygon.size ? 0 : i + 1];
      const bool p_below = p[axis] <= bound, q_below = q[axis] <= bound;
      const bool p_above = p[axis] >= bound, q_above = q[axis] >= bound;
      if (p_below) halves[0].add(p);
      if (p_above) halves[1].add(p);
      const bool crosses_below = p_below != q_below, crosses_above = p_above != q_above;
      if (crosses_below || crosses_above) {
        const double t = (bound - p[axis]) / (q[axis] - p[axis]);
        double x[3];
        for (int k = 0; k < 3; ++k) x[k] = p[k] + t * (q[k] - p[k]);
        x[axis] = bound;
        if (crosses_below) halves[0].add(x);
        if (crosses_above) halves[1].add(x);
      }
    }
  }

  // The polygon's bounds rounded outwards to float, within `voxel`.
  bool bounds_in(const Box3& voxel, Box3& out) const {
    const Polygon& polygon = buffers_[current_];
    PointBounds bounds;
    for (int i = 0; i < polygon.size; ++i) bounds.add(polygon.points[i]);
    return bounds.in(voxel, out);
  }

 private:
  Box3 triangle_box_;
  Polygon buffers_[2];
  int current_ = 0;
};

}  // namespace

bool triangle_bounds_in_voxel(const Scene& scene, uint32_t triangle, const Box3& voxel, bool perfect_splits,
                              Box3& out) {
  const Corners corners = corners_of(scene, triangle);
  const Box3 box = bounding_box(corners);
  if (!perfect_splits || contains(voxel, box)) return intersect_boxes(box, voxel, out);
  ClippedPolygon polygon(corners, box);
  for (int k = 0; k < 3; ++k)
    if (!polygon.clip_axis(voxel, k)) return false;
  return polygon.bounds_in(voxel, out);
}

StraddlerBounds straddler_bounds(const Scene& scene, uint32_t triangle, const Box3& parent_bounds,
                                 const Box3 (&child_voxels)[2], int axis, bool perfect_splits) {
  StraddlerBounds result{};
  if (!perfect_splits) {
    for (int c = 0; c < 2; ++c) result.reaches[c] = intersect_boxes(parent_bounds, child_voxels[c], result.bounds[c]);
    return result;
  }
  const Corners corners = corners_of(scene, triangle);
  const Box3 box = bounding_box(corners);
  bool clipped[2];
  for (int c = 0; c < 2; ++c) {
    clipped[c] = !contains(child_voxels[c], box);
    if (!clipped[c]) result.reaches[c] = intersect_boxes(box, child_voxels[c], result.bounds[c]);
  }
  if (!clipped[0] && !clipped[1]) return result;
  // Every plane but the split is a plane of the parent voxel, the same for both children: the
  // triangle is clipped by those once, and the polygon they leave by the split plane for each.
  ClippedPolygon shared(corners, box);
  for (int k = 0; k < 3; ++k) {
    if (k == axis) {
      shared.clip_min(child_voxels[0], k);
      shared.clip_max(child_voxels[1], k);
    } else {
      shared.clip_axis(child_voxels[0], k);
    }
    if (shared.empty()) return result;  // reaches stays false where clipped
  }
  PointBounds halves[2];
  shared.bounds_of_halves(axis, child_voxels[0].max[axis], halves);
  for (int c = 0; c < 2; ++c)
    if (clipped[c]) result.reaches[c] = !halves[c].empty() && halves[c].in(child_voxels[c], result.bounds[c]);
  return result;
}

}  // namespace kdray::detail
