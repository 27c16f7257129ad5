#include <kdray/scene.h>

#include <algorithm>
#include <cmath>
#include <iterator>

namespace kdray {

namespace {

// The names reports use, indexed by each enum's value (its code in kernels/pt_codes.h, counted
// from 0); each static_assert ties a table's length to its enum's last value.
constexpr const char* kMaterialTypeNames[] = {"diffuse", "emissive", "mirror", "rough-conductor", "dielectric",
                                              "metallic-roughness"};
constexpr const char* kAlphaModeNames[] = {"opaque", "mask", "blend"};
constexpr const char* kLightTypeNames[] = {"point", "spot", "directional"};
constexpr const char* kProjectionNames[] = {"perspective", "orthographic"};
static_assert(std::size(kMaterialTypeNames) == uint32_t(MaterialType::MetallicRoughness) + 1);
static_assert(std::size(kAlphaModeNames) == uint32_t(AlphaMode::Blend) + 1);
static_assert(std::size(kLightTypeNames) == uint32_t(LightType::Directional) + 1);
static_assert(std::size(kProjectionNames) == uint32_t(Projection::Orthographic) + 1);

template <typename Enum, size_t N>
const char* name_of(const char* const (&names)[N], Enum value) {
  return uint32_t(value) < N ? names[uint32_t(value)] : "unknown";
}

}  // namespace

const char* material_type_name(MaterialType type) { return name_of(kMaterialTypeNames, type); }
const char* alpha_mode_name(AlphaMode mode) { return name_of(kAlphaModeNames, mode); }
const char* light_type_name(LightType type) { return name_of(kLightTypeNames, type); }
const char* projection_name(Projection projection) { return name_of(kProjectionNames, projection); }

Camera default_camera(const Bounds& bounds) {
  Camera camera;
  camera.name = "default";
  const Vec3 center{(bounds.min.x + bounds.max.x) / 2, (bounds.min.y + bounds.max.y) / 2, (bounds.min.z + bounds.max.z) / 2};
  const double dx = double(bounds.max.x) - bounds.min.x, dy = double(bounds.max.y) - bounds.min.y,
               dz = double(bounds.max.z) - bounds.min.z;
  const double radius = std::max(0.5 * std::sqrt(dx * dx + dy * dy + dz * dz), 1e-3);
  const double half_fov = camera.vertical_fov_degrees * M_PI / 360.0;
  const double distance = radius / std::sin(half_fov);
  camera.target = center;
  camera.position = {center.x, center.y, float(double(center.z) + distance)};
  camera.up = {0, 1, 0};
  return camera;
}

Bounds scene_bounds(const Scene& scene) {
  if (scene.positions.empty()) return {};
  Bounds bounds{scene.positions[0], scene.positions[0]};
  for (const Vec3& p : scene.positions) {
    bounds.min = {std::min(bounds.min.x, p.x), std::min(bounds.min.y, p.y), std::min(bounds.min.z, p.z)};
    bounds.max = {std::max(bounds.max.x, p.x), std::max(bounds.max.y, p.y), std::max(bounds.max.z, p.z)};
  }
  return bounds;
}

}  // namespace kdray
