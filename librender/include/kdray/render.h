// Rendering a scene with its k-d tree on OpenCL devices or on the host: settings, statistics, the call.
#pragma once

#include <kdray/environment.h>
#include <kdray/film.h>
#include <kdray/kdtree.h>
#include <kdray/opencl_device.h>
#include <kdray/scene.h>

#include <cstdint>
#include <functional>
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
  uint32_t samples = 0;    // samples per pixel it rendered
  double seconds = 0;      // time its passes took
};

struct RenderStats {
  std::string device;           // its name, "host", or "N devices: names" for several
  std::string kernel_options;   // the -D feature defines the program was built with (host: the scene's features)
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

constexpr float kDefaultLightRadiance = 1.0f;

// The environment a render uses: settings.environment, else the default light when the scene
// has no light of its own and settings.default_light is on, else none.
std::shared_ptr<const Environment> render_environment(const Scene& scene, const RenderSettings& settings);

// Called after each pass with the samples per pixel done so far and the total asked for.
using RenderProgress = std::function<void(uint32_t done, uint32_t total)>;

// The device name that renders with the C++ build of the kernels' code on the CPU.
constexpr const char* kHostDevice = "host";

// Renders the range; throws kdray::Error for bad settings (size, camera, bounces). With several
// devices (device.device "all" or a list "0,1"), each renders consecutive sample ranges sized by
// its measured speed into its own film, and the films' exact sums add up to the single-device
// image bit for bit. device.device "host" (kHostDevice) renders with the C++ build of the same
// code on device.threads threads instead, no OpenCL involved: the same film, bit for bit.
Film render(const Scene& scene, const KdTree& tree, const RenderSettings& settings,
            const DeviceSelection& device, RenderStats* stats = nullptr, const RenderProgress& progress = {});

// The OpenCL build options (feature defines) for a scene: only what it uses, so a diffuse-only
// scene compiles a diffuse-only kernel.
std::string kernel_feature_options(const Scene& scene, const RenderSettings& settings, const DeviceSelection& device);

// The camera from settings, the scene or default_camera(scene bounds), with settings.fov_degrees
// applied, checked (finite, non-degenerate, 0 < fov < 180, a positive orthographic extent).
Camera render_camera(const Scene& scene, const RenderSettings& settings);

// The image size for a camera, as glTF viewers and Blender frame an asset: both sides as given;
// one side given, the other from the camera's aspect ratio; neither, the longer side
// RenderSettings::kDefaultSize. A camera without an aspect ratio gives square images.
void resolve_image_size(const Camera& camera, uint32_t& width, uint32_t& height);

// The settings with what they leave to the scene filled in: the camera (render_camera) and the
// image size (resolve_image_size). render() does this itself; tools call it to know the size.
RenderSettings resolve_view(const Scene& scene, RenderSettings settings);

// The film's channels for these settings: RGB, then the AOV layers asked for, in the order the
// kernels accumulate them (kernels/pt_codes.h); film_channel_names has film_channel_count names.
uint32_t film_channel_count(const RenderSettings& settings);
std::vector<std::string> film_channel_names(const RenderSettings& settings);

// Identifies the tree an image was rendered with (its nodes and leaf arrays): Film::tree_hash.
uint64_t tree_content_hash(const KdTree& tree);

// Identifies what else decides a render's pixels besides the film's size, samples, seed, bounces,
// sampler, scene and tree: the camera, the environment (its pixels included), whether the default
// light shines and the MIS switch. Film::settings_hash; merging refuses films that differ in it.
uint64_t render_settings_hash(const Scene& scene, const RenderSettings& settings);

}  // namespace kdray
