#include <double_hit.h>

#include <algorithm>
#include <cmath>

namespace kdray::test {
namespace {

struct D3 {
  double x, y, z;
};
D3 to_double(const Vec3& v) { return {v.x, v.y, v.z}; }
D3 sub(D3 a, D3 b) { return {a.x - b.x, a.y - b.y, a.z - b.z}; }
D3 cross(D3 a, D3 b) { return {a.y * b.z - a.z * b.y, a.z * b.x - a.x * b.z, a.x * b.y - a.y * b.x}; }
double dot(D3 a, D3 b) { return a.x * b.x + a.y * b.y + a.z * b.z; }
double length(D3 a) { return std::sqrt(dot(a, a)); }

}  // namespace

DoubleHit intersect_double(const Scene& scene, uint32_t triangle, const RayRecord& ray) {
  const D3 a = to_double(scene.positions[scene.indices[3 * triangle + 0]]);
  const D3 b = to_double(scene.positions[scene.indices[3 * triangle + 1]]);
  const D3 c = to_double(scene.positions[scene.indices[3 * triangle + 2]]);
  const D3 origin{ray.ox, ray.oy, ray.oz}, direction{ray.dx, ray.dy, ray.dz};
  const D3 e1 = sub(b, a), e2 = sub(c, a);
  const D3 p = cross(direction, e2);
  const double determinant = dot(e1, p);
  DoubleHit hit;
  // Relative test: the ray's direction is (numerically) in the triangle's plane.
  if (!(std::abs(determinant) > 1e-12 * length(e1) * length(e2) * length(direction))) return hit;
  hit.parallel = false;
  hit.triangle = triangle;
  const D3 s = sub(origin, a);
  const double u = dot(s, p) / determinant;
  const D3 q = cross(s, e1);
  const double v = dot(direction, q) / determinant;
  hit.t = dot(e2, q) / determinant;
  hit.margin = std::min({u, v, 1.0 - u - v});
  hit.hit = hit.margin >= 0 && hit.t > ray.tmin && hit.t < ray.tmax;
  // |determinant| = |d| |e1 x e2| cos(angle between ray and normal).
  const double twice_area = length(cross(e1, e2));
  hit.inverse_cosine = twice_area * length(direction) / std::abs(determinant);
  hit.uncertainty = 2e-6 * (1.0 + length(s) / std::sqrt(twice_area)) * hit.inverse_cosine;
  return hit;
}

}  // namespace kdray::test
