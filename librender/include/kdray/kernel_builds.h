// The OpenCL programs kdray builds and the exact options it passes to the driver, so that
// they can be compiled for GPU targets where there is no GPU (scripts/gpu-compile.sh).
#pragma once

#include <kdray/render.h>

#include <cstdint>
#include <string>
#include <vector>

namespace kdray {

struct KernelBuild {
  std::string name;        // megakernel, wavefront, trace-short-stack, trace-full-stack
  std::string entry_file;  // in kernels/
  std::string options;     // as clBuildProgram gets them
};

// The programs that rendering `scene` with `settings` (both forms) and tracing rays through it
// (kdtrace --stack short and full) build on a GPU that offers correctly rounded division and
// sqrt, as NVIDIA's and AMD's drivers do.
std::vector<KernelBuild> gpu_kernel_builds(const Scene& scene, const RenderSettings& settings);

}  // namespace kdray
