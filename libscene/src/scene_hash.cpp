// The scene's two hashes: its content hash (what a tree or an image was made from) and its
// geometry hash (what a k-d tree depends on).
#include "scene_hash.h"

#include <xxhash.h>

#include <memory>

namespace kdray {

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
