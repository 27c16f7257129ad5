/* The argument list every path-tracing kernel starts with (bound by librender's RenderKernelArgs in
 * this order), and the scene view built from it. OpenCL C only. */
#ifndef PT_KERNEL_ARGS_H
#define PT_KERNEL_ARGS_H

#pragma OPENCL EXTENSION cl_khr_int64_base_atomics : enable

#include "pt_path.h"

#define PT_SCENE_ARGS                                                                              \
  __global const KdNode *nodes, __global const kd_u32 *leaf_triangles,                                   \
      __global const float *triangle_vertices, __global const kd_u32 *indices,                           \
      __global const kd_u32 *material_ids,                                                               \
      __global const PtMaterial *materials, __global const float *normals, __global const float *uvs,    \
      __global const PtTexture *textures, __global const float4 *texels, __global const PtLight *lights, \
      __global const float *env_texels, __global const float *env_cdf, __global const PtPunctual *punctuals, \
      __global const PtRenderParams *params

inline PtSceneData pt_make_scene(__global const KdNode* nodes, __global const kd_u32* leaf_triangles,
                                 __global const float* triangle_vertices, __global const kd_u32* indices,
                                 __global const kd_u32* material_ids, __global const PtMaterial* materials,
                                 __global const float* normals, __global const float* uvs,
                                 __global const PtTexture* textures, __global const float4* texels,
                                 __global const PtLight* lights, __global const float* env_texels,
                                 __global const float* env_cdf, __global const PtPunctual* punctuals,
                                 __global const PtRenderParams* params) {
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
  scene.textures = textures;
  scene.texels = texels;
  scene.lights = lights;
  scene.env_texels = env_texels;
  scene.env_cdf = env_cdf;
  scene.punctuals = punctuals;
  return scene;
}
#define PT_MAKE_SCENE()                                                                               \
  pt_make_scene(nodes, leaf_triangles, triangle_vertices, indices, material_ids, materials, normals, \
                uvs, textures, texels, lights, env_texels, env_cdf, punctuals, params)

/* stats[0]: rays traced, stats[1]: non-finite sample values. */
inline void pt_add_stats(__global ulong* stats, ulong rays, uint nonfinite) {
  atom_add(&stats[0], rays);
  if (nonfinite) atom_add(&stats[1], (ulong)nonfinite);
}

#endif /* PT_KERNEL_ARGS_H */
