// The host renderer (device "host"): kernels/pt_path.h compiled as C++ and run on the CPU with
// oneTBB, into the same fixed-point film as the OpenCL kernels, bit for bit.
//
// Features. An OpenCL program is built for its scene's feature set (KD_FEATURE_*), which keeps
// PoCL's compile short and the kernel small. Here the integrator is compiled once with every
// feature in (KD_ALL_FEATURES) rather than in up to 2^14 variants: each KD_FEATURE_* part either
// acts only on data the scene has (a material's type, a texture index >= 0, a light count) or
// asks the scene's feature bits (PT_USES, kernels/pt_types.h), so where a feature is absent it
// does what the kernel built without it does, operation for operation. The MIS switch (KD_MIS_OFF)
// is compiled in and read from the bits the same way. tests/render/cpu_integrator_*_test.cpp
// check the films against kernels of different feature sets bit for bit.
//
// Determinism. One task sums all of a pixel's samples of a pass, in sample order, and the sums
// are fixed-point integers, so the film depends neither on the thread count nor on the passes.
//
// Compiled with -ffp-contract=off (librender/CMakeLists.txt), as the kernels are (kd_compat.h).
#define KD_ALL_FEATURES
#define KD_FEATURE_EMISSION
#define KD_FEATURE_MIRROR
#define KD_FEATURE_GLOSSY
#define KD_FEATURE_GLASS
#define KD_FEATURE_METALLIC_ROUGHNESS
#define KD_FEATURE_ALPHA
#define KD_FEATURE_TEXTURES
#define KD_FEATURE_METAL_ROUGH_TEXTURE
#define KD_FEATURE_NORMAL_MAP
#define KD_FEATURE_EMISSIVE_TEXTURE
#define KD_FEATURE_NORMALS
#define KD_FEATURE_ENVIRONMENT
#define KD_FEATURE_PUNCTUAL
#define KD_FEATURE_ORTHOGRAPHIC
#define KD_MIS_OFF  // a switch, asked of the scene's bits as the features are

#include "render_internal.h"

#include <kdray/clock.h>
#include <kdray/error.h>
#include <kdray/render.h>
#include <kdray/threads.h>
#include <kdray/trace_opencl.h>

#include <kernels/kd_types.h>
#include <kernels/kd_vector.h>
#include <kernels/pt_types.h>

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include <atomic>
#include <chrono>
#include <utility>

// The device code, in this file's own namespace: no other file compiles it with these defines.
namespace {
#include <kernels/pt_path.h>
}  // namespace

namespace kdray {
namespace {

// Pixels per task: consecutive pixels of a row, whose rays are coherent.
constexpr uint32_t kPixelsPerTask = 16;

PtSceneData make_scene(const SceneArrays& arrays, const PtRenderParams* params) {
#define KD_HOST_GEOMETRY(type, name) const type* name = static_cast<const type*>(arrays.geometry.name.data);
#define KD_HOST_SHADING(type, name) const type* name = static_cast<const type*>(arrays.name.data);
  PT_SCENE_BUFFERS(KD_HOST_GEOMETRY, KD_HOST_SHADING)
#undef KD_HOST_GEOMETRY
#undef KD_HOST_SHADING
  return PT_MAKE_SCENE();
}

class HostRender : public RenderWorker {
 public:
  HostRender(SceneArrays arrays, const PtRenderParams& params, unsigned threads)
      : arrays_(std::move(arrays)), params_(params),
        threads_(thread_count(threads)),
        film_(size_t(params.width) * params.height * params.film_channels, 0) {}

  unsigned threads() const { return threads_; }

  void pass(uint32_t first, uint32_t count) override {
    PtRenderParams params = params_;
    params.sample_offset = first;
    params.sample_count = count;
    const PtSceneData scene = make_scene(arrays_, &params);
    run_with_threads(threads_, [&] {
      tbb::parallel_for(tbb::blocked_range<uint32_t>(0, params.width * params.height, kPixelsPerTask),
                        [&](const tbb::blocked_range<uint32_t>& pixels) {
                          uint64_t rays = 0;
                          uint nonfinite = 0;
                          for (uint32_t pixel = pixels.begin(); pixel != pixels.end(); ++pixel)
                            rays += pt_render_pixel(&scene, &params, pixel, film_.data(), &nonfinite);
                          rays_ += rays;
                          nonfinite_ += nonfinite;
                        });
    });
  }

  void add_film(std::vector<int64_t>& sums, RenderStats& totals) override {
    for (size_t i = 0; i < sums.size(); ++i) sums[i] += film_[i];
    totals.rays += rays_;
    totals.nonfinite_values += nonfinite_;
  }

 private:
  const SceneArrays arrays_;
  const PtRenderParams params_;
  const unsigned threads_;
  std::vector<int64_t> film_;
  std::atomic<uint64_t> rays_{0}, nonfinite_{0};
};

}  // namespace

std::unique_ptr<RenderWorker> prepare_host(const Scene& scene, const KdTree& tree, const ResolvedRender& render,
                                           const DeviceSelection& device) {
  // The host's traversal is the CPU's: the fast path where it applies (trace_opencl.h).
  if (device.traversal && *device.traversal != TraversalPath::FastWhereSafe) {
    throw Error("", "the host renders with the fast traversal; the robust traversal alone is for OpenCL devices");
  }
  const auto start = std::chrono::steady_clock::now();
  SceneArrays arrays = scene_arrays(scene, tree, render.environment.get());
  const PtRenderParams params = render_params(render, arrays);
  auto host = std::make_unique<HostRender>(std::move(arrays), params, device.threads);
  RenderStats& stats = host->stats;
  stats.device = kHostDevice;
  // Every feature compiled in; the scene's own, as an OpenCL build would name them, gate them.
  const std::string options = kernel_feature_options(render.feature_bits, DeviceSelection{}, false);
  const size_t defines = options.find(" -D");
  stats.kernel_options = "-DKD_ALL_FEATURES" + (defines == std::string::npos ? "" : options.substr(defines));
  stats.default_light = render.environment && !render.settings.environment;
  stats.build_source = "built in";
  stats.traversal = traversal_path_name(TraversalPath::FastWhereSafe);
  stats.threads = host->threads();
  stats.upload_seconds = seconds_since(start);
  return host;
}

}  // namespace kdray
