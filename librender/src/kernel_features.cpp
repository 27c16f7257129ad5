// What a render's kernel is built with: the PT_FEATURE_* bits of the scene and settings and their
// -D options, so that a program holds only the code its scene uses.
#include "render_internal.h"

#include <kdray/render.h>
#include <kdray/trace_opencl.h>

#include <string>
#include <utility>

namespace kdray {

uint32_t kernel_feature_bits(const Scene& scene, const RenderSettings& settings, const Camera& camera,
                             const Environment* environment) {
  uint32_t bits = 0;
  const bool uvs = !scene.uvs.empty();
  bool textures = false;
  for (const Material& m : scene.materials) {
    if (m.type == MaterialType::Mirror) bits |= PT_FEATURE_MIRROR;
    if (m.type == MaterialType::RoughConductor) bits |= PT_FEATURE_GLOSSY;
    if (m.type == MaterialType::Dielectric) bits |= PT_FEATURE_GLASS;
    if (m.type == MaterialType::MetallicRoughness) bits |= PT_FEATURE_METALLIC_ROUGHNESS;
    if (m.alpha_mode != AlphaMode::Opaque) bits |= PT_FEATURE_ALPHA;
    if (!uvs) continue;
    textures |= m.diffuse_texture >= 0 || m.metal_rough_texture >= 0 || m.normal_texture >= 0 || m.emissive_texture >= 0;
    if (m.metal_rough_texture >= 0) bits |= PT_FEATURE_METAL_ROUGH_TEXTURE;
    if (m.normal_texture >= 0) bits |= PT_FEATURE_NORMAL_MAP;
    if (m.emissive_texture >= 0 && !scene.emissive_triangles.empty()) bits |= PT_FEATURE_EMISSIVE_TEXTURE;
  }
  if (textures) bits |= PT_FEATURE_TEXTURES;
  if (!scene.emissive_triangles.empty()) bits |= PT_FEATURE_EMISSION;
  if (!scene.normals.empty()) bits |= PT_FEATURE_NORMALS;
  if (environment) bits |= PT_FEATURE_ENVIRONMENT;
  if (!scene.lights.empty()) bits |= PT_FEATURE_PUNCTUAL;
  if (!settings.mis) bits |= PT_FEATURE_MIS_OFF;
  if (camera.projection == Projection::Orthographic) bits |= PT_FEATURE_ORTHOGRAPHIC;
  return bits;
}

std::string kernel_feature_options(uint32_t feature_bits, const DeviceSelection& device, bool gpu) {
  static const std::pair<uint32_t, const char*> kDefines[] = {
      {PT_FEATURE_EMISSION, "KD_FEATURE_EMISSION"},
      {PT_FEATURE_MIRROR, "KD_FEATURE_MIRROR"},
      {PT_FEATURE_GLOSSY, "KD_FEATURE_GLOSSY"},
      {PT_FEATURE_GLASS, "KD_FEATURE_GLASS"},
      {PT_FEATURE_METALLIC_ROUGHNESS, "KD_FEATURE_METALLIC_ROUGHNESS"},
      {PT_FEATURE_ALPHA, "KD_FEATURE_ALPHA"},
      {PT_FEATURE_TEXTURES, "KD_FEATURE_TEXTURES"},
      {PT_FEATURE_METAL_ROUGH_TEXTURE, "KD_FEATURE_METAL_ROUGH_TEXTURE"},
      {PT_FEATURE_NORMAL_MAP, "KD_FEATURE_NORMAL_MAP"},
      {PT_FEATURE_EMISSIVE_TEXTURE, "KD_FEATURE_EMISSIVE_TEXTURE"},
      {PT_FEATURE_NORMALS, "KD_FEATURE_NORMALS"},
      {PT_FEATURE_ENVIRONMENT, "KD_FEATURE_ENVIRONMENT"},
      {PT_FEATURE_PUNCTUAL, "KD_FEATURE_PUNCTUAL"},
      {PT_FEATURE_MIS_OFF, "KD_MIS_OFF"},
      {PT_FEATURE_ORTHOGRAPHIC, "KD_FEATURE_ORTHOGRAPHIC"},
  };
  std::string options = "-cl-std=CL1.2";
  for (const auto& [bit, name] : kDefines)
    if (feature_bits & bit) options += std::string(" -D") + name;
  // On a CPU a work-item's vector registers are free lanes; on a GPU the lanes are work-items.
  if (!gpu) options += kBounceBitsInLanesOption;
  return options + traversal_build_options(device, gpu);
}

std::string kernel_feature_options(const Scene& scene, const RenderSettings& settings, const DeviceSelection& device,
                                   bool gpu) {
  const Camera camera = render_camera(scene, settings);
  const uint32_t bits = kernel_feature_bits(scene, settings, camera, render_environment(scene, settings).get());
  return kernel_feature_options(bits, device, gpu);
}

}  // namespace kdray
