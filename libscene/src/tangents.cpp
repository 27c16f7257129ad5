#include <kdray/tangents.h>

#include <kdray/double3.h>

#include <algorithm>
#include <cmath>
#include <limits>

namespace kdray {
// Double precision throughout (kdray/double3.h): tangents come from differences of nearby
// positions and UVs.
namespace {

// v / |v|, or the zero vector when v is zero or not finite.
Double3 unit_or_zero(const Double3& v) {
  const double length = std::sqrt(dot(v, v));
  return length > 0 && std::isfinite(length) ? v * (1 / length) : Double3{0, 0, 0};
}

// v without its component along the unit (or zero) vector n.
Double3 in_plane(const Double3& v, const Double3& n) { return v - n * dot(n, v); }

// A unit vector perpendicular to n: n crossed with the axis least aligned with it.
Double3 any_perpendicular(const Double3& n) {
  const Double3 a{std::abs(n[0]), std::abs(n[1]), std::abs(n[2])};
  const Double3 axis = a[0] <= a[1] && a[0] <= a[2] ? Double3{1, 0, 0} : a[1] <= a[2] ? Double3{0, 1, 0} : Double3{0, 0, 1};
  const Double3 t = unit_or_zero(cross(axis, n));
  return dot(t, t) > 0 ? t : Double3{1, 0, 0};
}

// A triangle's dp/du and dp/dv, and the sign of its UV area: +1 where the UVs run
// counter-clockwise like the positions, -1 where they are mirrored, 0 where the UV area is
// zero (or the derivatives are not finite) and the triangle says nothing about tangents.
struct UvFrame {
  Double3 dpdu{}, dpdv{};
  int sign = 0;
};

UvFrame uv_frame(const Scene& scene, size_t triangle) {
  const uint32_t* corner = &scene.indices[3 * triangle];
  const Double3 p0 = double3(scene.positions[corner[0]]);
  const Double3 e1 = double3(scene.positions[corner[1]]) - p0, e2 = double3(scene.positions[corner[2]]) - p0;
  const Vec2 &t0 = scene.uvs[corner[0]], &t1 = scene.uvs[corner[1]], &t2 = scene.uvs[corner[2]];
  const double du1 = double(t1.u) - t0.u, dv1 = double(t1.v) - t0.v;
  const double du2 = double(t2.u) - t0.u, dv2 = double(t2.v) - t0.v;
  const double det = du1 * dv2 - du2 * dv1;
  UvFrame frame;
  if (det == 0) return frame;
  frame.dpdu = (e1 * dv2 - e2 * dv1) * (1 / det);
  frame.dpdv = (e2 * du1 - e1 * du2) * (1 / det);
  if (!std::isfinite(dot(frame.dpdu, frame.dpdu)) || !std::isfinite(dot(frame.dpdv, frame.dpdv))) return frame;
  frame.sign = det > 0 ? 1 : -1;
  return frame;
}

// Appends a copy of vertex v (all its attributes) and returns its number.
uint32_t copy_vertex(Scene& scene, uint32_t v) {
  const Vec3 position = scene.positions[v];
  scene.positions.push_back(position);
  if (!scene.normals.empty()) {
    const Vec3 normal = scene.normals[v];
    scene.normals.push_back(normal);
  }
  const Vec2 uv = scene.uvs[v];
  scene.uvs.push_back(uv);
  const Tangent tangent = scene.tangents[v];
  scene.tangents.push_back(tangent);
  return uint32_t(scene.positions.size() - 1);
}

// Splits the vertices to compute that triangles of both UV orientations share: the first
// orientation met keeps the vertex, the triangles of the other one get a copy.
void split_mirrored_vertices(Scene& scene, std::vector<bool>& missing) {
  constexpr uint32_t kNone = std::numeric_limits<uint32_t>::max();
  std::vector<int8_t> orientation(scene.positions.size(), 0);
  std::vector<uint32_t> copy(scene.positions.size(), kNone);
  for (size_t t = 0; t < scene.triangle_count(); ++t) {
    const int sign = uv_frame(scene, t).sign;
    if (sign == 0) continue;
    for (int corner = 0; corner < 3; ++corner) {
      uint32_t& v = scene.indices[3 * t + corner];
      if (v >= orientation.size() || !missing[v]) continue;  // a copy already, or authored
      if (orientation[v] == 0) orientation[v] = int8_t(sign);
      if (orientation[v] == sign) continue;
      if (copy[v] == kNone) {
        copy[v] = copy_vertex(scene, v);
        missing.push_back(true);
      }
      v = copy[v];
    }
  }
}

// Unit vertex normals: the scene's, or the area-weighted sum of the triangles' around each vertex.
std::vector<Double3> vertex_normals(const Scene& scene) {
  std::vector<Double3> normals(scene.positions.size(), Double3{0, 0, 0});
  if (!scene.normals.empty()) {
    for (size_t v = 0; v < normals.size(); ++v) normals[v] = unit_or_zero(double3(scene.normals[v]));
    return normals;
  }
  for (size_t t = 0; t < scene.triangle_count(); ++t) {
    const uint32_t* corner = &scene.indices[3 * t];
    const Double3 p0 = double3(scene.positions[corner[0]]);
    const Double3 area_normal = cross(double3(scene.positions[corner[1]]) - p0, double3(scene.positions[corner[2]]) - p0);
    for (int c = 0; c < 3; ++c) normals[corner[c]] = normals[corner[c]] + area_normal;
  }
  for (Double3& n : normals) n = unit_or_zero(n);
  return normals;
}

// The angle of a triangle's corner `c`: MikkTSpace's weight, so that a vertex's tangent does not
// depend on how the polygons around it were cut into triangles.
double corner_angle(const Scene& scene, const uint32_t* corner, int c) {
  const Double3 p = double3(scene.positions[corner[c]]);
  const Double3 a = unit_or_zero(double3(scene.positions[corner[(c + 1) % 3]]) - p);
  const Double3 b = unit_or_zero(double3(scene.positions[corner[(c + 2) % 3]]) - p);
  return std::acos(std::clamp(dot(a, b), -1.0, 1.0));
}

// Computes the tangents of the vertices marked missing into `tangents` (one per vertex).
void compute_missing(const Scene& scene, const std::vector<bool>& missing, std::vector<Tangent>& tangents) {
  const std::vector<Double3> normals = vertex_normals(scene);
  std::vector<Double3> sum_dpdu(scene.positions.size(), Double3{0, 0, 0}), sum_dpdv(scene.positions.size(), Double3{0, 0, 0});
  for (size_t t = 0; t < scene.triangle_count(); ++t) {
    const UvFrame frame = uv_frame(scene, t);
    if (frame.sign == 0) continue;
    const uint32_t* corner = &scene.indices[3 * t];
    for (int c = 0; c < 3; ++c) {
      const uint32_t v = corner[c];
      if (!missing[v]) continue;
      const double weight = corner_angle(scene, corner, c);
      sum_dpdu[v] = sum_dpdu[v] + unit_or_zero(in_plane(frame.dpdu, normals[v])) * weight;
      sum_dpdv[v] = sum_dpdv[v] + unit_or_zero(in_plane(frame.dpdv, normals[v])) * weight;
    }
  }
  for (size_t v = 0; v < missing.size(); ++v) {
    if (!missing[v]) continue;
    const Double3& n = normals[v];
    Double3 t = unit_or_zero(in_plane(sum_dpdu[v], n));
    if (dot(t, t) == 0) t = any_perpendicular(n);
    const float w = dot(cross(n, t), sum_dpdv[v]) < 0 ? -1.0f : 1.0f;
    tangents[v] = {float(t[0]), float(t[1]), float(t[2]), w};
  }
}

}  // namespace

bool scene_needs_tangents(const Scene& scene) {
  return !scene.uvs.empty() && std::any_of(scene.materials.begin(), scene.materials.end(),
                                           [](const Material& m) { return m.normal_texture >= 0; });
}

void complete_tangents(Scene& scene) {
  if (!scene_needs_tangents(scene)) {
    scene.tangents.clear();
    return;
  }
  if (scene.tangents.empty()) scene.tangents.assign(scene.positions.size(), Tangent{});
  std::vector<bool> missing(scene.positions.size());
  for (size_t v = 0; v < missing.size(); ++v) missing[v] = scene.tangents[v].w == 0;
  if (std::none_of(missing.begin(), missing.end(), [](bool m) { return m; })) return;
  split_mirrored_vertices(scene, missing);
  compute_missing(scene, missing, scene.tangents);
}

std::vector<Tangent> tangents_on_vertices(const Scene& scene) {
  if (!scene_needs_tangents(scene)) return {};
  std::vector<Tangent> tangents = scene.tangents;
  if (tangents.empty()) tangents.assign(scene.positions.size(), Tangent{});
  std::vector<bool> missing(tangents.size());
  for (size_t v = 0; v < missing.size(); ++v) missing[v] = tangents[v].w == 0;
  compute_missing(scene, missing, tangents);
  return tangents;
}

}  // namespace kdray
