// TextureCache (importers.h): each distinct texture decoded once per import.
#include "importers.h"
#include "texture_decoder.h"

#include <algorithm>

namespace kdray {

template <typename Decode>
int32_t TextureCache::cached(const std::string& key, Decode decode) {
  auto found = index_of_.find(key);
  if (found != index_of_.end()) return found->second;
  std::string problem;
  std::optional<Texture> texture = decode(problem);
  int32_t index = -1;
  if (texture) {
    scene_.textures.push_back(std::move(*texture));
    index = int32_t(scene_.textures.size() - 1);
  } else {
    scene_.import_stats.warnings.push_back("texture " + key + " not used: " + problem);
  }
  index_of_.emplace(key, index);
  return index;
}

int32_t TextureCache::from_file(const std::string& written_path, const std::string& reference) {
  std::string path = written_path;
  std::replace(path.begin(), path.end(), '\\', '/');  // Windows exporters write backslashes
  return cached(path, [&](std::string& problem) {
    std::optional<Texture> texture = decode_texture_file(path, problem);
    if (texture) texture->name = reference;
    return texture;
  });
}

int32_t TextureCache::from_memory(const std::string& key, const void* data, size_t size, const std::string& format_hint) {
  return cached(key, [&](std::string& problem) { return decode_texture_memory(key, data, size, format_hint, problem); });
}

int32_t TextureCache::from_texels(const std::string& key, const std::function<Texture()>& convert) {
  return cached(key, [&](std::string&) { return std::optional<Texture>(convert()); });
}

}  // namespace kdray
