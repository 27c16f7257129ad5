// Mapping the material descriptions of MTL files and of Assimp's material keys onto kdray's
// small set of material types. The rules are written out in formats/kdscene.md.
#pragma once

#include <kdray/scene.h>

#include <optional>
#include <string>

namespace kdray {

// What a source material says, in MTL terms; PBR sources fill metallic/roughness too.
struct SourceMaterial {
  std::string name;
  Vec3 diffuse{0.8f, 0.8f, 0.8f};  // Kd, or the PBR base colour
  Vec3 specular{0, 0, 0};          // Ks
  Vec3 emission{0, 0, 0};          // Ke
  float shininess = 0;             // Ns (Phong exponent)
  float ior = 1.0f;                // Ni
  float opacity = 1.0f;            // d (1 - Tr)
  float transmission = 0;          // PBR transmission factor
  int illum = 2;                   // MTL illumination model
  std::optional<float> metallic;   // PBR metallic factor, when the source has one
  std::optional<float> roughness;  // PBR perceptual roughness
  std::string diffuse_texture;     // path or embedded-texture reference; empty if none
  std::string metal_rough_texture;  // glTF metallic-roughness texture
  std::string normal_texture;
  std::string emissive_texture;
  // glTF sources name an alpha mode; their opacity is then the base colour's alpha, not glass.
  std::optional<AlphaMode> alpha_mode;
  float alpha_cutoff = 0.5f;
};

Material map_material(const SourceMaterial& source);

}  // namespace kdray
