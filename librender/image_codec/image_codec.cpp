// OpenImageIO behind the image codec interface (image_codec.h), for every format but EXR.
#include "image_codec.h"

#include <OpenImageIO/imageio.h>

namespace kdray {
namespace {

OIIO::TypeDesc type_desc(PixelType type) {
  switch (type) {
    case PixelType::UInt8:
      return OIIO::TypeDesc::UINT8;
    case PixelType::UInt32:
      return OIIO::TypeDesc::UINT;
    case PixelType::Float:
      break;
  }
  return OIIO::TypeDesc::FLOAT;
}

PixelType pixel_type(OIIO::TypeDesc type) {
  if (type == OIIO::TypeDesc::UINT8) return PixelType::UInt8;
  if (type == OIIO::TypeDesc::UINT) return PixelType::UInt32;
  return PixelType::Float;  // every other type is read as float
}

// The attributes of the types kdray writes; others are left out.
void read_attributes(const OIIO::ImageSpec& spec, std::map<std::string, ImageAttribute>& attributes) {
  for (const OIIO::ParamValue& value : spec.extra_attribs) {
    const std::string name = value.name().string();
    if (value.type() == OIIO::TypeDesc::INT) attributes[name] = int32_t(value.get_int());
    else if (value.type() == OIIO::TypeDesc::UINT) attributes[name] = uint32_t(value.get_int());
    else if (value.type() == OIIO::TypeDesc::FLOAT) attributes[name] = value.get_float();
    else if (value.type() == OIIO::TypeDesc::STRING) attributes[name] = value.get_string();
  }
}

class OiioReader : public ImageReader {
 public:
  explicit OiioReader(std::unique_ptr<OIIO::ImageInput> input) : input_(std::move(input)) {
    const OIIO::ImageSpec& spec = input_->spec();
    header_.width = spec.width;
    header_.height = spec.height;
    for (int c = 0; c < spec.nchannels; ++c) {
      header_.channel_names.push_back(c < int(spec.channelnames.size()) ? spec.channelnames[size_t(c)]
                                                                         : "channel" + std::to_string(c));
      header_.channel_types.push_back(pixel_type(spec.channelformat(c)));
    }
    header_.alpha_channel = spec.alpha_channel;
    read_attributes(spec, header_.attributes);
    header_.deep = spec.deep;
    header_.depth = spec.depth;
    header_.at_origin = spec.x == 0 && spec.y == 0 && spec.z == 0;
  }
  const ImageHeader& header() const override { return header_; }
  bool read(int first_channel, int end_channel, PixelType type, void* pixels) override {
    return input_->read_image(0, 0, first_channel, end_channel, type_desc(type), pixels);
  }
  std::string problem() override { return input_->geterror(); }

 private:
  std::unique_ptr<OIIO::ImageInput> input_;
  ImageHeader header_;
};

std::unique_ptr<ImageReader> open_image(const std::string& path, const std::string& format, std::string& problem) {
  // A named format opens by its reader alone: ImageInput::open would try every other format's
  // reader on a file that one refused, and some of them (DICOM) load hundreds of megabytes of
  // tables to look.
  std::unique_ptr<OIIO::ImageInput> input;
  if (format.empty()) {
    input = OIIO::ImageInput::open(path);
    if (!input) problem = OIIO::geterror();
  } else {
    input = OIIO::ImageInput::create(format);
    OIIO::ImageSpec opened;
    if (!input || !input->open(path, opened)) {
      problem = input ? input->geterror() : OIIO::geterror();
      input.reset();
    }
  }
  if (!input) return nullptr;
  return std::make_unique<OiioReader>(std::move(input));
}

bool write_image(const std::string& path, const ImageHeader& header, std::optional<PixelType> given,
                 const void* pixels, std::string& problem) {
  auto output = OIIO::ImageOutput::create(path);
  if (!output) {
    problem = "cannot write this image format: " + OIIO::geterror();
    return false;
  }
  const int channels = int(header.channel_names.size());
  OIIO::ImageSpec spec(header.width, header.height, channels, type_desc(header.channel_types.at(0)));
  spec.channelnames = header.channel_names;
  for (PixelType type : header.channel_types) {
    if (type != header.channel_types[0]) {
      for (PixelType each : header.channel_types) spec.channelformats.push_back(type_desc(each));
      break;
    }
  }
  spec.alpha_channel = header.alpha_channel;
  spec.z_channel = -1;
  for (const auto& [name, value] : header.attributes) {
    std::visit([&spec, &name = name](const auto& v) { spec.attribute(name, v); }, value);
  }
  const OIIO::TypeDesc given_type = given ? type_desc(*given) : OIIO::TypeDesc::UNKNOWN;
  bool ok = output->open(path, spec) && output->write_image(given_type, pixels);
  problem = ok ? std::string() : output->geterror();
  ok = output->close() && ok;
  if (!ok) problem = "cannot write image: " + (problem.empty() ? std::string("I/O error") : problem);
  return ok;
}

const ImageCodec kCodec = {open_image, write_image};

}  // namespace
}  // namespace kdray

extern "C" const kdray::ImageCodec* kdray_image_codec() { return &kdray::kCodec; }
