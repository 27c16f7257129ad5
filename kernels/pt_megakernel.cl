/* Megakernel path tracer with persistent threads: about as many work-items as the device runs
 * at once; each takes the next pixel from a global atomic counter (every work-item
 * fetches its own work, with no assumption that work-items run in lockstep) and renders samples
 * sample_offset..sample_offset+sample_count-1 of it. Each pixel belongs to one work-item per
 * launch, so its film sums are updated without atomics. */
#include "pt_kernel_args.h"

__kernel void pt_render(PT_SCENE_ARGS, __global long* film, __global uint* next_pixel, __global ulong* stats) {
  PtSceneData scene = PT_MAKE_SCENE();
  uint pixel_count = params->width * params->height;
  ulong rays = 0;
  uint nonfinite = 0;
  for (;;) {
    uint pixel = atomic_inc(next_pixel);
    if (pixel >= pixel_count) break;
    rays += pt_render_pixel(&scene, params, pixel, film, &nonfinite);
  }
  pt_add_stats(stats, rays, nonfinite);
}
