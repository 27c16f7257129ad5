// The view a render takes: the camera (the settings', the scene's first or the default one),
// the image size its aspect ratio gives, and the camera as the kernels' parameters.
#include "render_internal.h"

#include <kdray/error.h>
#include <kdray/render.h>

#include <algorithm>
#include <cmath>
#include <cstdint>

namespace kdray {
namespace {

bool finite(const Vec3& v) { return std::isfinite(v.x) && std::isfinite(v.y) && std::isfinite(v.z); }
Vec3 sub(const Vec3& a, const Vec3& b) { return {a.x - b.x, a.y - b.y, a.z - b.z}; }
Vec3 cross(const Vec3& a, const Vec3& b) {
  return {a.y * b.z - a.z * b.y, a.z * b.x - a.x * b.z, a.x * b.y - a.y * b.x};
}
float length(const Vec3& v) { return std::sqrt(v.x * v.x + v.y * v.y + v.z * v.z); }
Vec3 scale(const Vec3& v, float s) { return {v.x * s, v.y * s, v.z * s}; }
void store(float* out, const Vec3& v) {
  out[0] = v.x;
  out[1] = v.y;
  out[2] = v.z;
  out[3] = 0;
}

}  // namespace

void set_camera(PtRenderParams& params, const Camera& camera, uint32_t width, uint32_t height) {
  Vec3 forward = sub(camera.target, camera.position);
  forward = scale(forward, 1.0f / length(forward));
  Vec3 right = cross(forward, camera.up);
  right = scale(right, 1.0f / length(right));
  Vec3 up = cross(right, forward);
  // The image plane's half-height: at unit distance for a perspective view, in scene units for an
  // orthographic one.
  float half_height = camera.projection == Projection::Orthographic
                          ? camera.orthographic_half_height
                          : std::tan(camera.vertical_fov_degrees * 3.14159265358979f / 360.0f);
  store(params.cam_origin, camera.position);
  store(params.cam_forward, forward);
  store(params.cam_right, scale(right, half_height * float(width) / float(height)));
  store(params.cam_up, scale(up, half_height));
}

Camera render_camera(const Scene& scene, const RenderSettings& settings) {
  Camera camera = settings.camera         ? *settings.camera
                  : scene.cameras.empty() ? default_camera(scene_bounds(scene))
                                          : scene.cameras.front();
  Vec3 forward = sub(camera.target, camera.position);
  if (!finite(camera.position) || !finite(camera.target) || !finite(camera.up) || !(length(forward) > 0) ||
      !(length(cross(forward, camera.up)) > 0)) {
    throw Error("", "degenerate camera: position, target and up must be finite, distinct and not collinear");
  }
  if (settings.fov_degrees > 0) camera.vertical_fov_degrees = settings.fov_degrees;
  if (!(camera.vertical_fov_degrees > 0 && camera.vertical_fov_degrees < 180)) {
    throw Error("", "vertical field of view must be between 0 and 180 degrees");
  }
  if (camera.projection == Projection::Orthographic &&
      !(camera.orthographic_half_height > 0 && std::isfinite(camera.orthographic_half_height))) {
    throw Error("", "orthographic camera '" + camera.name + "' has no positive extent");
  }
  return camera;
}

void resolve_image_size(const Camera& camera, uint32_t& width, uint32_t& height) {
  const double aspect = camera.aspect_ratio > 0 ? camera.aspect_ratio : 1.0;
  auto side = [](double length) { return uint32_t(std::clamp(std::lround(length), 1l, long(UINT32_MAX))); };
  if (width == 0 && height == 0) {
    const double longer = RenderSettings::kDefaultSize;
    width = aspect >= 1 ? uint32_t(longer) : side(longer * aspect);
    height = aspect >= 1 ? side(longer / aspect) : uint32_t(longer);
  } else if (height == 0) {
    height = side(width / aspect);
  } else if (width == 0) {
    width = side(height * aspect);
  }
}

RenderSettings resolve_view(const Scene& scene, RenderSettings settings) {
  settings.camera = render_camera(scene, settings);
  resolve_image_size(*settings.camera, settings.width, settings.height);
  return settings;
}

}  // namespace kdray
