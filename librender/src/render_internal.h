// Internal to librender: the state one render keeps on the device, shared by the megakernel
// driver (render.cpp) and the wavefront driver (wavefront.cpp).
#pragma once

#include "device_scene.h"

#include <kdray/render.h>

#include <kernels/pt_types.h>

namespace kdray {

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
