// The environment light: an equirectangular radiance map around the scene (or a uniform colour),
// and the sampling table the kernels draw directions from (see kernels/pt_environment.h for the
// direction <-> pixel mapping, which is Mitsuba 3's `envmap` one with +Y up).
#pragma once

#include <kdray/scene.h>

#include <cstdint>
#include <string>
#include <vector>

namespace kdray {

struct Environment {
  std::string source;          // the image path, or "uniform" for a colour
  uint32_t width = 0, height = 0;
  std::vector<float> rgb;      // linear radiance, 3 floats per pixel, top row (+Y) first
  float strength = 1.0f;       // multiplies every pixel
  float rotate_degrees = 0.0f; // about +Y, counter-clockwise seen from above
};

// Reads an equirectangular image: EXR, or any format OpenImageIO reads (HDR, ...); the first
// three channels are RGB (one channel is grey). Throws kdray::Error naming the file.
Environment load_environment(const std::string& path);

// A uniform environment of this radiance.
Environment uniform_environment(const Vec3& color);

// The sampling table of kernels/pt_environment.h: height rows of width conditional cdf values,
// then the height values of the marginal cdf, for cell weights luminance * sin(theta) (strength
// and rotation do not change it), then the search guides of the rows and of the marginal. A map
// without any light gives a uniform table.
std::vector<float> environment_sampling_table(const Environment& environment);

// Mean of luminance over the sphere (weighting rows by sin(theta)), times strength: 0 means
// the environment gives no light.
double environment_mean_luminance(const Environment& environment);

}  // namespace kdray
