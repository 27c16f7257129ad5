// The kernels' arrays of a scene (see scene_arrays.h).
#include "scene_arrays.h"

#include <kdray/traverse.h>
#include <kdray/util.h>

#include <cmath>
#include <map>
#include <utility>

#include "cdf_guide.h"

namespace kdray {
namespace {

float luminance(const Vec3& c) { return (c.x + c.y + c.z) / 3.0f; }

double triangle_area(const Scene& scene, uint32_t triangle) {
  const Vec3& a = scene.positions[scene.indices[3 * triangle]];
  const Vec3& b = scene.positions[scene.indices[3 * triangle + 1]];
  const Vec3& c = scene.positions[scene.indices[3 * triangle + 2]];
  double e1[3] = {b.x - a.x, b.y - a.y, b.z - a.z}, e2[3] = {c.x - a.x, c.y - a.y, c.z - a.z};
  double cx = e1[1] * e2[2] - e1[2] * e2[1], cy = e1[2] * e2[0] - e1[0] * e2[2], cz = e1[0] * e2[1] - e1[1] * e2[0];
  return 0.5 * std::sqrt(cx * cx + cy * cy + cz * cz);
}

PtPunctual device_punctual(const Light& light) {
  PtPunctual p{};
  p.type = static_cast<kd_u32>(light.type);
  const Vec3* vectors[3] = {&light.position, &light.direction, &light.color};
  float* out[3] = {p.position, p.direction, p.power};
  for (int k = 0; k < 3; ++k) {
    out[k][0] = vectors[k]->x;
    out[k][1] = vectors[k]->y;
    out[k][2] = vectors[k]->z;
  }
  p.cos_inner = std::cos(light.inner_cone_radians);
  p.cos_outer = std::cos(light.outer_cone_radians);
  return p;
}

// Materials, and the textures they read: colour textures are sRGB-encoded, normal and
// metallic-roughness maps are data, so a texture gets one copy per way it is read.
void add_materials(SceneArrays& arrays, const Scene& scene) {
  std::map<std::pair<int32_t, bool>, int32_t> device_texture;
  auto texture_index = [&](int32_t index, bool linear) -> int32_t {
    if (index < 0 || scene.uvs.empty()) return -1;
    auto [entry, added] = device_texture.try_emplace({index, linear}, int32_t(arrays.device_textures.size()));
    if (!added) return entry->second;
    const Texture& texture = scene.textures[index];
    std::vector<float>& texels = arrays.device_texels;  // RGBA per texel
    arrays.device_textures.push_back(
        PtTexture{static_cast<kd_u32>(texels.size() / 4), texture.width, texture.height, 0});
    // Each of the 256 byte values decoded once: the same floats as decoding every byte, where a
    // 2048x2048 colour texture spent 0.2 s in srgb_to_linear's powf (bench/LOG.md, "The
    // environment's table searched from guides").
    float decoded[256];
    for (int byte = 0; byte < 256; ++byte) decoded[byte] = linear ? byte / 255.0f : srgb_to_linear(byte / 255.0f);
    texels.reserve(texels.size() + texture.rgba.size());
    for (size_t i = 0; i < texture.rgba.size(); ++i)
      texels.push_back(i % 4 == 3 ? texture.rgba[i] / 255.0f : decoded[texture.rgba[i]]);
    return entry->second;
  };
  for (const Material& m : scene.materials) {
    PtMaterial pm{};
    pm.base_color[0] = m.base_color.x;
    pm.base_color[1] = m.base_color.y;
    pm.base_color[2] = m.base_color.z;
    pm.type = static_cast<kd_u32>(m.type);
    pm.emission[0] = m.emission.x;
    pm.emission[1] = m.emission.y;
    pm.emission[2] = m.emission.z;
    pm.roughness = m.roughness;
    pm.ior = m.ior;
    pm.metallic = m.metallic;
    pm.alpha = m.alpha;
    pm.alpha_cutoff = m.alpha_mode == AlphaMode::Opaque ? 0.0f : m.alpha_mode == AlphaMode::Blend ? -1.0f : m.alpha_cutoff;
    pm.texture = texture_index(m.diffuse_texture, false);
    pm.metal_rough_texture = texture_index(m.metal_rough_texture, true);
    pm.normal_texture = texture_index(m.normal_texture, true);
    pm.emissive_texture = texture_index(m.emissive_texture, false);
    arrays.device_materials.push_back(pm);
  }
}

// Power-weighted emitter table; triangles whose emission has no power are never picked.
void add_emitters(SceneArrays& arrays, const Scene& scene) {
  std::vector<PtLight>& lights = arrays.device_lights;
  double total = 0;
  std::vector<double> powers;
  for (uint32_t triangle : scene.emissive_triangles) {
    const Material& m = scene.materials[scene.material_ids[triangle]];
    double power = luminance(m.emission) * triangle_area(scene, triangle);
    if (!(power > 0) || m.type != MaterialType::Emissive) continue;
    total += power;
    powers.push_back(total);
    lights.push_back(PtLight{triangle, 0});
  }
  std::vector<float> cdf(lights.size());
  for (size_t i = 0; i < lights.size(); ++i) cdf[i] = static_cast<float>(powers[i] / total);
  if (!lights.empty()) cdf.back() = 1.0f;
  for (size_t i = 0; i < lights.size(); ++i) lights[i].cdf = cdf[i];
  arrays.light_count = static_cast<uint32_t>(lights.size());
  if (!lights.empty()) arrays.device_light_guide = cdf_guide(cdf.data(), arrays.light_count);
  arrays.light_area_pdf_scale = total > 0 ? static_cast<float>(1.0 / total) : 0.0f;
}

}  // namespace

GeometryArrays geometry_arrays(const KdTree& tree) {
  GeometryArrays geometry;
  geometry.nodes = host_array(tree.nodes);
  geometry.leaf_blocks = host_array(tree.leaf_blocks);
  const Vec3& lo = tree.bounds.min;
  const Vec3& hi = tree.bounds.max;
  float min[3] = {lo.x, lo.y, lo.z}, max[3] = {hi.x, hi.y, hi.z};
  for (int axis = 0; axis < 3; ++axis) {
    geometry.bounds_min[axis] = min[axis];
    geometry.bounds_max[axis] = max[axis];
  }
  return geometry;
}

SceneArrays scene_arrays(const Scene& scene, const KdTree& tree, const Environment* environment) {
  SceneArrays arrays;
  arrays.geometry = geometry_arrays(tree);
  arrays.gathered_vertices = gather_triangle_vertices(scene);
  arrays.triangle_vertices = host_array(arrays.gathered_vertices);
  arrays.indices = host_array(scene.indices);
  arrays.material_ids = host_array(scene.material_ids);
  arrays.normals = host_array(scene.normals);
  arrays.uvs = host_array(scene.uvs);
  // Files carry tangents when they need them; a scene made in memory may not.
  if (scene.tangents.empty()) arrays.computed_tangents = tangents_on_vertices(scene);
  arrays.tangents = host_array(scene.tangents.empty() ? arrays.computed_tangents : scene.tangents);

  add_materials(arrays, scene);
  arrays.materials = host_array(arrays.device_materials);
  arrays.textures = host_array(arrays.device_textures);
  arrays.texels = host_array(arrays.device_texels);

  add_emitters(arrays, scene);
  arrays.lights = host_array(arrays.device_lights);
  arrays.light_guide = host_array(arrays.device_light_guide);

  if (environment) {
    arrays.env_table = environment_sampling_table(*environment);
    arrays.env_texels = host_array(environment->rgb);
  }
  arrays.env_cdf = host_array(arrays.env_table);

  for (const Light& light : scene.lights) arrays.device_punctuals.push_back(device_punctual(light));
  arrays.punctual_count = static_cast<uint32_t>(arrays.device_punctuals.size());
  arrays.punctuals = host_array(arrays.device_punctuals);
  return arrays;
}

}  // namespace kdray
