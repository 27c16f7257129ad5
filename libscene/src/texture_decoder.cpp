#include "texture_decoder.h"

#include "../texture_codec/texture_codec.h"

#include <dlfcn.h>

#include <cstdlib>
#include <mutex>

namespace kdray {
namespace {

struct LoadedCodec {
  const TextureCodec* codec = nullptr;
  std::string problem;  // why it could not be loaded
};

// Loaded once and kept for the life of the process. KDRAY_TEXTURE_CODEC overrides the
// build-tree path compiled in by CMake.
const LoadedCodec& loaded_codec() {
  static LoadedCodec loaded;
  static std::once_flag once;
  std::call_once(once, [] {
    const char* override_path = std::getenv("KDRAY_TEXTURE_CODEC");
    const char* path = override_path != nullptr ? override_path : KDRAY_TEXTURE_CODEC_PATH;
    void* module = ::dlopen(path, RTLD_NOW | RTLD_LOCAL);
    if (module == nullptr) {
      loaded.problem = std::string("texture decoding is unavailable: ") + ::dlerror();
      return;
    }
    using Entry = const TextureCodec* (*)();
    auto entry = reinterpret_cast<Entry>(::dlsym(module, "kdray_texture_codec"));
    if (entry == nullptr) {
      loaded.problem = std::string("texture decoding is unavailable: ") + path + " has no kdray_texture_codec";
      return;
    }
    loaded.codec = entry();
  });
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
