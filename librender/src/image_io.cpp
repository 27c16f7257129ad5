// Film images through the image codecs: OpenEXR for .exr, the module for PNG and JPEG (see image_io.h).
#include "image_codec_loader.h"

#include <kdray/atomic_file.h>
#include <kdray/error.h>
#include <kdray/image_io.h>
#include <kdray/util.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <map>

namespace kdray {
namespace fs = std::filesystem;
namespace {

constexpr const char* kSumPrefix = "kdray.sum.";

// OpenEXR stores channels sorted by name; films keep radiance first, then the AOVs.
const char* const kChannelOrder[] = {"R", "G", "B", "albedo.R", "albedo.G", "albedo.B", "N.X", "N.Y", "N.Z", "Z"};

uint8_t srgb_byte(float linear) { return static_cast<uint8_t>(std::lround(linear_to_srgb(linear) * 255.0f)); }

// Writes each channel in its stored type through a temporary sibling that keeps the extension,
// which names the format.
void write_atomically(const std::string& path, const ImageHeader& header, const void* pixels) {
  const ImageCodec& codec = image_codec(path);
  AtomicFile file(path);
  std::string problem;
  if (!codec.write(file.temporary_path(), header, std::nullopt, pixels, problem)) throw Error(path, problem);
  file.commit();
}

void write_exr(const std::string& path, const Film& film) {
  const size_t stride = film.channels.size();
  const size_t total_channels = stride * 3;  // mean, sum hi, sum lo
  ImageHeader header;
  header.width = int(film.width);
  header.height = int(film.height);
  for (const std::string& name : film.channels) {
    header.channel_names.push_back(name);
    header.channel_types.push_back(PixelType::Float);
  }
  for (const std::string& name : film.channels) {
    for (const char* half : {".hi", ".lo"}) {
      header.channel_names.push_back(kSumPrefix + name + half);
      header.channel_types.push_back(PixelType::UInt32);
    }
  }
  header.attributes = {{"kdray:spp", film.sample_count},
                       {"kdray:sample_offset", film.sample_offset},
                       {"kdray:seed", film.seed},
                       {"kdray:max_bounces", film.max_bounces},
                       {"kdray:sampler", std::string(sampler_name(film.sampler))},
                       {"kdray:seconds", float(film.render_seconds)},
                       {"kdray:scene_hash", hash_hex(film.scene_hash)},
                       {"kdray:tree_hash", hash_hex(film.tree_hash)},
                       {"kdray:settings_hash", hash_hex(film.settings_hash)},
                       {"kdray:fixed_bits", int32_t(kFilmFixedBits)}};

  std::vector<float> means = film.means();
  std::vector<uint32_t> pixels(film.pixel_count() * total_channels);  // every channel is 4 bytes
  for (size_t p = 0; p < film.pixel_count(); ++p) {
    uint32_t* out = &pixels[p * total_channels];
    for (size_t c = 0; c < stride; ++c) {
      std::memcpy(&out[c], &means[p * stride + c], sizeof(float));
      uint64_t bits = static_cast<uint64_t>(film.sums[p * stride + c]);
      out[stride + 2 * c] = static_cast<uint32_t>(bits >> 32);
      out[stride + 2 * c + 1] = static_cast<uint32_t>(bits);
    }
  }
  write_atomically(path, header, pixels.data());
}

void write_ldr(const std::string& path, const Film& film) {
  std::vector<float> means = film.means();
  const size_t stride = film.channels.size();
  std::vector<uint8_t> pixels(film.pixel_count() * 3);
  for (size_t p = 0; p < film.pixel_count(); ++p) {
    for (size_t c = 0; c < 3; ++c) pixels[p * 3 + c] = srgb_byte(means[p * stride + c]);
  }
  ImageHeader header;
  header.width = int(film.width);
  header.height = int(film.height);
  header.channel_names = {"R", "G", "B"};
  header.channel_types.assign(3, PixelType::UInt8);
  header.attributes = {{"oiio:ColorSpace", std::string("sRGB")}, {"Software", std::string("kdray kdrender")}};
  write_atomically(path, header, pixels.data());
}

// A metadata value, the fallback when it is absent or of another kind: integers are read from the
// integer types only, numbers from those and float.
int64_t integer_attribute(const ImageHeader& header, const char* name, int64_t fallback) {
  const auto found = header.attributes.find(name);
  if (found == header.attributes.end()) return fallback;
  if (const int32_t* value = std::get_if<int32_t>(&found->second)) return *value;
  if (const uint32_t* value = std::get_if<uint32_t>(&found->second)) return *value;
  return fallback;
}

double number_attribute(const ImageHeader& header, const char* name, double fallback) {
  const auto found = header.attributes.find(name);
  if (found == header.attributes.end()) return fallback;
  if (const float* value = std::get_if<float>(&found->second)) return *value;
  return double(integer_attribute(header, name, 0));
}

std::string text_attribute(const ImageHeader& header, const char* name, const std::string& fallback) {
  const auto found = header.attributes.find(name);
  const std::string* value = found == header.attributes.end() ? nullptr : std::get_if<std::string>(&found->second);
  return value ? *value : fallback;
}

uint64_t parse_hex(const std::string& path, const std::string& text) {
  const std::optional<uint64_t> value = parse_hash_hex(text);
  if (!value) throw Error(path, "bad hash in the kdray metadata");
  return *value;
}

// What an OpenEXR header claims, read by kdray before OpenEXR sees the file: OpenEXR sizes its
// chunk offset tables, line buffers and some attribute values from the header while opening,
// so a hostile header could make it allocate any amount of memory before kdray gets a say.
struct ExrClaims {
  int64_t width = 0, height = 0, channels = 0;
};

// The attribute types a kdrender film may carry, with their sizes. OpenEXR reads a value of a
// fixed-size type without looking at the size field, so the size must be exactly right or the
// two readers would part ways and OpenEXR would take later bytes for sizes kdray never checked
// (a string attribute claiming 2 GB). Types whose reader allocates from counts inside the value
// (preview, stringvector, floatvector, ...) are not accepted at all.
constexpr int64_t kSizeFromField = -1;
const std::map<std::string, int64_t> kExrAttributeSizes = {
    {"string", kSizeFromField}, {"chlist", kSizeFromField}, {"int", 4},     {"float", 4},
    {"double", 8},              {"compression", 1},         {"lineOrder", 1}, {"box2i", 16},
    {"box2f", 16},              {"v2i", 8},                 {"v2f", 8},     {"v3i", 12},
    {"v3f", 12},                {"m33f", 36},               {"m44f", 64},   {"chromaticities", 32},
    {"rational", 8},            {"timecode", 8},            {"keycode", 28},
};

ExrClaims read_exr_claims(const std::string& path, const std::string& header) {
  auto fail = [&](const std::string& what) { return Error(path, "not a kdrender EXR: " + what); };
  if (header.size() < 8 || header.compare(0, 4, "\x76\x2f\x31\x01") != 0) throw fail("not an OpenEXR file");
  // kdrender writes single-part scanline files of format version 2; the only flag it may set is
  // "long names" (bit 10), which raises the name limit from 31 to 255 bytes.
  constexpr uint8_t kLongNames = 0x04;
  if (header[4] != 2 || (uint8_t(header[5]) & ~kLongNames) != 0 || header[6] != 0 || header[7] != 0)
    throw fail("a tiled, deep, multi-part or newer-version file");
  const size_t max_name = (uint8_t(header[5]) & kLongNames) ? 255 : 31;
  ExrClaims claims;
  bool have_window = false, have_channels = false;
  size_t at = 8;
  auto name_at = [&](size_t& from, size_t limit) {
    const size_t end = header.find('\0', from);
    if (end == std::string::npos || end >= limit || end - from > max_name) throw fail("damaged header");
    std::string text = header.substr(from, end - from);
    from = end + 1;
    return text;
  };
  auto int32_at = [&](size_t offset) {
    int32_t value;
    std::memcpy(&value, header.data() + offset, 4);
    return int64_t(value);
  };
  for (;;) {
    const std::string name = name_at(at, header.size());
    if (name.empty()) break;  // the end of the header
    const std::string type = name_at(at, header.size());
    if (at + 4 > header.size()) throw fail("damaged header");
    const int64_t size = int32_at(at);
    at += 4;
    if (size < 0 || uint64_t(size) > header.size() - at) throw fail("damaged header");
    const auto known = kExrAttributeSizes.find(type);
    if (known == kExrAttributeSizes.end()) throw fail("attribute " + name + " has type " + type);
    if (known->second != kSizeFromField && known->second != size)
      throw fail("attribute " + name + " has the wrong size for its type " + type);
    const size_t end = at + size_t(size);
    if (name == "dataWindow" && type == "box2i") {
      claims.width = int32_at(at + 8) - int32_at(at) + 1;
      claims.height = int32_at(at + 12) - int32_at(at + 4) + 1;
      have_window = true;
    } else if (type == "chlist") {
      // Entries (a name and 16 bytes) up to an empty name, which must be the value's last byte:
      // OpenEXR reads any channel list up to that empty name whatever the size says, so every
      // list is checked, not only the image's own.
      size_t entry = at;
      int64_t count = 0;
      for (; entry < end && header[entry] != '\0'; ++count) {
        const std::string channel = name_at(entry, end);
        if (entry + 16 > end) throw fail("damaged channel list");
        // Pixel type, linear flag and padding, then x and y sampling. OpenEXR sizes its line
        // buffers from the sampling, so a negative one costs gigabytes; kdrender samples every pixel.
        if (uint64_t(int32_at(entry)) > 2) throw fail("channel " + channel + " has an unknown pixel type");
        if (int32_at(entry + 8) != 1 || int32_at(entry + 12) != 1) throw fail("channel " + channel + " is subsampled");
        entry += 16;
      }
      if (entry + 1 != end) throw fail("damaged channel list");
      if (name == "channels") {
        claims.channels = count;
        have_channels = true;
      }
    } else if (name == "compression" && type == "compression") {
      // What the expansion bound below holds for: none, RLE, ZIP of one or of 16 lines.
      if (uint8_t(header[at]) > 3) throw fail("compression other than none, RLE or ZIP");
    }
    at = end;
  }
  if (!have_window || !have_channels) throw fail("no data window or channel list in the header");
  return claims;
}

// A kdrender film is ZIP-compressed, and deflate expands at most 1032-fold (RLE 64-fold): more
// pixels than that ratio allows cannot be in the file.
void check_exr_claims(const std::string& path) {
  std::ifstream file(path, std::ios::binary);
  std::string header(64 * 1024, '\0');  // far more than any kdrender header
  file.read(header.data(), std::streamsize(header.size()));
  header.resize(size_t(file.gcount()));
  const ExrClaims claims = read_exr_claims(path, header);
  std::error_code error;
  const uint64_t file_size = fs::file_size(path, error);
  constexpr uint64_t kMaxExpansion = 1032;
  const bool sane = claims.width > 0 && claims.height > 0 && claims.channels > 0 && claims.width <= INT32_MAX &&
                    claims.height <= INT32_MAX && claims.channels <= 1024;
  // Each channel is read as 32-bit values.
  if (error || !sane ||
      uint64_t(claims.width) * uint64_t(claims.height) * uint64_t(claims.channels) * 4 / kMaxExpansion > file_size)
    throw Error(path, "not a kdrender EXR: the header announces " + std::to_string(claims.width) + "x" +
                          std::to_string(claims.height) + " pixels of " + std::to_string(claims.channels) +
                          " channels, which a " + std::to_string(file_size) + "-byte film cannot hold");
}

}  // namespace

std::optional<std::pair<uint32_t, uint32_t>> read_image_size(const std::string& path) {
  std::string problem;
  std::unique_ptr<ImageReader> in = image_codec(path).open(path, "", problem);
  if (!in) return std::nullopt;
  return std::make_pair(uint32_t(in->header().width), uint32_t(in->header().height));
}

bool is_supported_image_path(const std::string& path) {
  std::string ext = lowercase_extension(path);
  return ext == ".exr" || ext == ".png" || ext == ".jpg" || ext == ".jpeg";
}

void write_film_image(const std::string& path, const Film& film) {
  std::string ext = lowercase_extension(path);
  if (ext == ".exr") return write_exr(path, film);
  if (ext == ".png" || ext == ".jpg" || ext == ".jpeg") return write_ldr(path, film);
  throw Error(path, "unsupported output format '" + ext + "' (use .exr, .png or .jpg)");
}

Film read_film_exr(const std::string& path) {
  std::error_code error;
  if (!fs::is_regular_file(path, error))
    throw Error(path, fs::exists(path, error) ? "not a regular file" : "no such file");
  check_exr_claims(path);
  std::string problem;
  std::unique_ptr<ImageReader> in = image_codec(path).open(path, "exr", problem);
  if (!in) throw Error(path, "cannot read image: " + problem);
  const ImageHeader& header = in->header();
  if (header.deep || !header.at_origin || header.depth != 1)
    throw Error(path, "not a kdrender EXR: a deep image, or its data window does not start at the origin");
  Film film;
  film.width = uint32_t(header.width);
  film.height = uint32_t(header.height);
  const std::vector<std::string>& names = header.channel_names;
  auto channel_index = [&](const std::string& name) {
    auto found = std::find(names.begin(), names.end(), name);
    return found == names.end() ? -1 : int(found - names.begin());
  };
  std::vector<int> hi_index, lo_index;
  for (const std::string& name : names) {
    if (name.rfind(kSumPrefix, 0) == 0) continue;
    if (std::find(std::begin(kChannelOrder), std::end(kChannelOrder), name) == std::end(kChannelOrder)) {
      throw Error(path, "not a kdrender EXR: unexpected channel " + name);
    }
  }
  for (const char* name : kChannelOrder) {
    if (channel_index(name) < 0) continue;
    int hi = channel_index(std::string(kSumPrefix) + name + ".hi");
    int lo = channel_index(std::string(kSumPrefix) + name + ".lo");
    if (hi < 0 || lo < 0) {
      throw Error(path, std::string("not a kdrender EXR: channel ") + name + " has no exact sums to merge");
    }
    film.channels.push_back(name);
    hi_index.push_back(hi);
    lo_index.push_back(lo);
  }
  if (film.channels.empty()) throw Error(path, "not a kdrender EXR: no image channels");
  for (const char* key : {"kdray:spp", "kdray:sample_offset", "kdray:seed", "kdray:max_bounces", "kdray:scene_hash",
                          "kdray:tree_hash"}) {
    if (!header.attributes.count(key)) throw Error(path, std::string("not a kdrender EXR: no ") + key + " metadata");
  }
  if (integer_attribute(header, "kdray:fixed_bits", kFilmFixedBits) != kFilmFixedBits) {
    throw Error(path, "written with another fixed-point precision; cannot merge");
  }
  film.sample_count = uint32_t(integer_attribute(header, "kdray:spp", 0));
  film.sample_offset = uint32_t(integer_attribute(header, "kdray:sample_offset", 0));
  film.seed = uint32_t(integer_attribute(header, "kdray:seed", 0));
  film.max_bounces = uint32_t(integer_attribute(header, "kdray:max_bounces", 0));
  // Files written before the sampler choice used independent numbers.
  const std::string sampler_text = text_attribute(header, "kdray:sampler", "independent");
  std::optional<Sampler> sampler = parse_sampler(sampler_text);
  if (!sampler) throw Error(path, "unknown kdray:sampler '" + sampler_text + "'");
  film.sampler = *sampler;
  film.render_seconds = number_attribute(header, "kdray:seconds", 0);
  film.scene_hash = parse_hex(path, text_attribute(header, "kdray:scene_hash", ""));
  film.tree_hash = parse_hex(path, text_attribute(header, "kdray:tree_hash", ""));
  const std::string settings_hash = text_attribute(header, "kdray:settings_hash", "");  // absent in older images
  film.settings_hash = settings_hash.empty() ? 0 : parse_hex(path, settings_hash);

  // The sum channels in one read: the file is decompressed once, not once per channel.
  const int first = std::min(*std::min_element(hi_index.begin(), hi_index.end()),
                             *std::min_element(lo_index.begin(), lo_index.end()));
  const int end = std::max(*std::max_element(hi_index.begin(), hi_index.end()),
                           *std::max_element(lo_index.begin(), lo_index.end())) + 1;
  const size_t stride = size_t(end - first);
  std::vector<uint32_t> words(film.pixel_count() * stride);
  if (!in->read(first, end, PixelType::UInt32, words.data())) throw Error(path, "cannot read image: " + in->problem());
  film.sums.assign(film.pixel_count() * film.channels.size(), 0);
  for (size_t p = 0; p < film.pixel_count(); ++p) {
    const uint32_t* pixel = &words[p * stride];
    for (size_t c = 0; c < film.channels.size(); ++c) {
      const uint64_t bits = uint64_t(pixel[hi_index[c] - first]) << 32 | pixel[lo_index[c] - first];
      film.sums[p * film.channels.size() + c] = static_cast<int64_t>(bits);
    }
  }
  return film;
}

void preload_image_io(const std::string& path) { start_loading_image_codec(path); }

}  // namespace kdray
