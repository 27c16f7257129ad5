// Comparing a rendered image against a reference: error metrics per channel and overall,
// and a false-colour map of the per-pixel error. Images are read through OpenEXR (EXR) and
// OpenImageIO (any other format it reads: HDR, PNG, JPEG, TIFF...); values are compared as float,
// linear as stored (an 8-bit PNG becomes 0..1, no sRGB decoding).
#pragma once

#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

namespace kdray {

// An image as interleaved float channels, rows top to bottom.
struct FloatImage {
  int width = 0;
  int height = 0;
  std::vector<std::string> channel_names;  // e.g. R, G, B, A
  int alpha_channel = -1;                  // index into channel_names, or -1
  std::vector<float> pixels;               // width * height * channel_names.size()

  size_t channel_count() const { return channel_names.size(); }
  size_t pixel_count() const { return size_t(width) * size_t(height); }
  float at(size_t pixel, size_t channel) const { return pixels[pixel * channel_count() + channel]; }
};

// Reads the first subimage with all its channels. Throws kdray::Error naming the file.
FloatImage read_float_image(const std::string& path);

// Writes through a temporary file in the same directory renamed over `path`, so a reader
// never sees a partial image. The format follows the extension of `path`. Throws kdray::Error.
void write_float_image_atomic(const std::string& path, const FloatImage& image);

// The relative MSE's denominator is reference² + this: keeps near-black pixels from
// dominating (the common form in rendering papers).
constexpr double kRelMseEpsilon = 0.01;

// Error figures of one channel, or of all compared channels together ("overall": the
// mean over every compared sample, so each channel weighs the same).
struct ErrorMetrics {
  double rmse = 0;            // sqrt(mean (t - r)^2)
  double relmse = 0;          // mean (t - r)^2 / (r^2 + kRelMseEpsilon)
  double mae = 0;             // mean |t - r|
  double psnr = 0;            // 10 log10(peak^2 / MSE); +infinity when MSE is 0
  double max_abs = 0;         // max |t - r|
  double mean_test = 0;       // mean of the test image's finite samples
  double mean_reference = 0;  // mean of the reference image's finite samples
};

struct CompareOptions {
  // Channels to compare, by name. Empty: R, G and B when both images have them (a kdrender
  // EXR's AOV layers and exact sums are left out), else every channel both images have,
  // except alpha unless alpha is all they share.
  std::vector<std::string> channels;
  // PSNR peak. 0: the largest finite reference value over the compared channels, but at
  // least 1 (so 0..1 images use the classic peak 1 and HDR images their own brightest value).
  double peak = 0;
};

struct CompareResult {
  std::vector<std::string> channel_names;    // the compared channels, in test-image order
  std::vector<ErrorMetrics> per_channel;     // parallel to channel_names
  ErrorMetrics overall;
  double peak = 1;                           // the PSNR peak used
  // Pixels with a NaN or Inf in any compared channel. Such pixels (in either image) are left
  // out of every error figure and mean, so they are reported here rather than hidden in a NaN.
  uint64_t nonfinite_test = 0;
  uint64_t nonfinite_reference = 0;
  uint64_t compared_pixels = 0;              // pixels finite in both images
};

// Throws kdray::Error (file "") when the sizes differ or the requested channels are missing;
// check images_same_size first to tell a size mismatch apart.
CompareResult compare_images(const FloatImage& test, const FloatImage& reference,
                             const CompareOptions& options = {});

bool images_same_size(const FloatImage& a, const FloatImage& b);

// Per-pixel error for the heat map: mean over the compared channels of |t - r|; NaN where
// either pixel is not finite.
std::vector<float> per_pixel_abs_error(const FloatImage& test, const FloatImage& reference,
                                       const std::vector<std::string>& channel_names);

struct HeatmapOptions {
  // Error shown at full colour. 0: the 99th percentile of the finite per-pixel errors, so one
  // firefly does not turn the rest of the map black. Fix it to compare maps of several images.
  double scale = 0;
};

// An 8-bit-range RGB false-colour image (black, purple, red, orange, pale yellow as the error
// grows to `scale`), magenta where a pixel is NaN/Inf. Returns the scale used via `used_scale`.
FloatImage error_heatmap(const std::vector<float>& error, int width, int height,
                         const HeatmapOptions& options, double* used_scale = nullptr);

}  // namespace kdray
