/* Wavefront form of the same path tracer, kept to measure it against the megakernel
 * (librender/src/wavefront.cpp): one path per pixel lives in a global buffer and each step is
 * its own kernel: begin -> (closest hit -> shade -> shadow) per bounce -> accumulate. The two
 * trace kernels use persistent threads fetching batches of paths from an atomic counter. */
#include "pt_kernel_args.h"

#define PT_WAVE_BATCH 16u

/* Steps *i to this work-item's next path, claiming a new batch [*i, *end) from the counter when
 * the current one is done (start with *i = *end = 0); false once every path is taken. */
KD_INLINE bool pt_wave_next(__global uint* next_path, __global const PtRenderParams* params, uint* i, uint* end) {
  if (++*i < *end) return true;
  uint count = params->width * params->height;
  *i = atomic_add(next_path, PT_WAVE_BATCH);
  *end = min(*i + PT_WAVE_BATCH, count);
  return *i < count;
}

__kernel void pt_wave_begin(PT_SCENE_ARGS, __global PtPath* paths, uint sample) {
  uint pixel = get_global_id(0);
  if (pixel >= params->width * params->height) return;
  PtPath path;
  pt_path_begin(&path, params, pixel, sample);
  paths[pixel] = path;
}

__kernel void pt_wave_extend(PT_SCENE_ARGS, __global PtPath* paths, __global HitRecord* hits,
                             __global uint* next_path, __global ulong* stats) {
  PtSceneData scene = PT_MAKE_SCENE();
  ulong rays = 0;
  for (uint i = 0, end = 0; pt_wave_next(next_path, params, &i, &end);) {
    if (!paths[i].alive) continue;
    PtPath path = paths[i];
    hits[i] = kd_intersect_closest(&scene.kd, pt_path_ray(&path));
    ++rays;
  }
  pt_add_stats(stats, rays, 0);
}

__kernel void pt_wave_shade(PT_SCENE_ARGS, __global PtPath* paths, __global const HitRecord* hits) {
  PtSceneData scene = PT_MAKE_SCENE();
  uint i = get_global_id(0);
  if (i >= params->width * params->height || !paths[i].alive) return;
  PtPath path = paths[i];
  pt_path_shade(&path, &scene, params, hits[i]);
  paths[i] = path;
}

__kernel void pt_wave_shadow(PT_SCENE_ARGS, __global PtPath* paths, __global uint* next_path,
                             __global ulong* stats) {
  PtSceneData scene = PT_MAKE_SCENE();
  ulong rays = 0;
  for (uint i = 0, end = 0; pt_wave_next(next_path, params, &i, &end);) {
    if (!paths[i].shadow_pending) continue;
    PtPath path = paths[i];
    pt_path_resolve_shadow(&path, pt_path_occluded(&scene, &path, params));
    ++rays;
    paths[i] = path;
  }
  pt_add_stats(stats, rays, 0);
}

__kernel void pt_wave_accumulate(PT_SCENE_ARGS, __global const PtPath* paths, __global long* film,
                                 __global ulong* stats) {
  uint pixel = get_global_id(0);
  if (pixel >= params->width * params->height) return;
  long sums[PT_MAX_FILM_CHANNELS];
  for (uint c = 0; c < PT_MAX_FILM_CHANNELS; ++c) sums[c] = 0;
  uint nonfinite = 0;
  PtPath path = paths[pixel];
  pt_path_accumulate(&path, params, sums, &nonfinite);
  for (uint c = 0; c < params->film_channels; ++c) film[(size_t)pixel * params->film_channels + c] += sums[c];
  if (nonfinite) atom_add(&stats[1], (ulong)nonfinite);
}
