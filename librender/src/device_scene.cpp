// Upload of a scene's kernel arrays (see device_scene.h).
#include "device_scene.h"

namespace kdray {

namespace {
cl::Buffer upload(cl::Runtime& runtime, const HostArray& array) { return runtime.buffer(array.bytes, array.data); }
}  // namespace

DeviceGeometry upload_geometry(cl::Runtime& runtime, const GeometryArrays& geometry) {
  DeviceGeometry device;
#define KD_UPLOAD_GEOMETRY(type, name) device.name = upload(runtime, geometry.name);
#define KD_SKIP(type, name)
  PT_SCENE_BUFFERS(KD_UPLOAD_GEOMETRY, KD_SKIP)
#undef KD_UPLOAD_GEOMETRY
  return device;
}

DeviceScene upload_scene(cl::Runtime& runtime, const SceneArrays& arrays) {
  DeviceScene device;
  device.geometry = upload_geometry(runtime, arrays.geometry);
#define KD_UPLOAD_SHADING(type, name) device.name = upload(runtime, arrays.name);
  PT_SCENE_BUFFERS(KD_SKIP, KD_UPLOAD_SHADING)
#undef KD_UPLOAD_SHADING
#undef KD_SKIP
  return device;
}

cl_uint bind_scene_args(cl_kernel kernel, const DeviceScene& scene, const cl::Buffer& params) {
  cl_uint index = 0;
#define KD_BIND_GEOMETRY(type, name) cl::set_arg(kernel, index++, scene.geometry.name);
#define KD_BIND_SHADING(type, name) cl::set_arg(kernel, index++, scene.name);
  PT_SCENE_BUFFERS(KD_BIND_GEOMETRY, KD_BIND_SHADING)
#undef KD_BIND_GEOMETRY
#undef KD_BIND_SHADING
  cl::set_arg(kernel, index++, params);
  return index;
}

}  // namespace kdray
