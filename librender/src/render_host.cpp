// The host renderer (device "host"): kernels/pt_path.h compiled as C++ and run on the CPU with
// oneTBB, into the same fixed-point film as the OpenCL kernels, bit for bit.
//
// Forms. RenderForm::Megakernel runs each path to its end, as the megakernel does;
// RenderForm::Lanes runs packets of paths (render_lanes.cpp). Both write the same film.
//
// Determinism. One task sums all of a pixel's samples of a pass, and the sums are fixed-point
// integers, so the film depends neither on the thread count nor on the passes.
#include "host_path.h"  // first: its defines shape the device code's headers
#include "render_internal.h"

#include <kdray/clock.h>
#include <kdray/threads.h>

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include <atomic>
#include <chrono>
#include <utility>

namespace kdray {
namespace {

// Pixels per task: consecutive pixels of a row, whose rays are coherent.
constexpr uint32_t kPixelsPerTask = 16;

// Samples params.sample_offset .. + sample_count - 1 of pixels [begin, end), one path at a time.
void render_pixels_one_by_one(const SceneArrays& arrays, const PtRenderParams& params, uint32_t begin, uint32_t end,
                              int64_t* film, uint64_t* rays, uint32_t* nonfinite) {
  const PtSceneData scene = make_scene(arrays, &params);
  for (uint32_t pixel = begin; pixel != end; ++pixel) *rays += pt_render_pixel(&scene, &params, pixel, film, nonfinite);
}

class HostRender : public RenderWorker {
 public:
  HostRender(SceneArrays arrays, const PtRenderParams& params, unsigned threads, HostPixelRenderer render_pixels)
      : arrays_(std::move(arrays)), params_(params), render_pixels_(render_pixels),
        threads_(thread_count(threads)),
        film_(size_t(params.width) * params.height * params.film_channels, 0) {}

  unsigned threads() const { return threads_; }

  void pass(uint32_t first, uint32_t count) override {
    PtRenderParams params = params_;
    params.sample_offset = first;
    params.sample_count = count;
    run_with_threads(threads_, [&] {
      tbb::parallel_for(tbb::blocked_range<uint32_t>(0, params.width * params.height, kPixelsPerTask),
                        [&](const tbb::blocked_range<uint32_t>& pixels) {
                          uint64_t rays = 0;
                          uint32_t nonfinite = 0;
                          render_pixels_(arrays_, params, pixels.begin(), pixels.end(), film_.data(), &rays,
                                         &nonfinite);
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
  const HostPixelRenderer render_pixels_;
  const unsigned threads_;
  std::vector<int64_t> film_;
  std::atomic<uint64_t> rays_{0}, nonfinite_{0};
};

}  // namespace

std::unique_ptr<RenderWorker> prepare_host(const Scene& scene, const KdTree& tree, const RenderSettings& settings,
                                           const DeviceSelection& device, const Camera& camera,
                                           const std::shared_ptr<const Environment>& environment) {
  const auto start = std::chrono::steady_clock::now();
  SceneArrays arrays = scene_arrays(scene, tree, environment.get());
  const PtRenderParams params = render_params(scene, settings, camera, arrays, environment.get());
  const bool lanes = settings.form == RenderForm::Lanes;
  auto host = std::make_unique<HostRender>(std::move(arrays), params, device.threads,
                                           lanes ? render_pixels_in_lanes : render_pixels_one_by_one);
  RenderStats& stats = host->stats;
  stats.device = kHostDevice;
  // Every feature compiled in; the scene's own, as an OpenCL build would name them, gate them.
  const std::string options = kernel_feature_options(scene, settings, DeviceSelection{});
  const size_t defines = options.find(" -D");
  stats.kernel_options = "-DKD_ALL_FEATURES" + (defines == std::string::npos ? "" : options.substr(defines));
  stats.default_light = environment && !settings.environment;
  stats.build_source = "built in";
  stats.threads = host->threads();
  stats.upload_seconds = seconds_since(start);
  return host;
}

}  // namespace kdray
