// Small synthetic images written with OpenImageIO directly (not through the code under test).
#pragma once

#include <OpenImageIO/imageio.h>

#include <filesystem>
#include <stdexcept>
#include <string>
#include <vector>

namespace kdray::test {

// Writes interleaved float pixels; the file format follows the extension (EXR stores `exr_type`,
// PNG 8 bits).
inline void write_test_image(const std::filesystem::path& path, int width, int height,
                             const std::vector<std::string>& channels, const std::vector<float>& pixels,
                             OIIO::TypeDesc exr_type = OIIO::TypeDesc::FLOAT) {
  const bool eight_bit = path.extension() == ".png";
  OIIO::ImageSpec spec(width, height, int(channels.size()), eight_bit ? OIIO::TypeDesc::UINT8 : exr_type);
  spec.channelnames = channels;
  for (size_t c = 0; c < channels.size(); ++c) {
    if (channels[c] == "A") spec.alpha_channel = int(c);
  }
  auto output = OIIO::ImageOutput::create(path.string());
  if (!output || !output->open(path.string(), spec) || !output->write_image(OIIO::TypeDesc::FLOAT, pixels.data()) ||
      !output->close()) {
    throw std::runtime_error("cannot write test image " + path.string());
  }
}

// width x height pixels, every pixel the same channel values.
inline std::vector<float> constant_pixels(int width, int height, const std::vector<float>& value) {
  std::vector<float> pixels;
  for (int i = 0; i < width * height; ++i) pixels.insert(pixels.end(), value.begin(), value.end());
  return pixels;
}

}  // namespace kdray::test
