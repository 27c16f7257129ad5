// Internal to librender: the arrays the path-tracing kernels read (PT_SCENE_BUFFERS of
// kernels/pt_scene_args.h, layouts of kernels/pt_types.h), built on the host from a scene, its
// tree and the environment. Building them needs no device: an OpenCL render uploads them
// (device_scene.h), the host render reads them in place (render_host.cpp).
#pragma once

#include <kdray/environment.h>
#include <kdray/kdtree.h>
#include <kdray/scene.h>
#include <kdray/tangents.h>

#include <kernels/pt_scene_args.h>
#include <kernels/pt_types.h>

#include <cstddef>
#include <cstdint>
#include <vector>

namespace kdray {

// Bytes the kernel reads as one buffer: the scene's or tree's own vector, or one built here.
struct HostArray {
  const void* data = nullptr;
  size_t bytes = 0;
};
template <typename T, typename Allocator>
HostArray host_array(const std::vector<T, Allocator>& values) {
  return {values.data(), values.size() * sizeof(T)};
}
template <typename T>
HostArray host_array(const TreeArray<T>& values) {
  return {values.data(), values.size() * sizeof(T)};
}

// The traversal's arrays (what the trace kernel reads too).
struct GeometryArrays {
#define KD_ARRAY_MEMBER(type, name) HostArray name;
#define KD_ARRAY_SKIP(type, name)
  PT_SCENE_BUFFERS(KD_ARRAY_MEMBER, KD_ARRAY_SKIP)
  float bounds_min[3] = {0, 0, 0}, bounds_max[3] = {0, 0, 0};
};

// Every array of a render. Views point into the scene, the tree and the storage below, so the
// scene and the tree must outlive it; it may be moved, not copied.
struct SceneArrays {
  GeometryArrays geometry;
  PT_SCENE_BUFFERS(KD_ARRAY_SKIP, KD_ARRAY_MEMBER)
#undef KD_ARRAY_MEMBER
#undef KD_ARRAY_SKIP
  uint32_t light_count = 0;        // emissive triangles in the power table
  uint32_t punctual_count = 0;
  float light_area_pdf_scale = 0;  // 1 / sum(luminance(Le) * area)

  // Storage of the arrays that the scene does not hold as the kernels read them.
  TraversalArray<float> gathered_vertices;  // what triangle_vertices views
  std::vector<Tangent> computed_tangents;
  std::vector<PtMaterial> device_materials;
  std::vector<PtTexture> device_textures;
  std::vector<float> device_texels, env_table;
  std::vector<PtLight> device_lights;
  std::vector<uint32_t> device_light_guide;
  std::vector<PtPunctual> device_punctuals;

  SceneArrays() = default;
  SceneArrays(SceneArrays&&) = default;
  SceneArrays(const SceneArrays&) = delete;
  SceneArrays& operator=(const SceneArrays&) = delete;
};

GeometryArrays geometry_arrays(const KdTree& tree);
// environment may be null (then its arrays are empty).
SceneArrays scene_arrays(const Scene& scene, const KdTree& tree, const Environment* environment);

}  // namespace kdray
