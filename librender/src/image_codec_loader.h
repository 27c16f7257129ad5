// The image codec module (image_codec/), loaded once: on first use, or ahead of it on a thread of
// its own (preload_image_io in image_io.h).
#pragma once

#include "../image_codec/image_codec.h"

#include <string>

namespace kdray {

// The codec; throws kdray::Error naming `path` (the file about to be read or written) when the
// module cannot be loaded.
const ImageCodec& image_codec(const std::string& path);

}  // namespace kdray
