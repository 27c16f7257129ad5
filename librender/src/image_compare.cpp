#include "image_codec_loader.h"

#include <kdray/atomic_file.h>
#include <kdray/error.h>
#include <kdray/image_compare.h>
#include <kdray/util.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <filesystem>
#include <limits>
#include <string>

namespace kdray {
namespace {

// 8-bit formats get 8-bit pixels (OpenImageIO rounds and clamps); everything else keeps float.
PixelType storage_type_for(const std::string& path) {
  const std::string extension = lowercase_extension(path);
  if (extension == ".png" || extension == ".jpg" || extension == ".jpeg" || extension == ".bmp") {
    return PixelType::UInt8;
  }
  return PixelType::Float;
}

std::vector<size_t> channel_indices(const FloatImage& image, const std::vector<std::string>& names,
                                    const char* which) {
  std::vector<size_t> indices;
  for (const std::string& name : names) {
    auto found = std::find(image.channel_names.begin(), image.channel_names.end(), name);
    if (found == image.channel_names.end()) {
      throw Error("", std::string("the ") + which + " image has no channel \"" + name + "\"");
    }
    indices.push_back(size_t(found - image.channel_names.begin()));
  }
  return indices;
}

bool has_channel(const FloatImage& image, const std::string& name) {
  return std::find(image.channel_names.begin(), image.channel_names.end(), name) != image.channel_names.end();
}

std::vector<std::string> default_channels(const FloatImage& test, const FloatImage& reference) {
  // The radiance, when both have it: a kdrender EXR also carries AOV layers and its exact
  // fixed-point sums, which are not the picture.
  const std::vector<std::string> colour = {"R", "G", "B"};
  if (std::all_of(colour.begin(), colour.end(),
                  [&](const std::string& name) { return has_channel(test, name) && has_channel(reference, name); })) {
    return colour;
  }
  std::vector<std::string> shared, shared_without_alpha;
  for (size_t c = 0; c < test.channel_count(); ++c) {
    const std::string& name = test.channel_names[c];
    auto in_reference = std::find(reference.channel_names.begin(), reference.channel_names.end(), name);
    if (in_reference == reference.channel_names.end()) continue;
    shared.push_back(name);
    const bool is_alpha = int(c) == test.alpha_channel ||
                          int(in_reference - reference.channel_names.begin()) == reference.alpha_channel;
    if (!is_alpha) shared_without_alpha.push_back(name);
  }
  if (shared.empty()) throw Error("", "the images have no channel name in common");
  return shared_without_alpha.empty() ? shared : shared_without_alpha;
}

bool pixel_finite(const FloatImage& image, size_t pixel, const std::vector<size_t>& channels) {
  for (size_t c : channels) {
    if (!std::isfinite(image.at(pixel, c))) return false;
  }
  return true;
}

// Running sums for one channel; finished into ErrorMetrics once all pixels are seen.
struct ErrorSums {
  double squared = 0, relative = 0, absolute = 0, max_abs = 0;
  double test = 0, reference = 0;
  uint64_t count = 0;

