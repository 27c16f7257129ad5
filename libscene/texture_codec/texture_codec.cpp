#include "texture_codec.h"

#include <kdray/util.h>

#include <OpenImageIO/filesystem.h>
#include <OpenImageIO/imageio.h>

#include <algorithm>
#include <filesystem>
#include <cmath>
#include <memory>

#include <stdlib.h>
#include <unistd.h>

namespace kdray {
namespace {

// Larger images are refused rather than allocated (256 MiB of RGBA).
constexpr uint64_t kMaxTexturePixels = uint64_t(1) << 26;

uint8_t to_byte(float value) { return static_cast<uint8_t>(std::lround(std::clamp(value, 0.0f, 1.0f) * 255.0f)); }

bool decode(OIIO::ImageInput* input, const std::string& name, Texture& texture, std::string& problem) {
  const OIIO::ImageSpec& spec = input->spec();
  const uint64_t pixels = uint64_t(std::max(spec.width, 0)) * uint64_t(std::max(spec.height, 0));
  if (pixels == 0 || spec.nchannels <= 0 || pixels > kMaxTexturePixels) {
    problem = "unsupported image size " + std::to_string(spec.width) + "x" + std::to_string(spec.height);
    return false;
  }
  const int channels = spec.nchannels;
  std::vector<float> values(pixels * channels);
  if (!input->read_image(0, 0, 0, channels, OIIO::TypeDesc::FLOAT, values.data())) {
    problem = input->geterror();
    return false;
  }
  // Float formats (EXR, HDR) hold linear values; 8- and 16-bit images are already sRGB-encoded.
  const bool linear = spec.format.is_floating_point() ||
                      OIIO::Strutil::iequals(spec.get_string_attribute("oiio:ColorSpace"), "linear");
  const int alpha_channel = spec.alpha_channel >= 0 ? spec.alpha_channel : (channels == 4 ? 3 : (channels == 2 ? 1 : -1));
  texture.name = name;
  texture.width = static_cast<uint32_t>(spec.width);
  texture.height = static_cast<uint32_t>(spec.height);
  texture.rgba.resize(pixels * 4);
  for (uint64_t p = 0; p < pixels; ++p) {
    const float* in = &values[p * channels];
    const bool grey = channels < 3;
    float rgb[3] = {in[0], grey ? in[0] : in[1], grey ? in[0] : in[2]};
    uint8_t* out = &texture.rgba[p * 4];
    for (int c = 0; c < 3; ++c) out[c] = to_byte(linear ? linear_to_srgb(rgb[c]) : rgb[c]);
    out[3] = alpha_channel >= 0 ? to_byte(in[alpha_channel]) : 255;
  }
  return true;
}

bool decode_file(const std::string& path, Texture& texture, std::string& problem) {
  auto input = OIIO::ImageInput::open(path);
  if (!input) {
    problem = OIIO::geterror();
    if (problem.empty()) problem = "cannot open";
    return false;
  }
  return decode(input.get(), path, texture, problem);
}

// Some OpenImageIO readers (TGA in 2.4, for one) cannot read through an in-memory proxy;
// those get the bytes through a temporary file.
bool decode_memory_through_file(const std::string& name, const void* data, size_t size, const std::string& extension,
                                Texture& texture, std::string& problem) {
  std::string pattern = (std::filesystem::temp_directory_path() / "kdray-texture-XXXXXX").string() + "." + extension;
  const int fd = ::mkstemps(pattern.data(), int(extension.size() + 1));
  if (fd < 0) return false;
  const bool written = ::write(fd, data, size) == ssize_t(size);
  ::close(fd);
  bool decoded = false;
  if (written) {
    auto input = OIIO::ImageInput::open(pattern);
    if (input) decoded = decode(input.get(), name, texture, problem);
    else problem = OIIO::geterror();
  }
  ::unlink(pattern.c_str());
  return decoded;
}

bool decode_memory(const std::string& name, const void* data, size_t size, const std::string& format_hint,
                   Texture& texture, std::string& problem) {
  const std::string extension = format_hint.empty() ? std::string("png") : format_hint;
  OIIO::Filesystem::IOMemReader reader(const_cast<void*>(data), size);
  OIIO::ImageSpec config;
  config.attribute("oiio:ioproxy", OIIO::TypeDesc::PTR, &reader);
  auto input = OIIO::ImageInput::open("embedded." + extension, &config);
  if (input) return decode(input.get(), name, texture, problem);
  OIIO::geterror();  // clears the proxy attempt's message
  if (decode_memory_through_file(name, data, size, extension, texture, problem)) return true;
  if (problem.empty()) problem = "cannot decode the embedded " + extension + " image";
  return false;
}

}  // namespace
}  // namespace kdray

extern "C" const kdray::TextureCodec* kdray_texture_codec() {
  static const kdray::TextureCodec codec{kdray::decode_file, kdray::decode_memory};
  return &codec;
}
