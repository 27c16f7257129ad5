// Internal to librender: what the render driver (render.cpp) shares with the wavefront driver
// (wavefront.cpp) and the host renderer (render_host.cpp).
#pragma once

#include "device_scene.h"

#include <kdray/environment.h>
#include <kdray/kdtree.h>
#include <kdray/opencl_device.h>
#include <kdray/render_settings.h>
#include <kdray/scene.h>

#include <kernels/pt_types.h>

#include <cstdint>
#include <memory>
#include <string>
#include <vector>

namespace kdray {

// One participant of a render, an OpenCL device or the host: renders sample ranges into a film
// of its own.
class RenderWorker {
 public:
  virtual ~RenderWorker() = default;
  // Adds samples [first, first + count) of every pixel to its film.
  virtual void pass(uint32_t first, uint32_t count) = 0;
  // Adds its film to `sums` (the Film::sums layout) and its ray and non-finite counts to `stats`.
  virtual void add_film(std::vector<int64_t>& sums, RenderStats& stats) = 0;

  RenderStats stats;      // device, kernel, build and upload
  int device_index = -1;  // in list_devices(); -1 for the host
};

// What a render derives from the scene and its settings, resolved once (resolve_render,
// render.cpp) and handed to every worker.
struct ResolvedRender {
  RenderSettings settings;  // the camera and the image size filled in (resolve_view), checked
  std::shared_ptr<const Environment> environment;  // render_environment: null when none lights it
  uint32_t feature_bits = 0;                       // kernel_feature_bits

  const Camera& camera() const { return *settings.camera; }
};
ResolvedRender resolve_render(const Scene& scene, const RenderSettings& requested);

// The PT_FEATURE_* bits of a render (kernels/pt_codes.h): what its kernel is built with
// (kernel_features.cpp), and their build options on `device`, a GPU or not.
uint32_t kernel_feature_bits(const Scene& scene, const RenderSettings& settings, const Camera& camera,
                             const Environment* environment);
std::string kernel_feature_options(uint32_t feature_bits, const DeviceSelection& device, bool gpu);
// The option with which a CPU's program computes a bounce's sample values in lanes (kernels/pt_rng.h).
inline constexpr const char* kBounceBitsInLanesOption = " -DPT_BOUNCE_BITS_IN_LANES";

// The camera as the kernels' parameters for a width x height image (render_view.cpp).
void set_camera(PtRenderParams& params, const Camera& camera, uint32_t width, uint32_t height);

// The kernels' parameters of a render, but for the sample range (set per pass).
PtRenderParams render_params(const ResolvedRender& render, const SceneArrays& arrays);

// Film::settings_hash of a resolved render (render_hashes.cpp; render_settings_hash in render.h).
uint64_t render_settings_hash(const RenderSettings& settings, const Camera& camera, const Environment* environment);

// The host worker: the C++ build of kernels/pt_path.h on the CPU (render_host.cpp).
std::unique_ptr<RenderWorker> prepare_host(const Scene& scene, const KdTree& tree, const ResolvedRender& render,
                                           const DeviceSelection& device);

// The state one render keeps on an OpenCL device.
struct RenderJob {
  cl::Runtime& runtime;
  DeviceScene scene;
  PtRenderParams params;
  cl::Buffer params_buffer, film, counter, stats;
  cl_program program = nullptr;
  size_t local_size = 0, global_size = 0;

  // Uploads params with this pass's sample range.
  void set_pass(uint32_t sample_offset, uint32_t sample_count);
};

// Renders samples [first, first + count) of every pixel with the wavefront kernels into job.film.
void run_wavefront_pass(RenderJob& job, uint32_t first, uint32_t count);

}  // namespace kdray
