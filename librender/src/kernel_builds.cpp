#include <kdray/kernel_builds.h>

#include <kdray/device_build_options.h>
#include <kdray/trace_opencl.h>

#include <CL/cl.h>

namespace kdray {

std::vector<KernelBuild> gpu_kernel_builds(const Scene& scene, const RenderSettings& settings) {
  const std::string device_options = " " + device_build_options(CL_FP_CORRECTLY_ROUNDED_DIVIDE_SQRT);
  const std::string render_options = kernel_feature_options(scene, settings, DeviceSelection{}, true) + device_options;
  DeviceSelection full_stack;
  full_stack.short_stack_size = kernel_stack_size(TraversalStack::Full);
  return {{"megakernel", "pt_megakernel.cl", render_options},
          {"wavefront", "pt_wavefront.cl", render_options},
          {"trace-short-stack", "kd_trace.cl", trace_kernel_build(DeviceSelection{}, true).options + device_options},
          {"trace-full-stack", "kd_trace.cl", trace_kernel_build(full_stack, true).options + device_options}};
}

}  // namespace kdray
