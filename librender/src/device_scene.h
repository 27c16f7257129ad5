// Internal to librender: the one place where a scene's kernel arrays (scene_arrays.h) become
// device buffers, shared by the renderer and the trace kernel.
#pragma once

#include "opencl_runtime.h"
#include "scene_arrays.h"

namespace kdray {

struct DeviceGeometry {
  cl::Buffer nodes, leaf_blocks;
};

struct DeviceScene {
  DeviceGeometry geometry;
  cl::Buffer triangle_vertices;  // gather_triangle_vertices: what shading reads of a hit
  cl::Buffer indices;            // 3 per triangle: vertex numbers of normals and uvs
  cl::Buffer material_ids, materials, normals, uvs, tangents, textures, texels, lights, light_guide;
  cl::Buffer env_texels, env_cdf;  // kernels/pt_environment.h
  cl::Buffer punctuals;            // PtPunctual per Scene::lights entry
};

DeviceGeometry upload_geometry(cl::Runtime& runtime, const GeometryArrays& geometry);
DeviceScene upload_scene(cl::Runtime& runtime, const SceneArrays& arrays);

// Binds the PT_SCENE_ARGS arguments of kernel (the list of kernels/pt_scene_args.h), params last,
// then `rest` in order; returns the index of the next argument.
cl_uint bind_scene_args(cl_kernel kernel, const DeviceScene& scene, const cl::Buffer& params);
template <typename... Rest>
cl_uint bind_scene_args(cl_kernel kernel, const DeviceScene& scene, const cl::Buffer& params, const Rest&... rest) {
  cl_uint index = bind_scene_args(kernel, scene, params);
  (cl::set_arg(kernel, index++, rest), ...);
  return index;
}

}  // namespace kdray
