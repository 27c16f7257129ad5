#include "polygon.h"

#include <cmath>

namespace kdray {
namespace {

struct Point2 {
  double x, y;
};

double cross(const Point2& a, const Point2& b, const Point2& c) {
  return (b.x - a.x) * (c.y - a.y) - (b.y - a.y) * (c.x - a.x);
}

bool inside_or_on(const Point2& p, const Point2& a, const Point2& b, const Point2& c) {
  return cross(a, b, p) >= 0 && cross(b, c, p) >= 0 && cross(c, a, p) >= 0;
}

bool same_point(const Point2& a, const Point2& b) { return a.x == b.x && a.y == b.y; }

// Projects onto the coordinate plane most parallel to the polygon, oriented so the polygon
// winds counter-clockwise. Coordinates are taken relative to the first corner, which keeps
// precision for polygons far from the origin.
std::vector<Point2> project(const std::vector<Vec3>& polygon) {
  double nx = 0, ny = 0, nz = 0;  // Newell's normal
  for (size_t i = 0; i < polygon.size(); ++i) {
    const Vec3& a = polygon[i];
    const Vec3& b = polygon[(i + 1) % polygon.size()];
    nx += (double(a.y) - b.y) * (double(a.z) + b.z);
    ny += (double(a.z) - b.z) * (double(a.x) + b.x);
    nz += (double(a.x) - b.x) * (double(a.y) + b.y);
  }
  const double ax = std::fabs(nx), ay = std::fabs(ny), az = std::fabs(nz);
  int u = 0, v = 1;
  double dominant = nz;
  if (ax >= ay && ax >= az) u = 1, v = 2, dominant = nx;
  else if (ay >= az) u = 2, v = 0, dominant = ny;
  if (dominant < 0) std::swap(u, v);
  const Vec3& origin = polygon[0];
  auto coordinate = [](const Vec3& p, int axis) { return axis == 0 ? double(p.x) : axis == 1 ? double(p.y) : double(p.z); };
  std::vector<Point2> points(polygon.size());
  for (size_t i = 0; i < polygon.size(); ++i)
    points[i] = {coordinate(polygon[i], u) - coordinate(origin, u), coordinate(polygon[i], v) - coordinate(origin, v)};
  return points;
}

// Ear clipping costs O(n^3) at worst; polygons beyond this size are fanned to bound the time.
constexpr size_t kMaxEarClippingCorners = 4096;

}  // namespace

std::vector<std::array<uint32_t, 3>> triangulate_polygon(const std::vector<Vec3>& polygon) {
  std::vector<std::array<uint32_t, 3>> triangles;
  if (polygon.size() < 3) return triangles;
  triangles.reserve(polygon.size() - 2);
  std::vector<uint32_t> remaining(polygon.size());
  for (uint32_t i = 0; i < remaining.size(); ++i) remaining[i] = i;
  if (polygon.size() == 3 || polygon.size() > kMaxEarClippingCorners) {
    for (uint32_t i = 1; i + 1 < polygon.size(); ++i) triangles.push_back({0, i, i + 1});
    return triangles;
  }
  const std::vector<Point2> points = project(polygon);

  auto is_ear = [&](size_t at) {
    const size_t n = remaining.size();
    const uint32_t a = remaining[(at + n - 1) % n], b = remaining[at], c = remaining[(at + 1) % n];
    if (!(cross(points[a], points[b], points[c]) > 0)) return false;  // reflex, flat or NaN
    for (uint32_t other : remaining) {
      if (other == a || other == b || other == c) continue;
      const Point2& p = points[other];
      // A corner repeated at the same place (a polygon touching itself) does not block the ear.
      if (same_point(p, points[a]) || same_point(p, points[b]) || same_point(p, points[c])) continue;
      if (inside_or_on(p, points[a], points[b], points[c])) return false;
    }
    return true;
  };

  // Starting at corner 1 and moving forward, a convex polygon comes out as the fan around
  // corner 0 - the triangles other OBJ readers produce - and concave ones stay correct.
  size_t at = 1;
  size_t failed_in_a_row = 0;
  while (remaining.size() > 3) {
    const size_t n = remaining.size();
    at %= n;
    // After a full round without an ear (self-intersecting or degenerate input), clip anyway
    // so the polygon always yields n - 2 triangles.
    if (is_ear(at) || failed_in_a_row >= n) {
      triangles.push_back({remaining[(at + n - 1) % n], remaining[at], remaining[(at + 1) % n]});
      remaining.erase(remaining.begin() + at);  // `at` now names the next corner
      failed_in_a_row = 0;
    } else {
      ++at;
      ++failed_in_a_row;
    }
  }
  triangles.push_back({remaining[0], remaining[1], remaining[2]});
  return triangles;
}

}  // namespace kdray
