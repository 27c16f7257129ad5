// EXR files through the OpenEXR library, linked into librender: the image codec
// (image_codec.h) for every path ending in .exr. EXR is what kdrender writes for each frame and
// what kdcompare and kdrender --merge read back; OpenEXR loads in milliseconds, where the
// OpenImageIO module's libraries take about 0.3 s of CPU to load.
#pragma once

#include "../image_codec/image_codec.h"

namespace kdray {

// Reads channels in the order OpenImageIO presented them (R, G, B, then A, Z and the rest of
// each layer; layers by name), so that readers which take channels [0, 3) as colour keep working.
const ImageCodec& exr_codec();

}  // namespace kdray
