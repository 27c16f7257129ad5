#include <kdray/ray_sets.h>

#include <algorithm>
#include <cmath>
#include <iterator>

namespace kdray {
namespace {

class Random {
 public:
  explicit Random(uint64_t seed) : state_(seed) {}
  uint64_t next() {  // splitmix64
    uint64_t z = (state_ += 0x9e3779b97f4a7c15ull);
    z = (z ^ (z >> 30)) * 0xbf58476d1ce4e5b9ull;
    z = (z ^ (z >> 27)) * 0x94d049bb133111ebull;
    return z ^ (z >> 31);
  }
  double uniform() { return static_cast<double>(next() >> 11) * 0x1.0p-53; }  // [0, 1)
  size_t below(size_t n) { return static_cast<size_t>(next() % n); }
  float in(float lo, float hi) { return static_cast<float>(lo + (static_cast<double>(hi) - lo) * uniform()); }

 private:
  uint64_t state_;
};

struct Direction {
  double x, y, z;
};

Direction normalized(double x, double y, double z) {
  const double length = std::sqrt(x * x + y * y + z * z);
  if (length == 0.0) return {0, 0, 1};
  return {x / length, y / length, z / length};
}

RayRecord make_ray(const float origin[3], Direction d) {
  return RayRecord{origin[0], origin[1], origin[2], static_cast<float>(d.x), static_cast<float>(d.y),
                   static_cast<float>(d.z), 0.0f, INFINITY};
}

RayRecord aimed_ray(const float origin[3], const float target[3]) {
  return make_ray(origin, normalized(static_cast<double>(target[0]) - origin[0],
                                     static_cast<double>(target[1]) - origin[1],
                                     static_cast<double>(target[2]) - origin[2]));
}

// From `origin` towards `target`: the direction normalised (tmax +inf) or the difference itself
// (tmax 1), times `scale`, a power of two, with tmax divided by it.
RayRecord scaled_ray(const float origin[3], const float target[3], double scale, bool normalise) {
  Direction d{static_cast<double>(target[0]) - origin[0], static_cast<double>(target[1]) - origin[1],
              static_cast<double>(target[2]) - origin[2]};
  if (normalise) d = normalized(d.x, d.y, d.z);
  return RayRecord{origin[0],
                   origin[1],
                   origin[2],
                   static_cast<float>(d.x * scale),
                   static_cast<float>(d.y * scale),
                   static_cast<float>(d.z * scale),
                   0.0f,
                   normalise ? INFINITY : static_cast<float>(1.0 / scale)};
}

// The centre and radius of the sphere around `bounds` (radius 1 for a point).
void bounding_sphere(const Bounds& bounds, double centre[3], double& radius) {
  const float* lo = &bounds.min.x;
  const float* hi = &bounds.max.x;
  double squared = 0;
  for (int k = 0; k < 3; ++k) {
    centre[k] = 0.5 * (static_cast<double>(lo[k]) + hi[k]);
    squared += 0.25 * (static_cast<double>(hi[k]) - lo[k]) * (static_cast<double>(hi[k]) - lo[k]);
  }
  radius = squared > 0 ? std::sqrt(squared) : 1.0;
}

void point_on_sphere(Random& random, const double centre[3], double radius, float out[3]) {
  const double z = 2.0 * random.uniform() - 1.0;
  const double phi = 2.0 * M_PI * random.uniform();
  const double r = std::sqrt(std::max(0.0, 1.0 - z * z));
  const double unit[3] = {r * std::cos(phi), r * std::sin(phi), z};
  for (int k = 0; k < 3; ++k) out[k] = static_cast<float>(centre[k] + radius * unit[k]);
}

void point_in_box(Random& random, const Bounds& bounds, float out[3]) {
  const float* lo = &bounds.min.x;
  const float* hi = &bounds.max.x;
  for (int k = 0; k < 3; ++k) out[k] = random.in(lo[k], hi[k]);
}

void vertex_of(const Scene& scene, size_t triangle, int corner, float out[3]) {
  const Vec3& p = scene.positions[scene.indices[3 * triangle + corner]];
  out[0] = p.x;
  out[1] = p.y;
  out[2] = p.z;
}

void point_on_edge(const Scene& scene, Random& random, float out[3]) {
  const size_t triangle = random.below(scene.triangle_count());
  const int corner = static_cast<int>(random.below(3));
  float a[3], b[3];
  vertex_of(scene, triangle, corner, a);
  vertex_of(scene, triangle, (corner + 1) % 3, b);
  const double t = random.uniform();
  for (int k = 0; k < 3; ++k) out[k] = static_cast<float>(a[k] + t * (static_cast<double>(b[k]) - a[k]));
}

void point_in_triangle(const Scene& scene, Random& random, float out[3]) {
  const size_t triangle = random.below(scene.triangle_count());
  float a[3], b[3], c[3];
  vertex_of(scene, triangle, 0, a);
  vertex_of(scene, triangle, 1, b);
  vertex_of(scene, triangle, 2, c);
  double u = random.uniform(), v = random.uniform();
  if (u + v > 1.0) {
    u = 1.0 - u;
    v = 1.0 - v;
  }
  for (int k = 0; k < 3; ++k) out[k] = static_cast<float>(a[k] + u * (static_cast<double>(b[k]) - a[k]) +
                                                          v * (static_cast<double>(c[k]) - a[k]));
}

}  // namespace

std::vector<RayRecord> camera_rays(const Scene& scene, uint32_t width, uint32_t height) {
  const Bounds bounds = scene_bounds(scene);
  const Camera camera = scene.cameras.empty() ? default_camera(bounds) : scene.cameras.front();
  const Direction forward = normalized(camera.target.x - camera.position.x, camera.target.y - camera.position.y,
                                       camera.target.z - camera.position.z);
  Direction right = normalized(forward.y * camera.up.z - forward.z * camera.up.y,
                               forward.z * camera.up.x - forward.x * camera.up.z,
                               forward.x * camera.up.y - forward.y * camera.up.x);
  const Direction up{right.y * forward.z - right.z * forward.y, right.z * forward.x - right.x * forward.z,
                     right.x * forward.y - right.y * forward.x};
  const double half_height = std::tan(0.5 * camera.vertical_fov_degrees * M_PI / 180.0);
  const double half_width = half_height * width / std::max<uint32_t>(height, 1);
  const float origin[3] = {camera.position.x, camera.position.y, camera.position.z};
  std::vector<RayRecord> rays;
  rays.reserve(static_cast<size_t>(width) * height);
  for (uint32_t y = 0; y < height; ++y) {
    for (uint32_t x = 0; x < width; ++x) {
      const double sx = (2.0 * (x + 0.5) / width - 1.0) * half_width;
      const double sy = (1.0 - 2.0 * (y + 0.5) / height) * half_height;
      rays.push_back(make_ray(origin, normalized(forward.x + sx * right.x + sy * up.x,
                                                 forward.y + sx * right.y + sy * up.y,
                                                 forward.z + sx * right.z + sy * up.z)));
    }
  }
  return rays;
}

std::vector<RayRecord> random_rays(const Bounds& bounds, size_t count, uint64_t seed) {
  Random random(seed);
  double centre[3], radius;
  bounding_sphere(bounds, centre, radius);
  std::vector<RayRecord> rays;
  rays.reserve(count);
  for (size_t i = 0; i < count; ++i) {
    float origin[3], target[3];
    point_on_sphere(random, centre, radius, origin);
    point_in_box(random, bounds, target);
    rays.push_back(aimed_ray(origin, target));
  }
  return rays;
}

std::vector<RayRecord> hard_case_rays(const Scene& scene, const KdTree& tree, size_t count, uint64_t seed) {
  Random random(seed);
  const Bounds& bounds = tree.bounds;
  double centre[3], radius;
  bounding_sphere(bounds, centre, radius);
  std::vector<uint32_t> inner_nodes;
  for (uint32_t i = 0; i < tree.nodes.size(); ++i)
    if (!kd_node_is_leaf(tree.nodes[i])) inner_nodes.push_back(i);
  const bool has_triangles = scene.triangle_count() > 0;
  auto random_axis_direction = [&](int axis, float out[3]) {
    for (int k = 0; k < 3; ++k) out[k] = random.below(2) ? -0.0f : 0.0f;
    out[axis] = random.below(2) ? -1.0f : 1.0f;
  };
  std::vector<RayRecord> rays;
  rays.reserve(count);
  for (size_t i = 0; i < count; ++i) {
    float origin[3], target[3], direction[3];
    const int axis = static_cast<int>(random.below(3));
    point_in_box(random, bounds, origin);
    const size_t kind = i % 8;  // the cases below, in turn
    switch (kind) {
      case 0:  // axis-aligned, the other components +0 or -0
        random_axis_direction(axis, direction);
        origin[axis] = static_cast<float>(centre[axis] - direction[axis] * 2.0 * radius);
        rays.push_back(RayRecord{origin[0], origin[1], origin[2], direction[0], direction[1], direction[2], 0.0f,
                                 INFINITY});
        continue;
      case 1:    // origin exactly on a split plane
      case 2: {  // lying in a split plane
        if (!inner_nodes.empty()) {
          const KdNode node = tree.nodes[inner_nodes[random.below(inner_nodes.size())]];
          origin[kd_node_axis(node)] = kd_node_split(node);
          point_in_box(random, bounds, target);
          Direction d = normalized(static_cast<double>(target[0]) - origin[0], static_cast<double>(target[1]) - origin[1],
                                   static_cast<double>(target[2]) - origin[2]);
          RayRecord ray = make_ray(origin, d);
          if (kind == 2) (&ray.dx)[kd_node_axis(node)] = random.below(2) ? -0.0f : 0.0f;
          rays.push_back(ray);
          continue;
        }
        break;
      }
      case 3:  // at a vertex
      case 4:  // at a point on an edge
        if (has_triangles) {
          float sphere[3];
          point_on_sphere(random, centre, radius, sphere);
          if (kind == 3)
            vertex_of(scene, random.below(scene.triangle_count()), static_cast<int>(random.below(3)), target);
          else
            point_on_edge(scene, random, target);
          rays.push_back(aimed_ray(sphere, target));
          continue;
        }
        break;
      case 6:  // a segment, as a shadow ray is: the direction not normalised, scaled by a power of two
        if (has_triangles) {
          point_in_triangle(scene, random, origin);
          point_in_box(random, bounds, target);
          rays.push_back(scaled_ray(origin, target, std::ldexp(1.0, static_cast<int>(8 * random.below(4))), false));
          continue;
        }
        break;
      case 7:  // a long direction from an origin one float off a split plane, or at or near 0, on one axis
        point_in_box(random, bounds, target);
        if (!inner_nodes.empty() && random.below(2)) {
          const KdNode node = tree.nodes[inner_nodes[random.below(inner_nodes.size())]];
          const float split = kd_node_split(node);
          origin[kd_node_axis(node)] = std::nextafter(split, random.below(2) ? INFINITY : -INFINITY);
        } else {
          const float near_zero[] = {0.0f, -0.0f, 1.40129846e-45f, -1.40129846e-45f, 1.17549435e-38f, 7.88860905e-31f};
          origin[axis] = near_zero[random.below(std::size(near_zero))];
        }
        rays.push_back(scaled_ray(origin, target, std::ldexp(1.0, 1 + static_cast<int>(random.below(40))), true));
        continue;
      case 5:  // axis-aligned through a vertex
        if (has_triangles) {
          vertex_of(scene, random.below(scene.triangle_count()), static_cast<int>(random.below(3)), origin);
          random_axis_direction(axis, direction);
          origin[axis] = static_cast<float>(centre[axis] - direction[axis] * 2.0 * radius);
          rays.push_back(RayRecord{origin[0], origin[1], origin[2], direction[0], direction[1], direction[2], 0.0f,
                                   INFINITY});
          continue;
        }
        break;
    }
    point_in_box(random, bounds, target);
    point_on_sphere(random, centre, radius, origin);
    rays.push_back(aimed_ray(origin, target));
  }
  return rays;
}

std::vector<RayRecord> rays_toward_surface(const Scene& scene, const Vec3& origin, size_t count, uint64_t seed) {
  Random random(seed);
  const float from[3] = {origin.x, origin.y, origin.z};
  std::vector<RayRecord> rays;
  if (scene.triangle_count() == 0) return rays;
  rays.reserve(count);
  for (size_t i = 0; i < count; ++i) {
    float target[3];
    switch (i % 3) {
      case 0: vertex_of(scene, random.below(scene.triangle_count()), static_cast<int>(random.below(3)), target); break;
      case 1: point_on_edge(scene, random, target); break;
      default: point_in_triangle(scene, random, target); break;
    }
    rays.push_back(aimed_ray(from, target));
  }
  return rays;
}

}  // namespace kdray