  void add(double t, double r) {
    const double difference = t - r;
    squared += difference * difference;
    relative += difference * difference / (r * r + kRelMseEpsilon);
    absolute += std::abs(difference);
    max_abs = std::max(max_abs, std::abs(difference));
    test += t;
    reference += r;
    ++count;
  }
  void merge(const ErrorSums& other) {
    squared += other.squared;
    relative += other.relative;
    absolute += other.absolute;
    max_abs = std::max(max_abs, other.max_abs);
    test += other.test;
    reference += other.reference;
    count += other.count;
  }
  ErrorMetrics finish(double peak) const {
    ErrorMetrics metrics;
    if (count == 0) {  // nothing comparable: no figure may look like a good one
      const double nan = std::numeric_limits<double>::quiet_NaN();
      return {nan, nan, nan, nan, nan, nan, nan};
    }
    const double n = double(count);
    const double mse = squared / n;
    metrics.rmse = std::sqrt(mse);
    metrics.relmse = relative / n;
    metrics.mae = absolute / n;
    metrics.psnr = mse > 0 ? 10.0 * std::log10(peak * peak / mse) : std::numeric_limits<double>::infinity();
    metrics.max_abs = max_abs;
    metrics.mean_test = test / n;
    metrics.mean_reference = reference / n;
    return metrics;
  }
};

// Perceptually ordered control points (black -> purple -> red -> orange -> pale yellow),
// in the spirit of matplotlib's "inferno".
constexpr std::array<std::array<float, 3>, 5> kHeatColours = {{
    {0.00f, 0.00f, 0.02f},
    {0.34f, 0.06f, 0.43f},
    {0.74f, 0.22f, 0.33f},
    {0.98f, 0.56f, 0.04f},
    {0.99f, 1.00f, 0.64f},
}};

std::array<float, 3> heat_colour(double fraction) {
  const double position = std::clamp(fraction, 0.0, 1.0) * double(kHeatColours.size() - 1);
  const size_t low = std::min(size_t(position), kHeatColours.size() - 2);
  const float blend = float(position - double(low));
  std::array<float, 3> colour;
  for (size_t k = 0; k < 3; ++k) {
    colour[k] = kHeatColours[low][k] + blend * (kHeatColours[low + 1][k] - kHeatColours[low][k]);
  }
  return colour;
}

}  // namespace

FloatImage read_float_image(const std::string& path) {
  std::string why;
  std::unique_ptr<ImageReader> input = image_codec(path).open(path, "", why);
  if (!input) throw Error(path, "cannot read image: " + (why.empty() ? std::string("cannot open") : why));
  const ImageHeader& header = input->header();
  if (header.width <= 0 || header.height <= 0 || header.channel_names.empty() || header.depth > 1) {
    throw Error(path, "not a 2D image with pixels");
  }
  FloatImage image;
  image.width = header.width;
  image.height = header.height;
  image.channel_names = header.channel_names;
  image.alpha_channel = header.alpha_channel;
  image.pixels.resize(image.pixel_count() * image.channel_count());
  if (!input->read(0, int(image.channel_count()), PixelType::Float, image.pixels.data())) {
    throw Error(path, "cannot read pixels: " + input->problem());
  }
  return image;
}

void write_float_image_atomic(const std::string& path, const FloatImage& image) {
  if (image.pixels.size() != image.pixel_count() * image.channel_count() || image.channel_count() == 0) {
    throw Error(path, "internal: image buffer does not match its size");
  }
  ImageHeader header;
  header.width = image.width;
  header.height = image.height;
  header.channel_names = image.channel_names;
  header.channel_types.assign(image.channel_count(), storage_type_for(path));
  header.alpha_channel = image.alpha_channel;
  const ImageCodec& codec = image_codec(path);
  AtomicFile file(path);  // the temporary file keeps the extension, which names the format
  std::string problem;
  if (!codec.write(file.temporary_path(), header, PixelType::Float, image.pixels.data(), problem))
    throw Error(path, problem);
  file.commit();
}

bool images_same_size(const FloatImage& a, const FloatImage& b) {
  return a.width == b.width && a.height == b.height;
}

CompareResult compare_images(const FloatImage& test, const FloatImage& reference, const CompareOptions& options) {
  if (!images_same_size(test, reference)) {
    throw Error("", "image sizes differ: " + std::to_string(test.width) + "x" + std::to_string(test.height) +
                        " against " + std::to_string(reference.width) + "x" + std::to_string(reference.height));
  }
  CompareResult result;
  result.channel_names = options.channels.empty() ? default_channels(test, reference) : options.channels;
  const std::vector<size_t> test_channels = channel_indices(test, result.channel_names, "test");
  const std::vector<size_t> reference_channels = channel_indices(reference, result.channel_names, "reference");

  const size_t channels = result.channel_names.size();
  std::vector<ErrorSums> sums(channels);
  double brightest_reference = 0;
  for (size_t pixel = 0; pixel < test.pixel_count(); ++pixel) {
    const bool test_finite = pixel_finite(test, pixel, test_channels);
    const bool reference_finite = pixel_finite(reference, pixel, reference_channels);
    result.nonfinite_test += test_finite ? 0 : 1;
    result.nonfinite_reference += reference_finite ? 0 : 1;
    if (!test_finite || !reference_finite) continue;
    ++result.compared_pixels;
    for (size_t c = 0; c < channels; ++c) {
      const double r = reference.at(pixel, reference_channels[c]);
      sums[c].add(test.at(pixel, test_channels[c]), r);
      brightest_reference = std::max(brightest_reference, r);
    }
  }

  result.peak = options.peak > 0 ? options.peak : std::max(1.0, brightest_reference);
  ErrorSums all;
  for (const ErrorSums& channel : sums) {
    result.per_channel.push_back(channel.finish(result.peak));
    all.merge(channel);
  }
  result.overall = all.finish(result.peak);
  return result;
}

std::vector<float> per_pixel_abs_error(const FloatImage& test, const FloatImage& reference,
                                       const std::vector<std::string>& channel_names) {
  if (!images_same_size(test, reference)) throw Error("", "image sizes differ");
  const std::vector<size_t> test_channels = channel_indices(test, channel_names, "test");
  const std::vector<size_t> reference_channels = channel_indices(reference, channel_names, "reference");
  std::vector<float> error(test.pixel_count());
  for (size_t pixel = 0; pixel < error.size(); ++pixel) {
    if (!pixel_finite(test, pixel, test_channels) || !pixel_finite(reference, pixel, reference_channels)) {
      error[pixel] = std::numeric_limits<float>::quiet_NaN();
      continue;
    }
    double sum = 0;
    for (size_t c = 0; c < channel_names.size(); ++c) {
      sum += std::abs(double(test.at(pixel, test_channels[c])) - double(reference.at(pixel, reference_channels[c])));
    }
    error[pixel] = float(sum / double(channel_names.size()));
  }
  return error;
}

FloatImage error_heatmap(const std::vector<float>& error, int width, int height, const HeatmapOptions& options,
                         double* used_scale) {
  double scale = options.scale;
  if (scale <= 0) {
    std::vector<float> finite;
    for (float e : error) {
      if (std::isfinite(e)) finite.push_back(e);
    }
    if (!finite.empty()) {
      const size_t rank = std::min(finite.size() - 1, size_t(0.99 * double(finite.size())));
      std::nth_element(finite.begin(), finite.begin() + std::ptrdiff_t(rank), finite.end());
      scale = finite[rank];
    }
    if (!(scale > 0)) scale = 1;  // identical images: everything maps to black anyway
  }
  if (used_scale != nullptr) *used_scale = scale;

  FloatImage map;
  map.width = width;
  map.height = height;
  map.channel_names = {"R", "G", "B"};
  map.pixels.resize(size_t(width) * size_t(height) * 3);
  for (size_t pixel = 0; pixel < error.size() && pixel < map.pixel_count(); ++pixel) {
    const std::array<float, 3> colour =
        std::isfinite(error[pixel]) ? heat_colour(double(error[pixel]) / scale) : std::array<float, 3>{1, 0, 1};
    std::copy(colour.begin(), colour.end(), map.pixels.begin() + std::ptrdiff_t(pixel * 3));
  }
  return map;
}

}  // namespace kdray
