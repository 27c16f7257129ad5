#include "brute_force.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>
#include <sstream>

namespace kdray::test {

std::string describe_ray(const RayRecord& ray) {
  char text[256];
  std::snprintf(text, sizeof text, "o=(%.9g,%.9g,%.9g) d=(%.9g,%.9g,%.9g) [%.9g,%.9g]", ray.ox, ray.oy, ray.oz, ray.dx,
                ray.dy, ray.dz, ray.tmin, ray.tmax);
  return text;
}

double scene_magnitude(const Scene& scene) {
  double largest = 0;
  for (const Vec3& p : scene.positions) {
    for (float c : {p.x, p.y, p.z}) {
      if (std::isfinite(c)) largest = std::max(largest, double(std::abs(c)));
    }
  }
  return largest;
}

double t_tolerance(const RayRecord& ray, double scene_magnitude, double t) {
  const double origin_size = std::max({std::abs(ray.ox), std::abs(ray.oy), std::abs(ray.oz)});
  const double direction_length = std::sqrt(double(ray.dx) * ray.dx + double(ray.dy) * ray.dy + double(ray.dz) * ray.dz);
  return 4e-6 * (origin_size + scene_magnitude) / direction_length + 4e-7 * std::abs(t);
}

std::string disagreement(const Scene& scene, const RayRecord& ray, const HitRecord& hit, double scene_magnitude) {
  // The closest clear double hit: inside by more than its uncertainty, t clearly in range.
  double closest_clear = std::numeric_limits<double>::infinity();
  uint32_t closest_clear_triangle = KD_NO_HIT;
  for (uint32_t triangle = 0; triangle < scene.triangle_count(); ++triangle) {
    const DoubleHit h = intersect_double(scene, triangle, ray);
    if (!h.clearly_inside()) continue;
    const double tolerance = t_tolerance(ray, scene_magnitude, h.t);
    if (h.t > double(ray.tmin) + tolerance && h.t < double(ray.tmax) - tolerance && h.t < closest_clear) {
      closest_clear = h.t;
      closest_clear_triangle = triangle;
    }
  }
  std::ostringstream why;
  why.precision(9);
  why << "ray " << describe_ray(ray) << ": ";
  if (hit.triangle == KD_NO_HIT) {
    if (closest_clear_triangle == KD_NO_HIT) return "";
    why << "tree misses, double hits triangle " << closest_clear_triangle << " at t=" << closest_clear;
    return why.str();
  }
  if (hit.triangle >= scene.triangle_count() || !std::isfinite(hit.t)) {
    why << "tree returns triangle " << hit.triangle << " at t=" << hit.t;
    return why.str();
  }
  const DoubleHit own = intersect_double(scene, hit.triangle, ray);
  const double tolerance = t_tolerance(ray, scene_magnitude, double(hit.t));
  if (!own.possibly_inside() || std::abs(own.t - double(hit.t)) > tolerance * own.inverse_cosine) {
    why << "tree hits triangle " << hit.triangle << " at t=" << hit.t << ", double says ";
    if (own.parallel) {
      why << "parallel";
    } else {
      why << "margin " << own.margin << " (uncertainty " << own.uncertainty << ") at t=" << own.t;
    }
    return why.str();
  }
  if (closest_clear < own.t - tolerance) {
    why << "tree hits triangle " << hit.triangle << " at t=" << hit.t << " but triangle " << closest_clear_triangle
        << " is closer at t=" << closest_clear;
    return why.str();
  }
  return "";
}

size_t count_disagreements(const Scene& scene, const std::vector<RayRecord>& rays, const std::vector<HitRecord>& hits,
                           std::vector<std::string>* reports, size_t max_reports) {
  size_t count = 0;
  const double magnitude = scene_magnitude(scene);
  for (size_t i = 0; i < rays.size(); ++i) {
    const std::string why = disagreement(scene, rays[i], hits[i], magnitude);
    if (why.empty()) continue;
    ++count;
    if (reports != nullptr && reports->size() < max_reports) reports->push_back(why);
  }
  return count;
}

std::vector<HitRecord> trace_checked(const Scene& scene, const KdTree& tree, const std::vector<RayRecord>& rays,
                                     const TraceOptions& options) {
  std::vector<HitRecord> hits;
  trace_closest(tree, rays, hits, options);
  std::vector<std::string> reports;
  EXPECT_EQ(count_disagreements(scene, rays, hits, &reports), 0u) << "of " << rays.size() << " rays";
  for (const std::string& report : reports) ADD_FAILURE() << report;
  return hits;
}

}  // namespace kdray::test
