// Small scenes built in code for the scene tests.
#pragma once

#include <kdray/scene.h>

namespace kdray::test {

// Two triangles of a unit quad with two materials; attributes as asked.
inline Scene make_quad_scene(bool with_normals, bool with_uvs, bool with_texture) {
  Scene scene;
  scene.positions = {{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0}};
  scene.indices = {0, 1, 2, 0, 2, 3};
  scene.material_ids = {0, 1};
  if (with_normals) scene.normals.assign(4, Vec3{0, 0, 1});
  if (with_uvs) scene.uvs = {{0, 0}, {1, 0}, {1, 1}, {0, 1}};
  Material white;
  white.name = "white";
  Material light;
  light.name = "light";
  light.type = MaterialType::Emissive;
  light.emission = {17, 12, 4};
  if (with_texture) {
    scene.textures.push_back({"checker.png", 2, 1, {255, 0, 0, 255, 0, 255, 0, 128}});
    white.diffuse_texture = 0;
  }
  scene.materials = {white, light};
  scene.cameras.push_back({"main", {0.5f, 0.5f, 3}, {0.5f, 0.5f, 0}, {0, 1, 0}, 40, 1.5f});
  scene.cameras.push_back({"plan", {0.5f, 4, 0.5f}, {0.5f, 0, 0.5f}, {0, 0, -1}, 45, 2, Projection::Orthographic, 0.75f});
  scene.emissive_triangles = {1};
  scene.import_stats.source_file = "quad.obj";
  scene.import_stats.importer = "tinyobj";
  scene.import_stats.source_triangles = 3;
  scene.import_stats.dropped_degenerate = 1;
  scene.import_stats.warnings = {"a warning"};
  scene.content_hash = compute_content_hash(scene);
  scene.geometry_hash = compute_geometry_hash(scene);
  return scene;
}

}  // namespace kdray::test
