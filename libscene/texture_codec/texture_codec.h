// The entry point of the texture codec module (a shared library loaded with dlopen by
// libscene/src/texture_decoder.cpp). Both sides are built together, so C++ types may cross.
#pragma once

#include <kdray/scene.h>

#include <cstddef>
#include <string>

namespace kdray {

struct TextureCodec {
  bool (*decode_file)(const std::string& path, Texture& texture, std::string& problem);
  bool (*decode_memory)(const std::string& name, const void* data, size_t size, const std::string& format_hint,
                        Texture& texture, std::string& problem);
};

}  // namespace kdray

// Returns the module's codec; looked up by this name.
extern "C" const kdray::TextureCodec* kdray_texture_codec();
