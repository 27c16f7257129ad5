// The C++ build of the path tracer against the kernel (tests/render/cpu_integrator.h) on the
// smallest feature sets: the sample Cornell box (emission only, diffuse only) with the settings a
// render varies (sample range, seed, bounces, sampler, MIS switch, AOVs, threads), and a scene
// without lights under the default light (the environment only).
#include "cpu_integrator.h"
#include "light_scenes.h"
#include "test_scenes.h"

#include <kdray/import.h>

#include <vector>

namespace kdray::test {
namespace {

RenderSettings cornell_settings() {
  RenderSettings settings = tiny_settings(24, 3);
  settings.camera = cornell_camera();
  settings.sample_offset = 5;
  settings.seed = 7;
  return settings;
}

// Appends `materials` to the scene and hands them the Cornell box's diffuse triangles in turn: of
// each run of materials.size() + 1 diffuse triangles, the first stays diffuse and the others take
// the new materials in order.
void share_diffuse_triangles(Scene& scene, const std::vector<Material>& materials) {
  const uint32_t first = uint32_t(scene.materials.size());
  scene.materials.insert(scene.materials.end(), materials.begin(), materials.end());
  uint32_t diffuse = 0;
  for (uint32_t& id : scene.material_ids) {
    if (id >= first || scene.materials[id].type != MaterialType::Diffuse) continue;
    const uint32_t kind = diffuse++ % uint32_t(materials.size() + 1);
    if (kind) id = first + kind - 1;
  }
}

// Vertex normals tilted from +y by an x of -2, -1, 0, 1 or 2 times `step` in turn, and a z of
// z_per_x times that x.
void tilt_vertex_normals(Scene& scene, float step, float z_per_x) {
  for (size_t i = 0; i < scene.positions.size(); ++i) {
    const float tilt = step * float(i % 5) - 2.0f * step;
    scene.normals.push_back(Vec3{tilt, 1.0f, z_per_x * tilt});
  }
}

TEST(CpuIntegrator, CornellBoxMatchesTheKernelBitForBitOnOneThread) {
  Scene scene = import_scene(cornell_obj(), ImportOptions{});
  EXPECT_GT(expect_host_matches_kernel(scene, cornell_settings(), {"-DKD_FEATURE_EMISSION"}, 1), 24u * 24u / 2);
}

// The paths in lanes (librender/src/path_lanes.h) over 8 bounces, Russian roulette's included,
// with every AOV, on two threads: lanes end and take new samples at every step, and tasks end
// with lanes empty.
TEST(CpuIntegrator, CornellBoxInLanesMatchesTheKernelBitForBitWithEveryAov) {
  Scene scene = import_scene(cornell_obj(), ImportOptions{});
  RenderSettings settings = cornell_settings();
  settings.width = settings.height = 40;
  settings.spp = 5;
  settings.seed = 3;
  settings.aov_albedo = settings.aov_normal = settings.aov_depth = true;
  settings.max_bounces = 8;  // roulette from bounce 4 (kernels/pt_path.h)
  EXPECT_GT(expect_host_matches_kernel(scene, settings, {"-DKD_FEATURE_EMISSION"}, 2), 40u * 40u / 2);
}

// The lanes with smooth normals and with surfaces they hand to pt_path_shade lane by lane: of the
// Cornell box's diffuse triangles, every fourth made a mirror, the next a rough conductor, the
// next glass; vertex normals tilted a different way at each vertex, some of them zero (where the
// geometric normal shades) and some facing away.
TEST(CpuIntegrator, CornellBoxWithNormalsAndSpecularSurfacesInLanesMatchesTheKernelBitForBit) {
  Scene scene = import_scene(cornell_obj(), ImportOptions{});
  ASSERT_TRUE(scene.normals.empty());
  for (size_t i = 0; i < scene.positions.size(); ++i) {
    const float tilt = 0.3f * float(i % 7) - 0.9f;
    scene.normals.push_back(i % 5 == 0 ? Vec3{0, 0, 0} : Vec3{tilt, 1.0f - 0.2f * float(i % 3), -tilt});
  }
  std::vector<Material> specular;
  for (MaterialType type : {MaterialType::Mirror, MaterialType::RoughConductor, MaterialType::Dielectric}) {
    specular.emplace_back();
    specular.back().type = type;
    specular.back().roughness = 0.1f;
  }
  share_diffuse_triangles(scene, specular);
  RenderSettings settings = cornell_settings();
  settings.width = settings.height = 32;
  settings.spp = 16;
  EXPECT_GT(expect_host_matches_kernel(
                scene, settings,
                {"-DKD_FEATURE_EMISSION", "-DKD_FEATURE_NORMALS", "-DKD_FEATURE_MIRROR", "-DKD_FEATURE_GLOSSY",
                 "-DKD_FEATURE_GLASS"},
                2),
            32u * 32u / 4);
}

// The glTF material in lanes: of the Cornell box's diffuse triangles, three in four made glTF
// metallic-roughness ones (a rough plastic, a smooth one of another index, a half-metallic gold),
// under vertex normals tilted a different way at each vertex; next-event estimation on the
// ceiling light evaluates them in lanes, and each lane draws its lobe.
TEST(CpuIntegrator, CornellBoxWithGltfMaterialsInLanesMatchesTheKernelBitForBit) {
  Scene scene = import_scene(cornell_obj(), ImportOptions{});
  tilt_vertex_normals(scene, 0.25f, 0.5f);
  Material smooth = metal_rough({0.2f, 0.5f, 0.7f}, 0.0f, 0.08f);
  smooth.ior = 1.33f;
  share_diffuse_triangles(scene, {metal_rough({0.8f, 0.3f, 0.2f}, 0.0f, 1.0f), smooth,
                                  metal_rough({1.0f, 0.77f, 0.34f}, 0.5f, 0.3f)});
  RenderSettings settings = cornell_settings();
  settings.width = settings.height = 32;
  settings.spp = 16;
  settings.aov_albedo = true;
  EXPECT_GT(expect_host_matches_kernel(scene, settings,
                                       {"-DKD_FEATURE_EMISSION", "-DKD_FEATURE_NORMALS",
                                        "-DKD_FEATURE_METALLIC_ROUGHNESS"},
                                       2),
            32u * 32u / 4);
}

// Many triangle lights of unequal power: of the Cornell box's diffuse triangles, two in three made
// emitters of two strengths, so that the lanes' light pick (path_lanes.h, pick_lights) bisects a
// cdf of about twenty unequal entries, each lane taking its own number of steps.
TEST(CpuIntegrator, CornellBoxWithManyUnequalLightsInLanesMatchesTheKernelBitForBit) {
  Scene scene = import_scene(cornell_obj(), ImportOptions{});
  Material bright, dim;
  bright.type = dim.type = MaterialType::Emissive;
  bright.base_color = dim.base_color = {0.5f, 0.5f, 0.5f};
  bright.emission = {4.0f, 3.0f, 2.0f};
  dim.emission = {0.3f, 0.5f, 0.7f};
  share_diffuse_triangles(scene, {bright, dim});
  scene.emissive_triangles.clear();
  for (uint32_t t = 0; t < scene.triangle_count(); ++t)
    if (scene.materials[scene.material_ids[t]].type == MaterialType::Emissive) scene.emissive_triangles.push_back(t);
  ASSERT_GT(scene.emissive_triangles.size(), 16u);
  RenderSettings settings = cornell_settings();
  settings.width = settings.height = 32;
  settings.spp = 8;
  settings.max_bounces = 3;
  EXPECT_GT(expect_host_matches_kernel(scene, settings, {"-DKD_FEATURE_EMISSION"}, 2), 32u * 32u / 2);
}

// A panel of 1152 small emitters below the ceiling, of three strengths and of areas that grow
// across it: the emitters' cdf has 64 guide cells (kernels/pt_sampling.h), so the lanes' pick and
// the kernel's each bisect from their guide's range, not the whole cdf.
TEST(CpuIntegrator, CornellBoxWithAPanelOfManyLightsMatchesTheKernelBitForBit) {
  Scene scene = import_scene(cornell_obj(), ImportOptions{});
  const uint32_t first_material = uint32_t(scene.materials.size());
  for (const Vec3 emission : {Vec3{6.0f, 5.0f, 4.0f}, Vec3{1.0f, 2.0f, 3.0f}, Vec3{0.2f, 0.2f, 0.2f}}) {
    Material light;
    light.type = MaterialType::Emissive;
    light.base_color = {0.5f, 0.5f, 0.5f};
    light.emission = emission;
    scene.materials.push_back(light);
  }
  constexpr uint32_t kCells = 24;
  auto coordinate = [](uint32_t i) { return 150.0f + 250.0f * float(i * i) / float(kCells * kCells); };
  const uint32_t first_vertex = uint32_t(scene.positions.size());
  for (uint32_t j = 0; j <= kCells; ++j)
    for (uint32_t i = 0; i <= kCells; ++i) scene.positions.push_back(Vec3{coordinate(i), 500.0f, coordinate(j)});
  for (uint32_t j = 0; j < kCells; ++j) {
    for (uint32_t i = 0; i < kCells; ++i) {
      const uint32_t a = first_vertex + j * (kCells + 1) + i, b = a + 1, c = a + kCells + 1, d = c + 1;
      for (const uint32_t corner : {a, b, c, b, d, c}) scene.indices.push_back(corner);  // facing down
      for (int t = 0; t < 2; ++t) {
        scene.emissive_triangles.push_back(uint32_t(scene.material_ids.size()));
        scene.material_ids.push_back(first_material + (i + j + uint32_t(t)) % 3);
      }
    }
  }
  ASSERT_EQ(scene.emissive_triangles.size(), 2u + 2 * kCells * kCells);
  RenderSettings settings = cornell_settings();
  settings.width = settings.height = 32;
  settings.spp = 8;
  settings.max_bounces = 3;
  EXPECT_GT(expect_host_matches_kernel(scene, settings, {"-DKD_FEATURE_EMISSION"}, 2), 32u * 32u / 2);
}

// Every kind of light at once in lanes: the Cornell box's ceiling light, an environment seen
// through the open front and a point light inside, so that the 8 lanes of a step pick different
// kinds (triangle lights in lanes, the others sampled lane by lane and their shadow rays set up in
// lanes), over diffuse and glTF surfaces.
TEST(CpuIntegrator, CornellBoxUnderEveryKindOfLightInLanesMatchesTheKernelBitForBit) {
  Scene scene = import_scene(cornell_obj(), ImportOptions{});
  share_diffuse_triangles(scene, {metal_rough({0.7f, 0.7f, 0.3f}, 0.3f, 0.4f)});
  Light point;
  point.type = LightType::Point;
  point.position = {400, 300, 200};
  point.color = {3e4f, 2.5e4f, 2e4f};
  scene.lights = {point};
  RenderSettings settings = cornell_settings();
  settings.width = settings.height = 32;
  settings.spp = 16;
  settings.environment = shared_environment(sun_environment());
  EXPECT_GT(expect_host_matches_kernel(scene, settings,
                                       {"-DKD_FEATURE_EMISSION", "-DKD_FEATURE_METALLIC_ROUGHNESS",
                                        "-DKD_FEATURE_ENVIRONMENT", "-DKD_FEATURE_PUNCTUAL"},
                                       2),
            32u * 32u / 4);
}

// The lanes with alpha: every second of the Cornell box's diffuse triangles blended (alpha 0.5),
// shaded lane by lane where a ray meets one and walked through by the shadow rays of every lane,
// whose pass-through decisions hash the path's bounce; vertex normals tilted, so that some paths
// end at a BSDF sample below the surface with a shadow ray traced (the bounce it keeps).
TEST(CpuIntegrator, CornellBoxWithBlendedSurfacesInLanesMatchesTheKernelBitForBit) {
  Scene scene = import_scene(cornell_obj(), ImportOptions{});
  tilt_vertex_normals(scene, 0.4f, -1.0f);
  Material glass_pane;  // diffuse, half transparent
  glass_pane.base_color = {0.7f, 0.6f, 0.5f};
  glass_pane.alpha = 0.5f;
  glass_pane.alpha_mode = AlphaMode::Blend;
  share_diffuse_triangles(scene, {glass_pane});
  RenderSettings settings = cornell_settings();
  settings.width = settings.height = 32;
  settings.spp = 16;
  EXPECT_GT(expect_host_matches_kernel(scene, settings,
                                       {"-DKD_FEATURE_EMISSION", "-DKD_FEATURE_NORMALS", "-DKD_FEATURE_ALPHA"}, 2),
            32u * 32u / 4);
}

TEST(CpuIntegrator, CornellBoxWithoutMisMatchesTheKernelBitForBitOnTwoThreads) {
  Scene scene = import_scene(cornell_obj(), ImportOptions{});
  RenderSettings settings = cornell_settings();
  settings.mis = false;
  settings.sampler = Sampler::Independent;
  settings.max_bounces = 2;
  settings.aov_albedo = settings.aov_depth = true;
  EXPECT_GT(expect_host_matches_kernel(scene, settings, {"-DKD_FEATURE_EMISSION", "-DKD_MIS_OFF"}, 2),
            24u * 24u / 2);
}

TEST(CpuIntegrator, DefaultLightMatchesTheKernelBitForBit) {
  Scene scene = make_sphere_scene(Material{}, 1.0f, 8, 16);
  RenderSettings settings = tiny_settings(16, 2);
  settings.aov_normal = true;
  EXPECT_GT(expect_host_matches_kernel(scene, settings, {"-DKD_FEATURE_ENVIRONMENT"}), 16u * 16u / 2);
}

}  // namespace
}  // namespace kdray::test
