// The host renderer (device "host"): kernels/pt_path.h compiled as C++ and run on the CPU with
// oneTBB, into the same fixed-point film as the OpenCL kernels, bit for bit.
//
// Determinism. One task sums all of a pixel's samples of a pass, in sample order, and the sums
// are fixed-point integers, so the film depends neither on the thread count nor on the passes.
//
// The path tracer itself, compiled for this CPU, is render_host_pixels.cpp. device_for_render
// makes the host the default where it is the faster CPU path.
#include "render_host_pixels.h"
#include "render_internal.h"

#include <kdray/clock.h>
#include <kdray/error.h>
#include <kdray/opencl_device.h>
#include <kdray/render.h>
#include <kdray/threads.h>
#include <kdray/trace_opencl.h>

#include <kernels/pt_types.h>

#include <algorithm>

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include <atomic>
#include <chrono>
#include <cstdlib>
#include <cstring>
#include <string>
#include <utility>
#include <vector>

namespace kdray {
namespace {

// Pixels per task: consecutive pixels of a row, whose rays are coherent, and enough paths that
// the paths in lanes keep their batch of rays full (path_lanes.h: 2048 paths in flight) in passes
// of 8 samples and more.
constexpr uint32_t kPixelsPerTask = 256;

class HostRender : public RenderWorker {
 public:
  HostRender(SceneArrays arrays, const PtRenderParams& params, unsigned threads, RenderHostPixels render_pixels)
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
                          uint32_t nonfinite = 0;
                          rays_ += render_pixels_(arrays_, params, pixels.begin(), pixels.end(), film_.data(),
                                                  &nonfinite);
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
  const RenderHostPixels render_pixels_;
  const unsigned threads_;
  std::vector<int64_t> film_;
  std::atomic<uint64_t> rays_{0}, nonfinite_{0};
};

bool cpu_has_x86_64_v3() {
#ifdef KDRAY_HOST_PIXELS_HAVE_X86_64_V3
  // The level's features that GCC and clang both name (clang 14 and 15 know no "x86-64-v3"); the
  // CPUs that have them have the rest of it (F16C, LZCNT, MOVBE).
  return __builtin_cpu_supports("avx2") && __builtin_cpu_supports("bmi") && __builtin_cpu_supports("bmi2") &&
         __builtin_cpu_supports("fma");
#else
  return false;
#endif
}

}  // namespace

std::string device_for_render() {
  enum OpenCl { kNone, kCpuOnly, kGpu };
  static const OpenCl opencl = [] {
    try {
      const std::vector<DeviceInfo> devices = list_devices();
      if (std::any_of(devices.begin(), devices.end(), [](const DeviceInfo& d) { return d.is_gpu; })) return kGpu;
      return devices.empty() ? kNone : kCpuOnly;
    } catch (const Error&) {
      return kNone;  // no OpenCL platform: the host renders without one
    }
  }();
  if (opencl == kGpu) return "auto";
  return cpu_has_x86_64_v3() || opencl == kNone ? kHostDevice : "auto";
}

HostPixelsBuild host_pixels_build(size_t gathered_floats) {
  const char* asked = std::getenv("KDRAY_HOST_ISA");
  const bool generic = asked != nullptr && std::string(asked) == "generic";
  if (asked != nullptr && !generic) {
    throw Error("", std::string("KDRAY_HOST_ISA is '") + asked + "': the one value it takes is 'generic'");
  }
  const char* lanes = std::getenv("KDRAY_HOST_LANES");
  const bool lanes_off = lanes != nullptr && std::string(lanes) == "off";
  if (lanes != nullptr && !lanes_off) {
    throw Error("", std::string("KDRAY_HOST_LANES is '") + lanes + "': the one value it takes is 'off'");
  }
#ifdef KDRAY_HOST_PIXELS_HAVE_X86_64_V3
  const bool x86_64_v3 = cpu_has_x86_64_v3();
  if (!generic && x86_64_v3 && !lanes_off && host_pixels_x86_64_v3::paths_in_lanes_apply(gathered_floats)) {
    return {host_pixels_x86_64_v3::render_pixels_in_lanes, "x86-64-v3, paths in lanes", true};
  }
  if (!generic && x86_64_v3) return {host_pixels_x86_64_v3::render_pixels, "x86-64-v3", true};
#else
  (void)gathered_floats;
  (void)lanes_off;
#endif
  return {host_pixels_generic::render_pixels, "generic", false};
}

std::unique_ptr<RenderWorker> prepare_host(const Scene& scene, const KdTree& tree, const ResolvedRender& render,
                                           const DeviceSelection& device) {
  // The host's traversal is the CPU's: the fast path where it applies (trace_opencl.h).
  if (device.traversal && *device.traversal != TraversalPath::FastWhereSafe) {
    throw Error("", "the host renders with the fast traversal; the robust traversal alone is for OpenCL devices");
  }
  const auto start = std::chrono::steady_clock::now();
  SceneArrays arrays = scene_arrays(scene, tree, render.environment.get());
  const PtRenderParams params = render_params(render, arrays);
  // the longest arrays the paths in lanes gather from: the triangles' corners, the vertex normals
  const size_t gathered_floats = std::max(arrays.triangle_vertices.bytes, arrays.normals.bytes) / sizeof(float);
  const HostPixelsBuild build = host_pixels_build(gathered_floats);
  auto host = std::make_unique<HostRender>(std::move(arrays), params, device.threads, build.render);
  RenderStats& stats = host->stats;
  stats.device = kHostDevice;
  // Every feature compiled in; the scene's own, as an OpenCL build would name them, gate them.
  std::string options = kernel_feature_options(render.feature_bits, DeviceSelection{}, false);
  // as a CPU's program would be built, less the sample values in lanes where this build has none
  const size_t lanes = options.find(kBounceBitsInLanesOption);
  if (!build.bounce_bits_in_lanes && lanes != std::string::npos) options.erase(lanes, std::strlen(kBounceBitsInLanesOption));
  const size_t defines = options.find(" -D");
  stats.kernel_options = "-DKD_ALL_FEATURES" + (defines == std::string::npos ? "" : options.substr(defines));
  stats.default_light = render.environment && !render.settings.environment;
  stats.build_source = std::string("built in, ") + build.name;
  stats.traversal = traversal_path_name(TraversalPath::FastWhereSafe);
  stats.threads = host->threads();
  stats.upload_seconds = seconds_since(start);
  return host;
}

}  // namespace kdray
