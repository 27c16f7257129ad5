// Environment maps: uniform ones and the sampling table (see environment.h); maps from image
// files are read in environment_image.cpp.
#include <kdray/environment.h>

#include <kernels/pt_environment.h>

#include <cmath>
#include <cstring>
#include <memory>

#include "cdf_guide.h"

namespace kdray {
namespace {

constexpr double kPi = 3.14159265358979323846;

// Matches pt_luminance in kernels/pt_sampling.h.
double luminance(const float* rgb) { return (double(rgb[0]) + rgb[1] + rgb[2]) / 3.0; }

}  // namespace

Environment uniform_environment(const Vec3& color) {
  // A small grid rather than one pixel, so that the sampling table still follows sin(theta).
  Environment env;
  env.source = "uniform";
  env.width = 32;
  env.height = 16;
  env.rgb.resize(size_t(env.width) * env.height * 3);
  for (size_t i = 0; i < env.rgb.size(); i += 3) {
    env.rgb[i] = color.x;
    env.rgb[i + 1] = color.y;
    env.rgb[i + 2] = color.z;
  }
  return env;
}

std::vector<float> environment_sampling_table(const Environment& env) {
  const uint32_t w = env.width, h = env.height;
  std::vector<float> table(pt_env_guide_offset(w, h, h + 1));
  std::vector<double> row_sums(h);
  std::vector<double> row(w);
  double total = 0;
  for (uint32_t j = 0; j < h; ++j) {
    const double sin_theta = std::sin(kPi * (j + 0.5) / h);
    double sum = 0;
    for (uint32_t i = 0; i < w; ++i) {
      sum += luminance(&env.rgb[(size_t(j) * w + i) * 3]) * sin_theta;
      row[i] = sum;
    }
    for (uint32_t i = 0; i < w; ++i) {
      table[size_t(j) * w + i] = sum > 0 ? float(row[i] / sum) : float(double(i + 1) / w);
    }
    table[size_t(j) * w + w - 1] = 1.0f;
    row_sums[j] = sum;
    total += sum;
  }
  float* marginal = table.data() + size_t(w) * h;
  double running = 0;
  for (uint32_t j = 0; j < h; ++j) {
    running += total > 0 ? row_sums[j] : std::sin(kPi * (j + 0.5) / h);
    marginal[j] = float(running);
  }
  for (uint32_t j = 0; j < h; ++j) marginal[j] = float(marginal[j] / running);
  marginal[h - 1] = 1.0f;
  // The guides' indices as the table's words (pt_cdf_find reads them back as integers).
  for (uint32_t j = 0; j <= h; ++j) {
    const std::vector<uint32_t> guide = j < h ? cdf_guide(table.data() + size_t(j) * w, w) : cdf_guide(marginal, h);
    std::memcpy(table.data() + pt_env_guide_offset(w, h, j), guide.data(), guide.size() * sizeof(uint32_t));
  }
  return table;
}

double environment_mean_luminance(const Environment& env) {
  double weighted = 0, weights = 0;
  for (uint32_t j = 0; j < env.height; ++j) {
    const double sin_theta = std::sin(kPi * (j + 0.5) / env.height);
    for (uint32_t i = 0; i < env.width; ++i) weighted += luminance(&env.rgb[(size_t(j) * env.width + i) * 3]) * sin_theta;
    weights += sin_theta * env.width;
  }
  return weights > 0 ? env.strength * weighted / weights : 0.0;
}

}  // namespace kdray
