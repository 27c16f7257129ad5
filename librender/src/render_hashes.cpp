// What a film records of how it was made beyond its own numbers: the tree's content and the
// settings that decide its pixels, so that merging refuses films of different renders.
#include "render_internal.h"

#include <kdray/render.h>

#include <xxhash.h>

namespace kdray {

uint64_t tree_content_hash(const KdTree& tree) {
  XXH3_state_t* state = XXH3_createState();
  XXH3_64bits_reset(state);
  XXH3_64bits_update(state, tree.nodes.data(), tree.nodes.size() * sizeof(KdNode));
  XXH3_64bits_update(state, tree.leaf_blocks.data(), tree.leaf_blocks.size() * sizeof(uint32_t));
  uint64_t hash = XXH3_64bits_digest(state);
  XXH3_freeState(state);
  return hash;
}

uint64_t render_settings_hash(const RenderSettings& settings, const Camera& camera, const Environment* environment) {
  XXH3_state_t* state = XXH3_createState();
  XXH3_64bits_reset(state);
  auto add = [&](const void* data, size_t bytes) { XXH3_64bits_update(state, data, bytes); };
  const float camera_values[] = {camera.position.x, camera.position.y, camera.position.z, camera.target.x,
                                 camera.target.y,   camera.target.z,   camera.up.x,       camera.up.y,
                                 camera.up.z,       camera.vertical_fov_degrees};
  add(camera_values, sizeof camera_values);
  // Perspective views hash as they did before cameras had a projection, so their films still merge.
  if (camera.projection == Projection::Orthographic)
    add(&camera.orthographic_half_height, sizeof camera.orthographic_half_height);
  const uint32_t switches[] = {environment ? 1u : 0u, settings.mis ? 1u : 0u};
  add(switches, sizeof switches);
  if (environment) {
    const uint32_t size[] = {environment->width, environment->height};
    const float transform[] = {environment->strength, environment->rotate_degrees};
    add(size, sizeof size);
    add(transform, sizeof transform);
    add(environment->rgb.data(), environment->rgb.size() * sizeof(float));
  }
  uint64_t hash = XXH3_64bits_digest(state);
  XXH3_freeState(state);
  return hash;
}

uint64_t render_settings_hash(const Scene& scene, const RenderSettings& settings) {
  return render_settings_hash(settings, render_camera(scene, settings), render_environment(scene, settings).get());
}

}  // namespace kdray
