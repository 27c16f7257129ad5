// Collects an importer's world-space vertices and triangles into the scene model, dropping
// (and counting) the triangles a renderer cannot use: a repeated vertex index, zero area, or a
// non-finite corner. Shared by the tinyobjloader and Assimp importers so both apply the same rules.
#pragma once

#include <kdray/scene.h>

#include <cstdint>
#include <optional>
#include <vector>

namespace kdray {

class MeshBuilder {
 public:
  explicit MeshBuilder(ImportStats& stats) : stats_(stats) {}

  // `tangent` is one the asset authored (unit xyz, w = +1 or -1).
  uint32_t add_vertex(const Vec3& position, const std::optional<Vec3>& normal, const std::optional<Vec2>& uv,
                      const std::optional<Tangent>& tangent = std::nullopt);
  size_t vertex_count() const { return positions_.size(); }
  const Vec3& position(uint32_t vertex) const { return positions_[vertex]; }

  // Counts the triangle as a source triangle and keeps it unless it must be dropped.
  void add_triangle(uint32_t a, uint32_t b, uint32_t c, uint32_t material);

  // Moves the kept triangles into `scene`, keeping only referenced vertices. Normals are kept
  // when any kept vertex has one; vertices without get the area-weighted normal of the
  // triangles around them. UVs are kept when any kept vertex has one; the others get (0, 0).
  // Tangents are completed by complete_tangents (kdray/tangents.h), which keeps the authored
  // ones, so `scene` must hold its materials already.
  void finish(Scene& scene);

 private:
  void fill_missing_normals(Scene& scene, const std::vector<uint32_t>& new_index) const;

  ImportStats& stats_;
  std::vector<Vec3> positions_;
  std::vector<Vec3> normals_;
  std::vector<Vec2> uvs_;
  std::vector<Tangent> tangents_;    // w = 0 where the vertex has none
  std::vector<uint8_t> attributes_;  // per vertex: kHasNormal | kHasUV | kHasTangent
  std::vector<uint32_t> indices_;
  std::vector<uint32_t> material_ids_;
};

}  // namespace kdray
