// What a glTF 2.0 file says that Assimp 5.2.5 does not carry over, read from the file's own JSON
// beside Assimp's import: the cameras' exact angles, aspect ratios and projections (Assimp keeps
// yfov x aspect, a linear product, and drops orthographic cameras' extents), the materials'
// KHR_materials_emissive_strength, and the extensions the asset uses.
#pragma once

#include <optional>
#include <string>
#include <vector>

namespace kdray {

bool is_gltf_path(const std::string& path);

struct GltfCamera {
  bool orthographic = false;
  float yfov_radians = 0;  // perspective: the full vertical angle
  float aspect_ratio = 0;  // perspective: width / height, 0 where the file leaves it out
  float xmag = 0, ymag = 0;  // orthographic: half the view's width and height
};

// Assimp's glTF importer keeps the file's order of cameras and materials (its own default
// material, when it adds one, comes last), so index i here is Assimp's index i.
struct GltfFacts {
  std::vector<GltfCamera> cameras;
  std::vector<float> emissive_strength;  // per material: KHR_materials_emissive_strength, else 1
  std::vector<std::string> extensions_used;
};

// Reads a .gltf (JSON text) or .glb (the JSON chunk); nothing for glTF 1.0 files, whose cameras,
// materials and lights are laid out otherwise. Throws kdray::Error naming the file when the JSON
// cannot be read.
std::optional<GltfFacts> read_gltf_facts(const std::string& path);

// The extensions among `used` that kdray does not model, so conversion can name each of them.
std::vector<std::string> unmodelled_gltf_extensions(const std::vector<std::string>& used);

}  // namespace kdray
