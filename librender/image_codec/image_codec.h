// The image codec interface, of plain data, and the entry point of the image codec module:
// OpenImageIO behind it, in a shared library that librender loads with dlopen
// (src/image_codec_loader.cpp), so that only the tools which read or write images other than EXR
// load OpenImageIO's some 250 libraries, and kdrender loads them while it renders. EXR files go
// through OpenEXR behind the same interface (src/exr_codec.h), linked into librender: EXR is what
// kdrender writes for each frame and what kdcompare and kdrender --merge read back, and OpenEXR
// loads in milliseconds. Both sides are built together, so C++ types may cross.
#pragma once

#include <cstdint>
#include <map>
#include <memory>
#include <optional>
#include <string>
#include <variant>
#include <vector>

namespace kdray {

enum class PixelType : uint8_t { UInt8, UInt32, Float };

// A metadata value of the types kdray writes and reads.
using ImageAttribute = std::variant<int32_t, uint32_t, float, std::string>;

struct ImageHeader {
  int width = 0, height = 0;
  std::vector<std::string> channel_names;
  std::vector<PixelType> channel_types;  // one per channel, as stored
  int alpha_channel = -1;                // index into channel_names, or -1
  std::map<std::string, ImageAttribute> attributes;
  // Read only: a deep image, a volume (depth > 1), a data window away from the origin.
  bool deep = false;
  int depth = 1;
  bool at_origin = true;
};

class ImageReader {
 public:
  virtual ~ImageReader() = default;
  virtual const ImageHeader& header() const = 0;
  // Channels [first, end) of every pixel, interleaved, rows top to bottom, converted to `type`;
  // false when they cannot be read (problem() says why).
  virtual bool read(int first_channel, int end_channel, PixelType type, void* pixels) = 0;
  virtual std::string problem() = 0;
};

struct ImageCodec {
  // Opens an image by the reader of `format` alone ("exr"), or, when it is empty, by whichever
  // reader takes the file. nullptr, with `problem` set, when none does.
  std::unique_ptr<ImageReader> (*open)(const std::string& path, const std::string& format, std::string& problem);
  // Writes interleaved pixels to `path` in the format its extension names: given as `given`, or,
  // without it, each channel in its stored type. false, with `problem` set, on failure.
  bool (*write)(const std::string& path, const ImageHeader& header, std::optional<PixelType> given,
                const void* pixels, std::string& problem);
};

}  // namespace kdray

// Returns the module's codec; looked up by this name.
extern "C" const kdray::ImageCodec* kdray_image_codec();
