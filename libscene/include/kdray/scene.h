// The scene model: one world-space triangle mesh with per-triangle materials, optional
// per-vertex normals, UVs and tangents, embedded textures, cameras and the list of emissive
// triangles. Only what the source has is present: empty optional arrays mean "absent".
#pragma once

#include <kernels/pt_codes.h>

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
// A tangent: the unit direction of +u in the surface, and in w the handedness (+1 or -1) that
// makes w * cross(normal, tangent) the direction of +v.
struct Tangent {
  float x = 0, y = 0, z = 0, w = 0;
};
static_assert(sizeof(Vec3) == 12 && sizeof(Vec2) == 8 && sizeof(Tangent) == 16, "stored as contiguous float arrays");

// The kernels' numbering (kernels/pt_codes.h), which is also the one .kdscene files store.
enum class MaterialType : uint32_t {
  Diffuse = PT_DIFFUSE,                // Lambertian, base_color is the albedo
  Emissive = PT_EMISSIVE,              // one-sided area light; emission is the radiance; base_color still reflects
  Mirror = PT_MIRROR,                  // perfect specular reflection tinted by base_color
  RoughConductor = PT_ROUGH_CONDUCTOR,  // GGX microfacet reflection, roughness = alpha, Fresnel-Schlick with base_color as F0
  Dielectric = PT_DIELECTRIC,          // smooth glass with index of refraction ior
  // glTF metallic-roughness, the glTF 2.0 specification's BRDF (Appendix B): a GGX conductor
  // with base_color as F0, weighted by metallic, and, weighted 1 - metallic, a Lambertian
  // base_color and a GGX specular layer mixed by Schlick's Fresnel of index ior (f0 0.04 at 1.5);
  // roughness = alpha of both GGX lobes, whose Smith G is the height-correlated one.
  MetallicRoughness = PT_METALLIC_ROUGHNESS,
};

// glTF alpha modes: Mask cuts out where alpha < alpha_cutoff, Blend lets a ray through with
// probability 1 - alpha (stochastic transparency).
enum class AlphaMode : uint32_t { Opaque = 0, Mask = 1, Blend = 2 };

const char* alpha_mode_name(AlphaMode mode);

const char* material_type_name(MaterialType type);

struct Material {
  std::string name;
  MaterialType type = MaterialType::Diffuse;
  Vec3 base_color{0.8f, 0.8f, 0.8f};
  Vec3 emission{0, 0, 0};
  float roughness = 1.0f;     // GGX alpha for RoughConductor
  float ior = 1.5f;           // Dielectric
  int32_t diffuse_texture = -1;  // index into Scene::textures, or -1; its alpha channel is alpha too
  // Format version 3 on (older files read the defaults).
  float metallic = 0;            // MetallicRoughness
  float alpha = 1;               // opacity for alpha_mode, times the base-colour texture's alpha
  AlphaMode alpha_mode = AlphaMode::Opaque;
  float alpha_cutoff = 0.5f;
  int32_t metal_rough_texture = -1;  // glTF layout, linear: G scales sqrt(roughness), B metallic
  int32_t normal_texture = -1;       // tangent-space normal map, linear, +Y towards +v
  int32_t emissive_texture = -1;     // sRGB, multiplies emission
};

// Decoded at conversion time: 8-bit sRGB-encoded RGBA, rows top to bottom.
struct Texture {
  std::string name;  // source path, for reports
  uint32_t width = 0, height = 0;
  std::vector<uint8_t> rgba;
};

enum class Projection : uint32_t { Perspective = 0, Orthographic = 1 };

const char* projection_name(Projection projection);

struct Camera {
  std::string name;
  Vec3 position{0, 0, 1};
  Vec3 target{0, 0, 0};
  Vec3 up{0, 1, 0};
  float vertical_fov_degrees = 45.0f;  // perspective
  // Format version 6 on (older files read the defaults).
  float aspect_ratio = 0;  // width / height of the view as authored; 0: the asset does not say
  Projection projection = Projection::Perspective;
  float orthographic_half_height = 0;  // orthographic: half the view's height in scene units
};

// Punctual lights, as Assimp reads them (glTF KHR_lights_punctual, FBX, Collada, ...) in radiometric
// units: `color` (the light's colour times its intensity) is an intensity in W/sr for point and
// spot lights and an irradiance in W/m^2 for directional ones. glTF's photometric candela and lux
// are converted at import (1/683 W per lumen).
enum class LightType : uint32_t {
  Point = PT_PUNCTUAL_POINT,
  Spot = PT_PUNCTUAL_SPOT,
  Directional = PT_PUNCTUAL_DIRECTIONAL,
};

const char* light_type_name(LightType type);

struct Light {
  std::string name;
  LightType type = LightType::Point;
  Vec3 position{0, 0, 0};    // world space (point, spot)
  Vec3 direction{0, 0, -1};  // world space, unit: the way the light shines (spot, directional)
  Vec3 color{1, 1, 1};
  float inner_cone_radians = 0;  // spot: half-angle of full intensity
  float outer_cone_radians = 0;  // spot: half-angle beyond which there is no light
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
  std::vector<Tangent> tangents;       // per vertex when a material has a normal map, or empty
  std::vector<Material> materials;
  std::vector<Texture> textures;
  std::vector<Camera> cameras;         // at least one after import (a default framing camera)
  std::vector<uint32_t> emissive_triangles;  // triangles whose material emits
  std::vector<Light> lights;           // punctual lights, or empty
  ImportStats import_stats;
  uint64_t content_hash = 0;           // set by compute_content_hash / on load
  uint64_t geometry_hash = 0;          // set by compute_geometry_hash / on load

  size_t triangle_count() const { return indices.size() / 3; }
};

// What a tree built for a scene records of it: the geometry hash and the triangle count.
struct SceneGeometry {
  uint64_t geometry_hash = 0;
  uint64_t triangles = 0;
};
inline SceneGeometry geometry_of(const Scene& scene) { return {scene.geometry_hash, scene.triangle_count()}; }

Bounds scene_bounds(const Scene& scene);

// The camera for a scene that has none (every tool uses this one): on the +Z side of the
// bounding box's centre, looking down -Z with +Y up, far enough that the bounding sphere fills
// the vertical field of view.
Camera default_camera(const Bounds& bounds);

// 64-bit XXH3 over geometry, materials, textures, cameras and lights: what a tree or image was made from.
uint64_t compute_content_hash(const Scene& scene);

// 64-bit XXH3 over positions and indices only: what a k-d tree depends on, so a scene whose
// materials, textures, lights or cameras change keeps its tree (formats/kdscene.md).
uint64_t compute_geometry_hash(const Scene& scene);

}  // namespace kdray
