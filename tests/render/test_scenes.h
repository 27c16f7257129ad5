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

}  // namespace kdray::test
