#include "material_mapping.h"

#include <algorithm>
#include <cmath>

namespace kdray {
namespace {

float max_component(const Vec3& v) { return std::max({v.x, v.y, v.z}); }
float luminance(const Vec3& v) { return 0.2126f * v.x + 0.7152f * v.y + 0.0722f * v.z; }

// Below this GGX alpha a surface is rendered as a perfect mirror.
constexpr float kMirrorAlpha = 0.05f;
constexpr float kDefaultGlassIor = 1.5f;

bool is_mtl_glass_model(int illum) { return illum == 4 || illum == 6 || illum == 7 || illum == 9; }
bool is_mtl_mirror_model(int illum) { return illum == 3 || illum == 5 || illum == 8; }

}  // namespace

Material map_material(const SourceMaterial& source) {
  Material material;
  material.name = source.name;
  material.base_color = source.diffuse;
  if (max_component(source.emission) > 0) {
    material.type = MaterialType::Emissive;
    material.emission = source.emission;
    return material;
  }
  material.ior = source.ior > 1.0f ? source.ior : kDefaultGlassIor;
  if (source.alpha_mode) {
    material.alpha_mode = *source.alpha_mode;
    material.alpha = std::clamp(source.opacity, 0.0f, 1.0f);
    material.alpha_cutoff = source.alpha_cutoff;
  }
  const bool see_through = source.alpha_mode ? false : source.opacity < 1.0f;
  if (see_through || source.transmission > 0 || is_mtl_glass_model(source.illum)) {
    material.type = MaterialType::Dielectric;
    material.base_color = {1, 1, 1};
    return material;
  }
  if (source.metallic) {  // PBR metal/roughness source
    const float perceptual = std::clamp(source.roughness.value_or(1.0f), 0.0f, 1.0f);
    material.roughness = perceptual * perceptual;
    // A smooth metal is a mirror; every other PBR material, rough metals included, follows the
    // specification's BRDF (whose height-correlated masking the rough conductor does not share).
    if (*source.metallic >= 1.0f && source.metal_rough_texture.empty() && material.roughness < kMirrorAlpha) {
      material.type = MaterialType::Mirror;
      return material;
    }
    material.type = MaterialType::MetallicRoughness;
    material.metallic = std::clamp(*source.metallic, 0.0f, 1.0f);
    return material;
  }
  // Phong-style source: specular-dominated surfaces become conductors, with the Phong
  // exponent converted to a GGX alpha (Walter et al. 2007: alpha = sqrt(2 / (Ns + 2))).
  const bool specular_dominated = max_component(source.specular) > 0 &&
                                  (is_mtl_mirror_model(source.illum) || luminance(source.specular) > luminance(source.diffuse));
  if (!specular_dominated) return material;
  material.base_color = source.specular;
  material.roughness = std::sqrt(2.0f / (std::max(source.shininess, 0.0f) + 2.0f));
  material.type = material.roughness < kMirrorAlpha ? MaterialType::Mirror : MaterialType::RoughConductor;
  return material;
}

}  // namespace kdray
