// The scene model: one world-space triangle mesh with per-triangle materials, optional
// per-vertex normals and UVs, embedded textures, cameras and the list of emissive triangles.
// Only what the source has is present: empty optional arrays mean "absent".
#pragma once

#include <cstdint>
#include <string>
#include <vector>

namespace kdray {

struct Vec3 {
  float x = 0, y = 0, z = 0;
};
struct Vec2 {
  float u = 0, v = 0;
};
static_assert(sizeof(Vec3) == 12 && sizeof(Vec2) == 8, "stored as contiguous float arrays");

enum class MaterialType : uint32_t {
  Diffuse = 0,         // Lambertian, base_color is the albedo
  Emissive = 1,        // one-sided area light; emission is the radiance; base_color still reflects
  Mirror = 2,          // perfect specular reflection tinted by base_color
  RoughConductor = 3,  // GGX microfacet reflection, roughness = alpha, Fresnel-Schlick with base_color as F0
  Dielectric = 4,      // smooth glass with index of refraction ior
};

const char* material_type_name(MaterialType type);

struct Material {
  std::string name;
  MaterialType type = MaterialType::Diffuse;
  Vec3 base_color{0.8f, 0.8f, 0.8f};
  Vec3 emission{0, 0, 0};
  float roughness = 1.0f;     // GGX alpha for RoughConductor
  float ior = 1.5f;           // Dielectric
  int32_t diffuse_texture = -1;  // index into Scene::textures, or -1
};

// Decoded at conversion time: 8-bit sRGB-encoded RGBA, rows top to bottom.
struct Texture {
  std::string name;  // source path, for reports
  uint32_t width = 0, height = 0;
  std::vector<uint8_t> rgba;
};

struct Camera {
  std::string name;
  Vec3 position{0, 0, 1};
  Vec3 target{0, 0, 0};
  Vec3 up{0, 1, 0};
  float vertical_fov_degrees = 45.0f;
};

// What the importer dropped or ignored, so summaries can say so.
struct ImportStats {
  std::string source_file;
  std::string importer;             // "tinyobj" or "assimp"
  uint64_t source_triangles = 0;    // after triangulation, before drops
  uint64_t dropped_degenerate = 0;  // zero area or repeated index
  uint64_t dropped_non_finite = 0;  // NaN or Inf vertex
  uint64_t ignored_points = 0;
  uint64_t ignored_lines = 0;
  std::vector<std::string> warnings;  // e.g. a texture that could not be read
};

struct Bounds {
  Vec3 min{0, 0, 0};
  Vec3 max{0, 0, 0};
};

struct Scene {
  std::vector<Vec3> positions;
  std::vector<uint32_t> indices;       // three per triangle
  std::vector<uint32_t> material_ids;  // one per triangle, into materials
  std::vector<Vec3> normals;           // per vertex, or empty
  std::vector<Vec2> uvs;               // per vertex, or empty
  std::vector<Material> materials;
  std::vector<Texture> textures;
  std::vector<Camera> cameras;         // at least one after import (a default framing camera)
  std::vector<uint32_t> emissive_triangles;  // triangles whose material emits
  ImportStats import_stats;
  uint64_t content_hash = 0;           // set by compute_content_hash / on load

  size_t triangle_count() const { return indices.size() / 3; }
};

Bounds scene_bounds(const Scene& scene);

// 64-bit XXH3 over geometry, materials, textures and cameras: what a tree or image was made from.
uint64_t compute_content_hash(const Scene& scene);

}  // namespace kdray
