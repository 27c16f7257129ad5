/* The buffers every path-tracing kernel takes first, in this order, then the PtRenderParams:
 * one list that the kernel signatures (PT_SCENE_ARGS, kernels/pt_kernel_args.h) and librender's
 * binder (bind_scene_args) both expand, so an argument added here is declared and bound in the
 * same place of the list on both sides. GEOMETRY(type, name) entries are what traversal reads,
 * the host's DeviceGeometry::name (the trace kernel uploads those alone), SHADING(type, name)
 * entries its DeviceScene::name, each the PtSceneData field of its name; type is the device
 * element type. */
#ifndef PT_SCENE_ARGS_H
#define PT_SCENE_ARGS_H

#define PT_SCENE_BUFFERS(GEOMETRY, SHADING) \
  GEOMETRY(KdNode, nodes)                   \
  GEOMETRY(kd_u32, leaf_blocks)             \
  SHADING(float, triangle_vertices)         \
  SHADING(kd_u32, indices)                  \
  SHADING(kd_u32, material_ids)             \
  SHADING(PtMaterial, materials)            \
  SHADING(float, normals)                   \
  SHADING(float, uvs)                       \
  SHADING(float, tangents)                  \
  SHADING(PtTexture, textures)              \
  SHADING(float4, texels)                   \
  SHADING(PtLight, lights)                  \
  SHADING(kd_u32, light_guide)              \
  SHADING(float, env_texels)                \
  SHADING(float, env_cdf)                   \
  SHADING(PtPunctual, punctuals)

#endif /* PT_SCENE_ARGS_H */
