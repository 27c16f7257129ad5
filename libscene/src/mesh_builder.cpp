#include "mesh_builder.h"

#include <kdray/double3.h>
#include <kdray/tangents.h>

#include <cmath>
#include <limits>

namespace kdray {
namespace {

constexpr uint8_t kHasNormal = 1, kHasUV = 2, kHasTangent = 4;

bool is_finite(const Vec3& v) { return std::isfinite(v.x) && std::isfinite(v.y) && std::isfinite(v.z); }

// (b - a) x (c - a) in double precision.
Double3 edge_cross(const Vec3& a, const Vec3& b, const Vec3& c) {
  return cross(double3(b) - double3(a), double3(c) - double3(a));
}

// Exactly zero area in double precision: collinear or coincident corners.
bool has_zero_area(const Vec3& a, const Vec3& b, const Vec3& c) {
  return edge_cross(a, b, c) == Double3{0, 0, 0};
}

}  // namespace

uint32_t MeshBuilder::add_vertex(const Vec3& position, const std::optional<Vec3>& normal,
                                 const std::optional<Vec2>& uv, const std::optional<Tangent>& tangent) {
  // A non-finite or zero normal or tangent, or a non-finite UV, counts as absent.
  const bool usable_normal = normal && is_finite(*normal) && (normal->x != 0 || normal->y != 0 || normal->z != 0);
  const bool usable_uv = uv && std::isfinite(uv->u) && std::isfinite(uv->v);
  const bool usable_tangent = tangent && is_finite({tangent->x, tangent->y, tangent->z}) &&
                              (tangent->x != 0 || tangent->y != 0 || tangent->z != 0) &&
                              (tangent->w == 1 || tangent->w == -1);
  positions_.push_back(position);
  normals_.push_back(usable_normal ? *normal : Vec3{});
  uvs_.push_back(usable_uv ? *uv : Vec2{});
  tangents_.push_back(usable_tangent ? *tangent : Tangent{});
  attributes_.push_back(
      uint8_t((usable_normal ? kHasNormal : 0) | (usable_uv ? kHasUV : 0) | (usable_tangent ? kHasTangent : 0)));
  return static_cast<uint32_t>(positions_.size() - 1);
}

void MeshBuilder::add_triangle(uint32_t a, uint32_t b, uint32_t c, uint32_t material) {
  ++stats_.source_triangles;
  const Vec3 &pa = positions_[a], &pb = positions_[b], &pc = positions_[c];
  if (!is_finite(pa) || !is_finite(pb) || !is_finite(pc)) {
    ++stats_.dropped_non_finite;
    return;
  }
  if (a == b || b == c || a == c || has_zero_area(pa, pb, pc)) {
    ++stats_.dropped_degenerate;
    return;
  }
  indices_.insert(indices_.end(), {a, b, c});
  material_ids_.push_back(material);
}

void MeshBuilder::finish(Scene& scene) {
  constexpr uint32_t kUnused = std::numeric_limits<uint32_t>::max();
  std::vector<uint32_t> new_index(positions_.size(), kUnused);
  uint8_t all_attributes = kHasNormal | kHasUV, any_attributes = 0;
  uint32_t kept = 0;
  for (uint32_t& index : indices_) {
    if (new_index[index] == kUnused) {
      new_index[index] = kept++;
      all_attributes &= attributes_[index];
      any_attributes |= attributes_[index];
    }
    index = new_index[index];
  }
  const bool keep_normals = any_attributes & kHasNormal;
  const bool keep_uvs = any_attributes & kHasUV;
  const bool keep_tangents = any_attributes & kHasTangent;
  scene.positions.assign(kept, Vec3{});
  if (keep_normals) scene.normals.assign(kept, Vec3{});
  if (keep_uvs) scene.uvs.assign(kept, Vec2{});
  if (keep_tangents) scene.tangents.assign(kept, Tangent{});
  for (size_t old = 0; old < new_index.size(); ++old) {
    const uint32_t to = new_index[old];
    if (to == kUnused) continue;
    scene.positions[to] = positions_[old];
    if (keep_normals) scene.normals[to] = normals_[old];
    if (keep_uvs) scene.uvs[to] = uvs_[old];
    if (keep_tangents) scene.tangents[to] = tangents_[old];
  }
  scene.indices = std::move(indices_);
  scene.material_ids = std::move(material_ids_);
  if (keep_normals && !(all_attributes & kHasNormal)) fill_missing_normals(scene, new_index);
  complete_tangents(scene);
}

// Missing normals get the area-weighted average of the normals of the triangles around them
// (the cross product's length is twice the area); if those cancel out, the first one's normal.
void MeshBuilder::fill_missing_normals(Scene& scene, const std::vector<uint32_t>& new_index) const {
  std::vector<bool> missing(scene.positions.size(), false);
  for (size_t old = 0; old < new_index.size(); ++old)
    if (new_index[old] != std::numeric_limits<uint32_t>::max() && !(attributes_[old] & kHasNormal))
      missing[new_index[old]] = true;
  std::vector<Double3> sum(scene.positions.size(), {0, 0, 0});
  std::vector<Double3> first(scene.positions.size(), {0, 0, 0});
  for (size_t t = 0; t < scene.indices.size(); t += 3) {
    const Vec3 &a = scene.positions[scene.indices[t]], &b = scene.positions[scene.indices[t + 1]],
               &c = scene.positions[scene.indices[t + 2]];
    const Double3 normal = edge_cross(a, b, c);
    for (int corner = 0; corner < 3; ++corner) {
      const uint32_t v = scene.indices[t + corner];
      if (!missing[v]) continue;
      if (sum[v] == Double3{0, 0, 0}) first[v] = normal;
      for (int axis = 0; axis < 3; ++axis) sum[v][axis] += normal[axis];
    }
  }
  for (size_t v = 0; v < missing.size(); ++v) {
    if (!missing[v]) continue;
    Double3 n = sum[v];
    double length = std::sqrt(n[0] * n[0] + n[1] * n[1] + n[2] * n[2]);
    if (!(length > 0)) {
      n = first[v];
      length = std::sqrt(n[0] * n[0] + n[1] * n[1] + n[2] * n[2]);
    }
    scene.normals[v] = {float(n[0] / length), float(n[1] / length), float(n[2] / length)};
  }
}

}  // namespace kdray
