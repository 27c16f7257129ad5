// What a render is asked for (RenderSettings) and what it reports (RenderStats).
#pragma once

#include <kdray/environment.h>
#include <kdray/film.h>
#include <kdray/scene.h>

#include <cstdint>
#include <memory>
#include <optional>
#include <string>
#include <vector>

namespace kdray {

enum class RenderForm {
  Megakernel,  // one kernel runs whole paths (the default: faster on PoCL, bench/LOG.md, "Renderer")
  Wavefront,   // one kernel per path step over a buffer of paths (kept for the comparison)
};

struct RenderSettings {
  static constexpr uint32_t kDefaultSize = 512;
  static constexpr uint32_t kDefaultSpp = 16;
  static constexpr uint32_t kDefaultMaxBounces = 8;
  static constexpr uint32_t kMaxBouncesLimit = 1024;

  uint32_t width = 0, height = 0;  // 0: from the camera's aspect ratio (resolve_view)
  uint32_t spp = kDefaultSpp;     // samples per pixel in this range
  uint32_t sample_offset = 0;     // renders samples sample_offset..sample_offset+spp-1
  uint32_t seed = 0;
  uint32_t max_bounces = kDefaultMaxBounces;  // as Cycles counts: 0 is direct light only
  Sampler sampler = Sampler::Sobol;
  std::optional<Camera> camera;   // default: the scene's first camera, else default_camera()
  float fov_degrees = 0;          // > 0: replaces the camera's vertical field of view
  // Lights rays that leave the scene (camera rays too); none by default.
  std::shared_ptr<const Environment> environment;
  // A scene with no emitter, no punctual light and no environment is lit by a uniform white
  // environment of radiance 1 (default_light_radiance) rather than rendering black.
  bool default_light = true;
  bool mis = true;  // test switch: false gives light samples full weight (same expectation, more noise)
  bool aov_albedo = false, aov_normal = false, aov_depth = false;
  double time_limit_seconds = 0;  // > 0: stop after the last whole pass within the limit
  RenderForm form = RenderForm::Megakernel;
};

// What one device did in a render across several (--device all or a list).
struct DeviceShare {
  std::string device;
  int index = 0;           // in list_devices()
  std::string traversal;   // "fast" or "robust": the traversal its program compiled (trace_opencl.h)
  uint32_t samples = 0;    // samples per pixel it rendered
  double seconds = 0;      // time its passes took
};

struct RenderStats {
  std::string device;           // its name, "host", or "N devices: names" for several
  std::string kernel_options;   // the -D feature defines the program was built with (host: the scene's features)
  std::string traversal;        // "fast" or "robust" (both, comma-separated, when devices differ)
  double build_seconds = 0;     // obtaining the OpenCL program
  std::string build_source;     // "compiled", "disk cache" or "memory"
  double upload_seconds = 0;
  double render_seconds = 0;
  uint32_t samples_rendered = 0;  // per pixel; below spp only when the time limit stopped it
  uint64_t rays = 0;              // closest-hit and shadow rays traced
  uint64_t nonfinite_values = 0;  // NaN/Inf sample values (counted as 0); should stay 0
  bool default_light = false;     // the scene had no light and the default environment lit it
  std::vector<DeviceShare> devices;  // one entry per device used
  unsigned threads = 0;              // host: the worker threads it rendered with
};

}  // namespace kdray
