// A scene's content hash from its structured parts already encoded, which the file writer
// shares so that it encodes them once (scene_file.cpp); compute_content_hash and
// compute_geometry_hash (kdray/scene.h) are defined beside it, in scene_hash.cpp.
#pragma once

#include "scene_encoding.h"

#include <kdray/scene.h>

#include <cstdint>

namespace kdray::encoding {

uint64_t content_hash(const Scene& scene, const EncodedParts& parts);

}  // namespace kdray::encoding
