#include "texture_decoder.h"

#include "../texture_codec/texture_codec.h"

#include <dlfcn.h>

#include <cstdlib>
#include <filesystem>
#include <mutex>
#include <system_error>

namespace kdray {
namespace {

struct LoadedCodec {
  const TextureCodec* codec = nullptr;
  std::string problem;  // why it could not be loaded
};

constexpr const char* kModuleName = "kdray_texture_codec.so";

// The module lives in lib/kdray/ beside the folder of the executables: one level up when
// installed (PREFIX/bin/kdconvert, PREFIX/lib/kdray/), two in the build tree
// (build/tools/kdconvert/kdconvert, build/lib/kdray/), so a relocated or installed copy works.
// KDRAY_TEXTURE_CODEC names another module file.
std::string module_path() {
  if (const char* override_path = std::getenv("KDRAY_TEXTURE_CODEC")) return override_path;
  std::error_code error;
  const std::filesystem::path executable = std::filesystem::read_symlink("/proc/self/exe", error);
  if (!error) {
    for (const char* up : {"..", "../.."}) {
      const std::filesystem::path candidate = executable.parent_path() / up / "lib" / "kdray" / kModuleName;
      if (std::filesystem::exists(candidate, error)) return candidate.lexically_normal().string();
    }
  }
  return kModuleName;  // leaves the search to dlopen (LD_LIBRARY_PATH), whose error names the file
}

// Loaded once and kept for the life of the process.
const LoadedCodec& loaded_codec() {
  static LoadedCodec loaded;
  static std::once_flag once;
  std::call_once(once, [] {
    const std::string module_file = module_path();
    const char* path = module_file.c_str();
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
