#include "mesh_builder.h"

#include <cmath>
#include <limits>

namespace kdray {
namespace {

constexpr uint8_t kHasNormal = 1, kHasUV = 2;

bool is_finite(const Vec3& v) { return std::isfinite(v.x) && std::isfinite(v.y) && std::isfinite(v.z); }

// Exactly zero area in double precision: collinear or coincident corners.
bool has_zero_area(const Vec3& a, const Vec3& b, const Vec3& c) {
  const double e1x = double(b.x) - a.x, e1y = double(b.y) - a.y, e1z = double(b.z) - a.z;
  const double e2x = double(c.x) - a.x, e2y = double(c.y) - a.y, e2z = double(c.z) - a.z;
  const double nx = e1y * e2z - e1z * e2y, ny = e1z * e2x - e1x * e2z, nz = e1x * e2y - e1y * e2x;
  return nx == 0 && ny == 0 && nz == 0;
}

}  // namespace

uint32_t MeshBuilder::add_vertex(const Vec3& position, const std::optional<Vec3>& normal,
                                 const std::optional<Vec2>& uv) {
  // A non-finite or zero normal, or a non-finite UV, counts as absent.
  const bool usable_normal = normal && is_finite(*normal) && (normal->x != 0 || normal->y != 0 || normal->z != 0);
  const bool usable_uv = uv && std::isfinite(uv->u) && std::isfinite(uv->v);
  positions_.push_back(position);
  normals_.push_back(usable_normal ? *normal : Vec3{});
  uvs_.push_back(usable_uv ? *uv : Vec2{});
  attributes_.push_back(uint8_t((usable_normal ? kHasNormal : 0) | (usable_uv ? kHasUV : 0)));
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
  const bool keep_normals = kept > 0 && (all_attributes & kHasNormal);
  const bool keep_uvs = any_attributes & kHasUV;
  scene.positions.assign(kept, Vec3{});
  if (keep_normals) scene.normals.assign(kept, Vec3{});
  if (keep_uvs) scene.uvs.assign(kept, Vec2{});
  for (size_t old = 0; old < new_index.size(); ++old) {
    const uint32_t to = new_index[old];
    if (to == kUnused) continue;
    scene.positions[to] = positions_[old];
    if (keep_normals) scene.normals[to] = normals_[old];
    if (keep_uvs) scene.uvs[to] = uvs_[old];
  }
  scene.indices = std::move(indices_);
  scene.material_ids = std::move(material_ids_);
}

}  // namespace kdray
