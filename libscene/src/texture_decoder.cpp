#include "texture_decoder.h"

#include "../texture_codec/texture_codec.h"

#include <kdray/module.h>

namespace kdray {
namespace {

struct LoadedCodec {
  const TextureCodec* codec = nullptr;
  std::string problem;  // why it could not be loaded
};

// Loaded once and kept for the life of the process (kdray/module.h); KDRAY_TEXTURE_CODEC names
// another module file.
const LoadedCodec& loaded_codec() {
  static const LoadedCodec loaded = [] {
    LoadedCodec codec;
    std::string problem;
    using Entry = const TextureCodec* (*)();
    auto entry = reinterpret_cast<Entry>(
        load_module_symbol("kdray_texture_codec.so", "KDRAY_TEXTURE_CODEC", "kdray_texture_codec", problem));
    if (entry == nullptr)
      codec.problem = "texture decoding is unavailable: " + problem;
    else
      codec.codec = entry();
    return codec;
  }();
  return loaded;
}

template <typename Decode>
std::optional<Texture> with_codec(std::string& problem, Decode decode) {
  const LoadedCodec& loaded = loaded_codec();
  if (loaded.codec == nullptr) {
    problem = loaded.problem;
    return std::nullopt;
  }
  Texture texture;
  if (!decode(*loaded.codec, texture)) return std::nullopt;
  return texture;
}

}  // namespace

std::optional<Texture> decode_texture_file(const std::string& path, std::string& problem) {
  return with_codec(problem, [&](const TextureCodec& codec, Texture& texture) {
    return codec.decode_file(path, texture, problem);
  });
}

std::optional<Texture> decode_texture_memory(const std::string& name, const void* data, size_t size,
                                             const std::string& format_hint, std::string& problem) {
  return with_codec(problem, [&](const TextureCodec& codec, Texture& texture) {
    return codec.decode_memory(name, data, size, format_hint, texture, problem);
  });
}

}  // namespace kdray
