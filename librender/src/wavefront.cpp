// The wavefront driver (kernels/pt_wavefront.cl): one path per pixel in a device buffer, each
// step its own launch. Kept to measure against the megakernel; no path compaction.
#include "render_internal.h"

namespace kdray {
namespace {

struct WavefrontKernels {
  cl::Kernel begin, extend, shade, shadow, accumulate;
  cl::Buffer paths, hits;
};

}  // namespace

void run_wavefront_pass(RenderJob& job, uint32_t first, uint32_t count) {
  cl::Runtime& runtime = job.runtime;
  const size_t pixels = size_t(job.params.width) * job.params.height;
  WavefrontKernels k;
  k.paths = runtime.buffer(pixels * PT_PATH_BYTES, nullptr, CL_MEM_READ_WRITE);
  k.hits = runtime.buffer(pixels * sizeof(HitRecord), nullptr, CL_MEM_READ_WRITE);
  k.begin = cl::create_kernel(job.program, "pt_wave_begin");
  k.extend = cl::create_kernel(job.program, "pt_wave_extend");
  k.shade = cl::create_kernel(job.program, "pt_wave_shade");
  k.shadow = cl::create_kernel(job.program, "pt_wave_shadow");
  k.accumulate = cl::create_kernel(job.program, "pt_wave_accumulate");
  const cl_uint begin_sample_arg = bind_scene_args(k.begin.get(), job.scene, job.params_buffer, k.paths);
  bind_scene_args(k.extend.get(), job.scene, job.params_buffer, k.paths, k.hits, job.counter, job.stats);
  bind_scene_args(k.shade.get(), job.scene, job.params_buffer, k.paths, k.hits);
  bind_scene_args(k.shadow.get(), job.scene, job.params_buffer, k.paths, job.counter, job.stats);
  bind_scene_args(k.accumulate.get(), job.scene, job.params_buffer, k.paths, job.film, job.stats);

  job.set_pass(first, count);
  cl_command_queue queue = runtime.queue();
  // Path vertices 0..max_bounces+1 (see pt_path_shade) need max_bounces + 2 extensions.
  const uint32_t steps = job.params.max_bounces + 2;
  for (uint32_t sample = first; sample < first + count; ++sample) {
    cl::set_arg(k.begin.get(), begin_sample_arg, sample);
    cl::run_kernel(queue, k.begin.get(), pixels, job.local_size);
    for (uint32_t step = 0; step < steps; ++step) {
      cl::zero_buffer(queue, job.counter, sizeof(cl_uint));
      cl::run_kernel(queue, k.extend.get(), job.global_size, job.local_size);
      cl::run_kernel(queue, k.shade.get(), pixels, job.local_size);
      cl::zero_buffer(queue, job.counter, sizeof(cl_uint));
      cl::run_kernel(queue, k.shadow.get(), job.global_size, job.local_size);
    }
    cl::run_kernel(queue, k.accumulate.get(), pixels, job.local_size);
  }
  cl::check(clFinish(queue), "clFinish");
}

}  // namespace kdray
