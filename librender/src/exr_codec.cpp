// OpenEXR behind the image codec interface (exr_codec.h).
#include "exr_codec.h"

#include <OpenEXR/ImfChannelList.h>
#include <OpenEXR/ImfFloatAttribute.h>
#include <OpenEXR/ImfFrameBuffer.h>
#include <OpenEXR/ImfHeader.h>
#include <OpenEXR/ImfInputFile.h>
#include <OpenEXR/ImfIntAttribute.h>
#include <OpenEXR/ImfOutputFile.h>
#include <OpenEXR/ImfPartType.h>
#include <OpenEXR/ImfStdIO.h>
#include <OpenEXR/ImfStringAttribute.h>
#include <OpenEXR/ImfThreading.h>

#include <algorithm>
#include <cctype>
#include <cerrno>
#include <cstring>
#include <exception>
#include <fstream>
#include <map>
#include <numeric>
#include <stdexcept>
#include <string_view>
#include <thread>
#include <tuple>

namespace kdray {
namespace {

// Runs `work`; false, with `problem` set, when it throws. OpenEXR reports every failure, a
// damaged or truncated file included, by exception (Iex::BaseExc derives from std::exception).
template <typename Work>
bool guarded(std::string& problem, Work&& work) {
  try {
    work();
    return true;
  } catch (const std::exception& error) {
    problem = error.what();
  } catch (...) {
    problem = "unknown error in OpenEXR";
  }
  return false;
}

// Line blocks are compressed and decompressed on every core, as OpenImageIO's EXR reader and
// writer did: ZIP is most of the time of reading or writing a large film. OpenEXR runs a file's
// blocks on its global thread pool, which is made here once.
int exr_threads() {
  static const int threads = [] {
    const int count = int(std::max(1u, std::thread::hardware_concurrency()));
    Imf::setGlobalThreadCount(count);
    return count;
  }();
  return threads;
}

// Both kdray pixel types OpenEXR stores are 4 bytes; it has no 8-bit channels.
constexpr size_t kChannelBytes = 4;

Imf::PixelType exr_type(PixelType type) {
  if (type == PixelType::UInt8) throw std::invalid_argument("EXR has no 8-bit channels");
  return type == PixelType::UInt32 ? Imf::UINT : Imf::FLOAT;
}

// HALF channels are read as float, as OpenImageIO read them.
PixelType pixel_type(Imf::PixelType type) { return type == Imf::UINT ? PixelType::UInt32 : PixelType::Float; }

// Compares ASCII letters regardless of case, as OpenImageIO matches channel names.
bool same_name(std::string_view a, std::string_view b) {
  return a.size() == b.size() && std::equal(a.begin(), a.end(), b.begin(), [](char x, char y) {
           return std::tolower(static_cast<unsigned char>(x)) == std::tolower(static_cast<unsigned char>(y));
         });
}

// OpenImageIO's order of the usual channel names within a layer; a layer with X and Y or Z (a
// position or a normal) takes the second, which keeps X, Y, Z together. Other names come after
// these, by name.
constexpr std::string_view kUsualOrder[] = {"R",  "Red", "G",  "Green", "B",  "Blue", "Y",
                                            "real", "imag", "A", "Alpha", "AR", "RA", "AG",
                                            "GA", "AB",  "BA", "Z",     "Depth", "Zback"};
constexpr std::string_view kVectorOrder[] = {"R",  "Red", "G",  "Green", "B",  "Blue", "X",
                                             "Y",  "Z",   "real", "imag", "A",  "Alpha", "AR",
                                             "RA", "AG",  "GA", "AB",    "BA", "Depth", "Zback"};

template <size_t N>
int rank_in(const std::string_view (&order)[N], std::string_view suffix) {
  return int(std::find_if(order, order + N, [suffix](std::string_view usual) { return same_name(usual, suffix); }) -
             order);
}

struct ChannelName {
  std::string_view layer;   // up to and including the last dot; empty without one
  std::string_view suffix;  // after the last dot
};

ChannelName split_name(std::string_view name) {
  const size_t dot = name.find_last_of('.');
  if (dot == std::string_view::npos) return {{}, name};
  return {name.substr(0, dot + 1), name.substr(dot + 1)};
}

// The names of the file's channels (which OpenEXR keeps sorted by name) in the order OpenImageIO
// presented them: by layer, then by each name's place among the usual names, then by name.
std::vector<std::string> presentation_order(const Imf::ChannelList& channels) {
  std::vector<std::string> names;
  for (auto channel = channels.begin(); channel != channels.end(); ++channel) names.emplace_back(channel.name());
  std::vector<ChannelName> parts;
  struct LayerAxes {
    bool x = false, y_or_z = false;
  };
  std::map<std::string_view, LayerAxes> layers;
  for (const std::string& name : names) {
    parts.push_back(split_name(name));
    LayerAxes& axes = layers[parts.back().layer];
    axes.x |= same_name(parts.back().suffix, "X");
    axes.y_or_z |= same_name(parts.back().suffix, "Y") || same_name(parts.back().suffix, "Z");
  }
  std::vector<int> ranks;
  for (const ChannelName& part : parts) {
    const LayerAxes& axes = layers[part.layer];
    ranks.push_back(axes.x && axes.y_or_z ? rank_in(kVectorOrder, part.suffix) : rank_in(kUsualOrder, part.suffix));
  }
  std::vector<size_t> order(names.size());
  std::iota(order.begin(), order.end(), size_t(0));
  std::sort(order.begin(), order.end(), [&](size_t a, size_t b) {
    return std::tie(parts[a].layer, ranks[a], parts[a].suffix) < std::tie(parts[b].layer, ranks[b], parts[b].suffix);
  });
  std::vector<std::string> sorted;
  for (size_t index : order) sorted.push_back(names[index]);
  return sorted;
}

// The attributes of the types kdray writes; others are left out.
void read_attributes(const Imf::Header& header, std::map<std::string, ImageAttribute>& attributes) {
  for (auto attribute = header.begin(); attribute != header.end(); ++attribute) {
    const Imf::Attribute& value = attribute.attribute();
    if (const auto* integer = dynamic_cast<const Imf::IntAttribute*>(&value))
      attributes[attribute.name()] = int32_t(integer->value());
    else if (const auto* number = dynamic_cast<const Imf::FloatAttribute*>(&value))
      attributes[attribute.name()] = number->value();
    else if (const auto* text = dynamic_cast<const Imf::StringAttribute*>(&value))
      attributes[attribute.name()] = text->value();
  }
}

// The first part of the file (scanline or tiled; the top level of a tiled one).
class ExrReader : public ImageReader {
 public:
  explicit ExrReader(const std::string& path) : file_(path.c_str(), exr_threads()) {
    const Imf::Header& exr = file_.header();
    if (exr.hasType() && Imf::isDeepData(exr.type())) throw std::runtime_error("a deep image, which kdray does not read");
    // OpenEXR has checked that the data window is within +-INT_MAX / 2.
    window_ = exr.dataWindow();
    header_.width = window_.max.x - window_.min.x + 1;
    header_.height = window_.max.y - window_.min.y + 1;
    header_.at_origin = window_.min.x == 0 && window_.min.y == 0;
    for (const std::string& name : presentation_order(exr.channels())) {
      const Imf::Channel& channel = *exr.channels().findChannel(name);
      if (channel.xSampling != 1 || channel.ySampling != 1)
        throw std::runtime_error("channel " + name + " is subsampled, which kdray does not read");
      const std::string_view suffix = split_name(name).suffix;
      if (header_.alpha_channel < 0 && (same_name(suffix, "A") || same_name(suffix, "Alpha")))
        header_.alpha_channel = int(header_.channel_names.size());
      header_.channel_names.push_back(name);
      header_.channel_types.push_back(pixel_type(channel.type));
    }
    read_attributes(exr, header_.attributes);
  }
  const ImageHeader& header() const override { return header_; }
  bool read(int first_channel, int end_channel, PixelType type, void* pixels) override {
    return guarded(problem_, [&] {
      if (first_channel < 0 || end_channel > int(header_.channel_names.size()) || first_channel >= end_channel)
        throw std::out_of_range("no channels " + std::to_string(first_channel) + " to " + std::to_string(end_channel));
      const size_t pixel_bytes = kChannelBytes * size_t(end_channel - first_channel);
      const Imf::PixelType slice_type = exr_type(type);
      Imf::FrameBuffer frame;
      for (int c = first_channel; c < end_channel; ++c) {
        char* first_pixel = static_cast<char*>(pixels) + kChannelBytes * size_t(c - first_channel);
        frame.insert(header_.channel_names[size_t(c)],
                     Imf::Slice::Make(slice_type, first_pixel, window_, pixel_bytes, pixel_bytes * size_t(header_.width)));
      }
      file_.setFrameBuffer(frame);
      file_.readPixels(window_.min.y, window_.max.y);
    });
  }
  std::string problem() override { return problem_; }

