// Importing assets into the scene model: OBJ through tinyobjloader, everything else Assimp
// reads through Assimp.
#pragma once

#include <kdray/scene.h>

#include <cstdint>
#include <string>

namespace kdray {

enum class Importer { Auto, Assimp, TinyObj };
enum class UpAxis { Y, Z };  // Z: the source is Z-up and is rotated to kdray's Y-up

struct ImportOptions {
  Importer importer = Importer::Auto;
  float scale = 1.0f;
  UpAxis up_axis = UpAxis::Y;
  std::string camera;  // name or index of the asset camera to put first; empty: the asset's first
  // Memory budget in bytes (0: none): an import whose estimate exceeds it is refused, and an
  // importer run in its own process cannot allocate beyond it.
  uint64_t max_memory = 0;
};

// Throws kdray::Error naming `path` when the file cannot be read or holds no triangles.
Scene import_scene(const std::string& path, const ImportOptions& options);

}  // namespace kdray
