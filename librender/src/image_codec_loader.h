// The image codec module (image_codec/), loaded once: on first use, or ahead of it on a thread of
// its own. image_io.cpp is its one user; this header knows nothing of image_io.h, so the two do
// not include each other.
#pragma once

#include "../image_codec/image_codec.h"

#include <string>

namespace kdray {

// The codec; throws kdray::Error naming `path` (the file about to be read or written) when the
// module cannot be loaded.
const ImageCodec& image_codec(const std::string& path);

// Starts loading the module on a thread of its own, unless a load has started (preload_image_io).
void start_loading_image_codec();

}  // namespace kdray
