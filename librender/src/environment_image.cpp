// Environment maps from image files, through the image codecs (see environment.h).
#include "image_codec_loader.h"

#include <kdray/environment.h>
#include <kdray/error.h>

#include <cmath>

namespace kdray {
namespace {

// Large enough for 16k x 8k maps, small enough that a hostile header cannot ask for 100 GB.
constexpr uint64_t kMaxEnvironmentPixels = uint64_t(1) << 28;

}  // namespace

Environment load_environment(const std::string& path) {
  std::string problem;
  std::unique_ptr<ImageReader> in = image_codec(path).open(path, "", problem);
  if (!in) throw Error(path, "cannot read the environment image: " + problem);
  const ImageHeader& header = in->header();
  if (header.width <= 0 || header.height <= 0 || header.channel_names.empty() || header.depth > 1) {
    throw Error(path, "not a 2D image");
  }
  const uint64_t pixels = uint64_t(header.width) * uint64_t(header.height);
  if (pixels > kMaxEnvironmentPixels) {
    throw Error(path, "environment image of " + std::to_string(header.width) + "x" + std::to_string(header.height) +
                          " pixels is too large");
  }
  Environment env;
  env.source = path;
  env.width = uint32_t(header.width);
  env.height = uint32_t(header.height);
  // Read straight into place: a 4k x 2k map is 100 MB of floats, so no extra copies.
  const int channels = header.channel_names.size() >= 3 ? 3 : 1;
  env.rgb.resize(pixels * 3);
  if (!in->read(0, channels, PixelType::Float, env.rgb.data())) {
    throw Error(path, "cannot read the environment image: " + in->problem());
  }
  in.reset();
  if (channels == 1) {
    for (uint64_t i = pixels; i-- > 0;) env.rgb[3 * i] = env.rgb[3 * i + 1] = env.rgb[3 * i + 2] = env.rgb[i];
  }
  for (float& value : env.rgb) value = std::isfinite(value) && value > 0 ? value : 0.0f;  // finite, >= 0
  return env;
}

}  // namespace kdray