 private:
  Imf::InputFile file_;
  Imath::Box2i window_;
  ImageHeader header_;
  std::string problem_;
};

// `format` is "exr" or empty: the one reader either way.
std::unique_ptr<ImageReader> open_exr(const std::string& path, const std::string& /*format*/, std::string& problem) {
  std::unique_ptr<ImageReader> reader;
  guarded(problem, [&] { reader = std::make_unique<ExrReader>(path); });
  return reader;
}

void add_attribute(Imf::Header& exr, const std::string& name, const ImageAttribute& value) {
  if (const int32_t* integer = std::get_if<int32_t>(&value)) exr.insert(name, Imf::IntAttribute(*integer));
  // EXR has no unsigned attribute: the bits as an int, as OpenImageIO stored them, read back as
  // int32_t; kdray's readers take either.
  if (const uint32_t* natural = std::get_if<uint32_t>(&value)) exr.insert(name, Imf::IntAttribute(int32_t(*natural)));
  if (const float* number = std::get_if<float>(&value)) exr.insert(name, Imf::FloatAttribute(*number));
  if (const std::string* text = std::get_if<std::string>(&value)) exr.insert(name, Imf::StringAttribute(*text));
}

// A single-part scanline file, ZIP-compressed in blocks of 16 lines (OpenImageIO's default for
// EXR, and what read_film_exr's check of a film's header allows for).
bool write_exr(const std::string& path, const ImageHeader& header, std::optional<PixelType> given,
               const void* pixels, std::string& problem) {
  const bool written = guarded(problem, [&] {
    Imf::Header exr(header.width, header.height);
    exr.compression() = Imf::ZIP_COMPRESSION;
    const size_t pixel_bytes = kChannelBytes * header.channel_names.size();
    Imf::FrameBuffer frame;
    for (size_t c = 0; c < header.channel_names.size(); ++c) {
      const Imf::PixelType stored = exr_type(header.channel_types.at(c));
      // OpenEXR writes each channel from pixels of its own type.
      if (given && exr_type(*given) != stored)
        throw std::invalid_argument("channel " + header.channel_names[c] + " given in another type than it is stored in");
      exr.channels().insert(header.channel_names[c], Imf::Channel(stored));
      frame.insert(header.channel_names[c],
                   Imf::Slice::Make(stored, static_cast<const char*>(pixels) + kChannelBytes * c, exr.dataWindow(),
                                    pixel_bytes, pixel_bytes * size_t(header.width)));
    }
    for (const auto& [name, value] : header.attributes) add_attribute(exr, name, value);
    // OpenEXR writes the table of line offsets when the file object is destroyed, where a
    // failure cannot be reported: the stream's state says whether everything reached the file.
    std::ofstream stream(path, std::ios::binary);
    if (!stream) throw std::runtime_error(std::string("cannot create the file: ") + std::strerror(errno));
    {
      Imf::StdOFStream exr_stream(stream, path.c_str());
      Imf::OutputFile file(exr_stream, exr, exr_threads());
      file.setFrameBuffer(frame);
      file.writePixels(header.height);
    }
    stream.close();
    if (!stream) throw std::runtime_error("I/O error");
  });
  if (!written) problem = "cannot write image: " + problem;
  return written;
}

const ImageCodec kExrCodec = {open_exr, write_exr};

}  // namespace

const ImageCodec& exr_codec() { return kExrCodec; }

}  // namespace kdray
