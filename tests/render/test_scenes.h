// Small generated scenes with known answers for the renderer tests.
#pragma once

#include <kdray/scene.h>

#include <array>
#include <cstdint>

namespace kdray::test {

// Adds the quad a,b,c,d (counter-clockwise seen from the side its normal faces) as two triangles.
inline void add_quad(Scene& scene, const std::array<Vec3, 4>& corners, uint32_t material) {
  uint32_t base = static_cast<uint32_t>(scene.positions.size());
  for (const Vec3& corner : corners) scene.positions.push_back(corner);
  for (uint32_t i : {0u, 1u, 2u, 0u, 2u, 3u}) scene.indices.push_back(base + i);
  scene.material_ids.push_back(material);
  scene.material_ids.push_back(material);
}

// A glTF metallic-roughness material; roughness_alpha is the GGX alpha.
inline Material metal_rough(Vec3 base, float metallic, float roughness_alpha) {
  Material m;
  m.type = MaterialType::MetallicRoughness;
  m.base_color = base;
  m.metallic = metallic;
  m.roughness = roughness_alpha;
  return m;
}

// Adds a grey diffuse square floor of half size `half_size` at height y, facing up, with a
// material of its own. Returns that material's number.
inline uint32_t add_floor(Scene& scene, float y, float half_size, float albedo) {
  Material floor;
  floor.base_color = {albedo, albedo, albedo};
  scene.materials.push_back(floor);
  const uint32_t material = uint32_t(scene.materials.size() - 1);
  const float s = half_size;
  add_quad(scene, {{{-s, y, -s}, {-s, y, s}, {s, y, s}, {s, y, -s}}}, material);
  return material;
}

// A camera 4 units above the origin looking straight down (-Y), the image's up along -Z: it sees
// a floor at y = 0 with +X to the right.
inline Camera camera_above_floor(float vertical_fov_degrees) {
  Camera camera;
  camera.position = {0, 4, 0};
  camera.target = {0, 0, 0};
  camera.up = {0, 0, -1};
  camera.vertical_fov_degrees = vertical_fov_degrees;
  return camera;
}

// A directional light travelling along `direction` with irradiance `irradiance` (W/m^2) on a
// surface facing it.
inline Light directional_light(const Vec3& direction, float irradiance) {
  Light light;
  light.type = LightType::Directional;
  light.direction = direction;
  light.color = {irradiance, irradiance, irradiance};
  return light;
}

// A closed cube [-1,1]^3 whose faces all face inwards, every face of material 0; the camera
// sits at the centre. With an Emissive material of albedo a and emission Le this is the
// furnace: radiance Le * (1 + a + ... + a^(B+1)) with B max bounces.
inline Scene make_inward_cube(const Material& material) {
  Scene scene;
  scene.materials.push_back(material);
  const float s = 1.0f;
  // Each face: corners ordered so that the winding normal points to the cube's centre.
  add_quad(scene, {{{-s, -s, -s}, {-s, -s, s}, {s, -s, s}, {s, -s, -s}}}, 0);  // floor y=-1, normal +y
  add_quad(scene, {{{-s, s, -s}, {s, s, -s}, {s, s, s}, {-s, s, s}}}, 0);      // ceiling y=+1, normal -y
  add_quad(scene, {{{-s, -s, -s}, {-s, s, -s}, {-s, s, s}, {-s, -s, s}}}, 0);  // x=-1, normal +x
  add_quad(scene, {{{s, -s, -s}, {s, -s, s}, {s, s, s}, {s, s, -s}}}, 0);      // x=+1, normal -x
  add_quad(scene, {{{-s, -s, -s}, {s, -s, -s}, {s, s, -s}, {-s, s, -s}}}, 0);  // z=-1, normal +z
  add_quad(scene, {{{-s, -s, s}, {-s, s, s}, {s, s, s}, {s, -s, s}}}, 0);      // z=+1, normal -z
  if (material.type == MaterialType::Emissive) {
    for (uint32_t t = 0; t < scene.triangle_count(); ++t) scene.emissive_triangles.push_back(t);
  }
  Camera camera;
  camera.position = {0, 0, 0};
  camera.target = {0, 0, -1};
  camera.up = {0, 1, 0};
  camera.vertical_fov_degrees = 90.0f;
  scene.cameras.push_back(camera);
  return scene;
}

// Every material and optional attribute the kernels support, in one small closed room: diffuse
// walls with a checker-textured floor, a one-sided ceiling light, and a box whose faces are a
// mirror, a rough conductor and glass; per-vertex normals and UVs everywhere.
inline Scene make_feature_room() {
  Scene scene;
  auto material = [&](MaterialType type, Vec3 color) {
    Material m;
    m.type = type;
    m.base_color = color;
    scene.materials.push_back(m);
    return static_cast<uint32_t>(scene.materials.size() - 1);
  };
  uint32_t wall = material(MaterialType::Diffuse, {0.7f, 0.7f, 0.7f});
  uint32_t floor = material(MaterialType::Diffuse, {1, 1, 1});
  scene.materials[floor].diffuse_texture = 0;
  uint32_t light = material(MaterialType::Emissive, {0.5f, 0.5f, 0.5f});
  scene.materials[light].emission = {8, 7, 6};
  uint32_t mirror = material(MaterialType::Mirror, {0.9f, 0.9f, 0.9f});
  uint32_t metal = material(MaterialType::RoughConductor, {0.9f, 0.6f, 0.3f});
  scene.materials[metal].roughness = 0.3f;
  uint32_t glass = material(MaterialType::Dielectric, {1, 1, 1});
  scene.materials[glass].ior = 1.5f;

  const float s = 1.0f;
  add_quad(scene, {{{-s, -s, -s}, {-s, -s, s}, {s, -s, s}, {s, -s, -s}}}, floor);
  add_quad(scene, {{{-s, s, -s}, {s, s, -s}, {s, s, s}, {-s, s, s}}}, wall);
  add_quad(scene, {{{-s, -s, -s}, {-s, s, -s}, {-s, s, s}, {-s, -s, s}}}, wall);
  add_quad(scene, {{{s, -s, -s}, {s, -s, s}, {s, s, s}, {s, s, -s}}}, wall);
  add_quad(scene, {{{-s, -s, -s}, {s, -s, -s}, {s, s, -s}, {-s, s, -s}}}, wall);
  add_quad(scene, {{{-s, -s, s}, {-s, s, s}, {s, s, s}, {s, -s, s}}}, wall);
  const float l = 0.3f, y = 0.99f;
  add_quad(scene, {{{-l, y, -l}, {l, y, -l}, {l, y, l}, {-l, y, l}}}, light);  // faces down
  scene.emissive_triangles = {12, 13};
  const float b = 0.35f, lo = -1.0f, hi = -0.2f;  // an outward-facing box on the floor
  add_quad(scene, {{{-b, hi, -b}, {-b, hi, b}, {b, hi, b}, {b, hi, -b}}}, mirror);
  add_quad(scene, {{{-b, lo, b}, {b, lo, b}, {b, hi, b}, {-b, hi, b}}}, glass);
  add_quad(scene, {{{b, lo, -b}, {b, hi, -b}, {b, hi, b}, {b, lo, b}}}, metal);
  add_quad(scene, {{{-b, lo, -b}, {-b, lo, b}, {-b, hi, b}, {-b, hi, -b}}}, glass);
  add_quad(scene, {{{-b, lo, -b}, {-b, hi, -b}, {b, hi, -b}, {b, lo, -b}}}, metal);

  // Flat per-vertex normals (from each quad's winding) and a unit UV square per quad.
  for (size_t t = 0; t < scene.triangle_count(); t += 2) {
    const Vec3& p0 = scene.positions[scene.indices[3 * t]];
    const Vec3& p1 = scene.positions[scene.indices[3 * t + 1]];
    const Vec3& p2 = scene.positions[scene.indices[3 * t + 2]];
    Vec3 e1{p1.x - p0.x, p1.y - p0.y, p1.z - p0.z}, e2{p2.x - p0.x, p2.y - p0.y, p2.z - p0.z};
    Vec3 n{e1.y * e2.z - e1.z * e2.y, e1.z * e2.x - e1.x * e2.z, e1.x * e2.y - e1.y * e2.x};
    for (int corner = 0; corner < 4; ++corner) scene.normals.push_back(n);
    scene.uvs.insert(scene.uvs.end(), {{0, 0}, {1, 0}, {1, 1}, {0, 1}});
  }
  Texture checker;
  checker.name = "checker";
  checker.width = 4;
  checker.height = 4;
  for (uint32_t i = 0; i < 16; ++i) {
    uint8_t v = ((i % 4) + (i / 4)) % 2 ? 230 : 40;
    checker.rgba.insert(checker.rgba.end(), {v, uint8_t(v / 2), 40, 255});
  }
  scene.textures.push_back(checker);

  Camera camera;
  camera.position = {0, 0, 0.95f};
  camera.target = {0, -0.3f, 0};
  camera.vertical_fov_degrees = 70.0f;
  scene.cameras.push_back(camera);
  return scene;
}

}  // namespace kdray::test
