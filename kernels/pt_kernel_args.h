/* The argument list every path-tracing kernel starts with (kernels/pt_scene_args.h), and the scene
 * view built from it. OpenCL C only. */
#ifndef PT_KERNEL_ARGS_H
#define PT_KERNEL_ARGS_H

#pragma OPENCL EXTENSION cl_khr_int64_base_atomics : enable

#include "pt_path.h"
#include "pt_scene_args.h"

#define PT_SCENE_ARG(type, name) __global const type *name,
#define PT_SCENE_ARGS PT_SCENE_BUFFERS(PT_SCENE_ARG, PT_SCENE_ARG) __global const PtRenderParams *params
#define PT_SCENE_ARG_NAME(type, name) name,

inline PtSceneData pt_make_scene(PT_SCENE_ARGS) {
  PtSceneData scene;
  scene.kd.nodes = nodes;
  scene.kd.leaf_triangles = leaf_triangles;
  scene.kd.triangle_vertices = triangle_vertices;
  for (int i = 0; i < 3; ++i) {
    scene.kd.bounds_min[i] = params->bounds_min[i];
    scene.kd.bounds_max[i] = params->bounds_max[i];
  }
  scene.indices = indices;
  scene.material_ids = material_ids;
  scene.materials = materials;
  scene.normals = normals;
  scene.uvs = uvs;
  scene.tangents = tangents;
  scene.textures = textures;
  scene.texels = texels;
  scene.lights = lights;
  scene.env_texels = env_texels;
  scene.env_cdf = env_cdf;
  scene.punctuals = punctuals;
  scene.coat_tables = coat_tables;
  return scene;
}
#define PT_MAKE_SCENE() pt_make_scene(PT_SCENE_BUFFERS(PT_SCENE_ARG_NAME, PT_SCENE_ARG_NAME) params)

/* stats[0]: rays traced, stats[1]: non-finite sample values. */
inline void pt_add_stats(__global ulong* stats, ulong rays, uint nonfinite) {
  atom_add(&stats[0], rays);
  if (nonfinite) atom_add(&stats[1], (ulong)nonfinite);
}

#endif /* PT_KERNEL_ARGS_H */
