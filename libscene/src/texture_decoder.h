// Decoding diffuse textures into the scene's 8-bit sRGB RGBA form. The decoding itself
// (OpenImageIO) lives in a module loaded on first use (texture_codec/): OpenImageIO pulls in
// some 250 shared libraries whose loading costs about 0.25 s, which every tool and every
// conversion of an untextured asset would otherwise pay at startup.
#pragma once

#include <kdray/scene.h>

#include <cstddef>
#include <optional>
#include <string>

namespace kdray {

// From an image file. On failure returns nullopt and sets `problem` (a missing or unreadable
// texture is a warning for the importer, not an error).
std::optional<Texture> decode_texture_file(const std::string& path, std::string& problem);

// From an image file held in memory (an asset's embedded texture); `format_hint` is a file
// extension such as "png".
std::optional<Texture> decode_texture_memory(const std::string& name, const void* data, size_t size,
                                             const std::string& format_hint, std::string& problem);

}  // namespace kdray
