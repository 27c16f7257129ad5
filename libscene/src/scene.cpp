#include <kdray/scene.h>

#include "scene_encoding.h"

#include <xxhash.h>

#include <algorithm>
#include <cmath>
#include <iterator>
#include <memory>

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

// The hash covers, in this order, each part as (8-byte little-endian size, bytes): positions,
// indices, material ids, normals, UVs, emissive triangles, then the encoded materials,
// textures and cameras, then the encoded lights and the tangents only when there are any, so
// that scenes without them keep the hash they had in format version 1 (formats/kdscene.md).
// Import statistics are not content.
uint64_t encoding::content_hash(const Scene& scene, const EncodedParts& parts) {
  std::unique_ptr<XXH3_state_t, decltype(&XXH3_freeState)> state(XXH3_createState(), &XXH3_freeState);
  XXH3_64bits_reset(state.get());
  auto feed = [&](const void* data, uint64_t size) {
    XXH3_64bits_update(state.get(), &size, sizeof size);
    XXH3_64bits_update(state.get(), data, size);
  };
  auto feed_array = [&](const auto& array) { feed(array.data(), array.size() * sizeof array[0]); };
  auto feed_text = [&](const std::string& text) { feed(text.data(), text.size()); };
  feed_array(scene.positions);
  feed_array(scene.indices);
  feed_array(scene.material_ids);
  feed_array(scene.normals);
  feed_array(scene.uvs);
  feed_array(scene.emissive_triangles);
  feed_text(parts.materials);
  feed_text(parts.textures);
  feed_text(parts.cameras);
  if (!scene.lights.empty()) feed_text(parts.lights);
  if (!scene.tangents.empty()) feed_array(scene.tangents);
  return XXH3_64bits_digest(state.get());
}

// The same (size, bytes) framing as the content hash, over the first two of its parts.
uint64_t compute_geometry_hash(const Scene& scene) {
  std::unique_ptr<XXH3_state_t, decltype(&XXH3_freeState)> state(XXH3_createState(), &XXH3_freeState);
  XXH3_64bits_reset(state.get());
  auto feed_array = [&](const auto& array) {
    const uint64_t size = array.size() * sizeof array[0];
    XXH3_64bits_update(state.get(), &size, sizeof size);
    XXH3_64bits_update(state.get(), array.data(), size);
  };
  feed_array(scene.positions);
  feed_array(scene.indices);
  return XXH3_64bits_digest(state.get());
}

uint64_t compute_content_hash(const Scene& scene) {
  return encoding::content_hash(scene, encoding::encode_parts(scene));
}

}  // namespace kdray
