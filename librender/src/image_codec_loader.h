// The image codec for a path: OpenEXR (exr_codec.h, linked in) for .exr, and for every other
// format the module (image_codec/, OpenImageIO), loaded once: on first use, or ahead of it on a
// thread of its own. image_io.cpp, image_compare.cpp and environment_image.cpp are its users;
// this header knows nothing of image_io.h, so the two do not include each other.
#pragma once

#include "../image_codec/image_codec.h"

#include <string>

namespace kdray {

// The codec that reads and writes `path`, by its extension; throws kdray::Error naming `path`
// when that is the module and it cannot be loaded.
const ImageCodec& image_codec(const std::string& path);

// Starts loading the module on a thread of its own when `path` is read or written by it, unless
// a load has started (preload_image_io).
void start_loading_image_codec(const std::string& path);

}  // namespace kdray
