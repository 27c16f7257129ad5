// The two importers behind import_scene (import.cpp), and what they share. Each returns the
// asset's geometry, materials, textures and cameras as found; import.cpp then applies the
// user's options, lists emissive triangles and adds a default camera.
#pragma once

#include <kdray/scene.h>

#include <cstdint>
#include <functional>
#include <map>
#include <string>

namespace kdray {

Scene import_with_tinyobj(const std::string& path);
Scene import_with_assimp(const std::string& path);

// Runs `importer` in a child process and returns its scene; the child's death (an abort or a
// crash inside a third-party importer, the kernel killing it for memory, or a CPU time limit
// that grows with the file's size) becomes a kdray::Error naming `path` and `importer_name`,
// and the importer's own errors pass through. `max_memory` (bytes, 0: none) limits the
// child's address space beyond what the process already holds.
Scene import_in_child_process(const std::string& path, Scene (*importer)(const std::string&),
                              const char* importer_name, uint64_t max_memory);

// Decodes each distinct texture once and appends it to scene.textures; unreadable textures
// become warnings in scene.import_stats and index -1.
class TextureCache {
 public:
  explicit TextureCache(Scene& scene) : scene_(scene) {}
  // `reference` is the name as the material writes it; it names the texture in the scene, so
  // the content hash does not depend on where the asset was converted.
  int32_t from_file(const std::string& path, const std::string& reference);
  int32_t from_memory(const std::string& key, const void* data, size_t size, const std::string& format_hint);
  // A texture the asset holds as raw texels: `convert` makes the scene's texture on first use.
  int32_t from_texels(const std::string& key, const std::function<Texture()>& convert);

 private:
  template <typename Decode>
  int32_t cached(const std::string& key, Decode decode);

  Scene& scene_;
  std::map<std::string, int32_t> index_of_;
};

}  // namespace kdray
