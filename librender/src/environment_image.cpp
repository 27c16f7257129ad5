// Environment maps from image files, through OpenImageIO (see environment.h). Kept apart from
// the sampling table so that tools which only upload scenes (kdtrace) do not link OpenImageIO,
// whose some 250 shared libraries cost about 0.2 s at every start.
#include <kdray/environment.h>
#include <kdray/error.h>

#include <OpenImageIO/imageio.h>

#include <cmath>

namespace kdray {
namespace {

// Large enough for 16k x 8k maps, small enough that a hostile header cannot ask for 100 GB.
constexpr uint64_t kMaxEnvironmentPixels = uint64_t(1) << 28;

}  // namespace

Environment load_environment(const std::string& path) {
  auto in = OIIO::ImageInput::open(path);
  if (!in) throw Error(path, "cannot read the environment image: " + OIIO::geterror());
  const OIIO::ImageSpec& spec = in->spec();
  if (spec.width <= 0 || spec.height <= 0 || spec.nchannels <= 0 || spec.depth > 1) {
    throw Error(path, "not a 2D image");
  }
  const uint64_t pixels = uint64_t(spec.width) * uint64_t(spec.height);
  if (pixels > kMaxEnvironmentPixels) {
    throw Error(path, "environment image of " + std::to_string(spec.width) + "x" + std::to_string(spec.height) +
                          " pixels is too large");
  }
  Environment env;
  env.source = path;
  env.width = uint32_t(spec.width);
  env.height = uint32_t(spec.height);
  // Read straight into place: a 4k x 2k map is 100 MB of floats, so no extra copies.
  const int channels = spec.nchannels >= 3 ? 3 : 1;
  env.rgb.resize(pixels * 3);
  if (!in->read_image(0, 0, 0, channels, OIIO::TypeDesc::FLOAT, env.rgb.data())) {
    throw Error(path, "cannot read the environment image: " + in->geterror());
  }
  in->close();
  if (channels == 1) {
    for (uint64_t i = pixels; i-- > 0;) env.rgb[3 * i] = env.rgb[3 * i + 1] = env.rgb[3 * i + 2] = env.rgb[i];
  }
  for (float& value : env.rgb) value = std::isfinite(value) && value > 0 ? value : 0.0f;  // finite, >= 0
  return env;
}

}  // namespace kdray
