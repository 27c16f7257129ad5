// The C++ build of the path tracer against the kernel (tests/render/cpu_integrator.h) with what a
// textured glTF asset brings: a metallic-roughness sphere with base-colour (its alpha cut out),
// metallic-roughness and normal textures, per-vertex normals and UVs (tangents from them), over a
// diffuse floor under a directional light and a lamp with an emissive texture; and the same with
// the sphere opaque.

#include "cpu_integrator.h"
#include "light_scenes.h"
#include "test_scenes.h"

#include <cmath>

namespace kdray::test {
namespace {

// A w x h texture whose texels differ from their neighbours in every channel; alpha alternates
// between opaque and below the cut-off when `holes` is set.
Texture pattern(uint32_t w, uint32_t h, int seed, bool holes) {
  Texture t{"pattern", w, h, {}};
  for (uint32_t y = 0; y < h; ++y)
    for (uint32_t x = 0; x < w; ++x) {
      for (int c = 0; c < 3; ++c) t.rgba.push_back(uint8_t((37 * x + 91 * y + 53 * c + seed) % 256));
      t.rgba.push_back(holes && (x + y) % 3 == 0 ? 40 : 255);
    }
  return t;
}

// The asset: the sphere's base-colour alpha cut out where `cut_out`, else opaque (then the
// host's lanes shade it in lanes, its textures looked up lane by lane).
Scene textured_asset(bool cut_out) {
  Material sphere = metal_rough({0.9f, 0.8f, 0.7f}, 0.5f, 0.4f);
  if (cut_out) sphere.alpha_mode = AlphaMode::Mask;
  sphere.diffuse_texture = 0;
  sphere.metal_rough_texture = 1;
  sphere.normal_texture = 2;
  Scene scene = make_sphere_scene(sphere, 1.0f, 12, 24);
  scene.textures = {pattern(6, 5, 0, true), pattern(3, 4, 7, false), pattern(4, 4, 19, false), pattern(2, 3, 5, false)};
  for (const Vec3& p : scene.positions) {  // unit sphere: the normal is the position
    scene.normals.push_back(p);
    const float u = 0.5f + std::atan2(p.z, p.x) / 6.2831853f;
    const float v = 0.5f + std::asin(std::fmax(-1.0f, std::fmin(p.y, 1.0f))) / 3.1415927f;
    scene.uvs.push_back({2 * u, v});
  }
  add_floor(scene, -1.0f, 3.0f, 0.6f);
  // A textured emitter above, facing down.
  Material lamp;
  lamp.type = MaterialType::Emissive;
  lamp.emission = {4, 3.5f, 3};
  lamp.emissive_texture = 3;
  scene.materials.push_back(lamp);
  const uint32_t first_lamp_triangle = scene.triangle_count();
  add_quad(scene, {{{-1, 2, -1}, {1, 2, -1}, {1, 2, 1}, {-1, 2, 1}}}, 2);
  scene.emissive_triangles = {first_lamp_triangle, first_lamp_triangle + 1};
  scene.normals.resize(scene.positions.size(), Vec3{0, 1, 0});
  for (int quad = 0; quad < 2; ++quad) scene.uvs.insert(scene.uvs.end(), {{0, 0}, {0, 1}, {1, 1}, {1, 0}});
  scene.lights.push_back(directional_light({0.3f, -0.8f, -0.5f}, 3.0f));
  return scene;
}

TEST(CpuIntegrator, TexturedMetallicRoughnessAssetMatchesTheKernelBitForBit) {
  Scene scene = textured_asset(true);
  EXPECT_GT(expect_host_matches_kernel(scene, tiny_settings(24, 4),
                                       {"-DKD_FEATURE_EMISSION", "-DKD_FEATURE_METALLIC_ROUGHNESS", "-DKD_FEATURE_ALPHA",
                                        "-DKD_FEATURE_TEXTURES", "-DKD_FEATURE_METAL_ROUGH_TEXTURE",
                                        "-DKD_FEATURE_NORMAL_MAP", "-DKD_FEATURE_EMISSIVE_TEXTURE",
                                        "-DKD_FEATURE_NORMALS", "-DKD_FEATURE_PUNCTUAL"}),
            24u * 24u / 2);
}

TEST(CpuIntegrator, OpaqueTexturedMetallicRoughnessAssetMatchesTheKernelBitForBit) {
  Scene scene = textured_asset(false);
  RenderSettings settings = tiny_settings(24, 8);
  settings.aov_albedo = settings.aov_normal = true;
  EXPECT_GT(expect_host_matches_kernel(scene, settings,
                                       {"-DKD_FEATURE_EMISSION", "-DKD_FEATURE_METALLIC_ROUGHNESS",
                                        "-DKD_FEATURE_TEXTURES", "-DKD_FEATURE_METAL_ROUGH_TEXTURE",
                                        "-DKD_FEATURE_NORMAL_MAP", "-DKD_FEATURE_EMISSIVE_TEXTURE",
                                        "-DKD_FEATURE_NORMALS", "-DKD_FEATURE_PUNCTUAL"}),
            24u * 24u / 2);
}

}  // namespace
}  // namespace kdray::test
