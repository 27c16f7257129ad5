// Writing rendered films (EXR, PNG, JPEG) and reading kdrender EXRs back for merging.
#pragma once

#include <kdray/film.h>

#include <cstdint>
#include <optional>
#include <string>
#include <utility>

namespace kdray {

// By extension: .exr is linear float with the AOV layers, the exact fixed-point sums (channels
// "kdray.sum.<channel>.hi/.lo", uint32) and metadata (kdray:spp, kdray:sample_offset, kdray:seed,
// kdray:max_bounces, kdray:seconds, kdray:scene_hash, kdray:tree_hash,
// kdray:settings_hash); .png/.jpg/.jpeg are
// 8-bit sRGB of the radiance, clamped. Written to a temporary name in the same directory and
// renamed into place. Throws kdray::Error.
void write_film_image(const std::string& path, const Film& film);

// Reads an EXR written by write_film_image, sums included. Throws kdray::Error.
Film read_film_exr(const std::string& path);

// The width and height of an image (EXR, or any format OpenImageIO reads); nullopt when it cannot
// be opened.
std::optional<std::pair<uint32_t, uint32_t>> read_image_size(const std::string& path);

// True when write_film_image knows the extension of path.
bool is_supported_image_path(const std::string& path);

// EXR files are read and written by OpenEXR, linked in; every other format by a module loaded on
// first use (OpenImageIO: some 250 shared libraries, about 0.3 s of CPU to load). For a `path`
// of another format this starts loading the module on a thread of its own, so that a program can
// have it ready by the time it writes; for an EXR it does nothing. Not while another thread loads
// libraries: glibc runs one dlopen at a time, so that one would wait.
void preload_image_io(const std::string& path);

}  // namespace kdray
