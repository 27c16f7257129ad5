// The cereal portable-binary encoding of the structured .kdscene sections (materials,
// cameras, textures, scene info), shared by the file writer and the content hash so both
// see exactly the same bytes. The byte layout is specified in formats/kdscene.md.
#pragma once

#include <kdray/scene.h>

#include <string>
#include <vector>

namespace kdray::encoding {

// The structured parts that are content (they enter the content hash).
struct EncodedParts {
  std::string materials, textures, cameras, lights;
};
EncodedParts encode_parts(const Scene& scene);

std::string encode_materials(const std::vector<Material>& materials);
std::string encode_cameras(const std::vector<Camera>& cameras);
std::string encode_textures(const std::vector<Texture>& textures);
std::string encode_lights(const std::vector<Light>& lights);
// Scene info: the content hash again (inside the checksummed payload, so a damaged header
// hash is caught without recomputing it), the geometry hash (format version 4 on) and the
// import statistics.
struct SceneInfo {
  uint64_t content_hash = 0;
  uint64_t geometry_hash = 0;  // 0 when read from a file older than version 4
  ImportStats import_stats;
};
std::string encode_scene_info(const SceneInfo& info);

// Decoders throw kdray::Error naming `path` when the bytes are malformed. Every element
// count is checked against the bytes that remain before anything is allocated.
std::vector<Material> decode_materials(const std::string& path, const std::vector<char>& bytes, uint32_t version);
std::vector<Camera> decode_cameras(const std::string& path, const std::vector<char>& bytes, uint32_t version);
std::vector<Texture> decode_textures(const std::string& path, const std::vector<char>& bytes);
std::vector<Light> decode_lights(const std::string& path, const std::vector<char>& bytes);
SceneInfo decode_scene_info(const std::string& path, const std::vector<char>& bytes, uint32_t version);

}  // namespace kdray::encoding
