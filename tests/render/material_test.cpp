// glTF metallic-roughness and alpha, known answers: a sphere in a white furnace reflects what an
// independent integral of the specification's BRDF says, a black base shows the specular layer
// alone (not a diffuse surface), a smooth full metal is a mirror of its base colour; fully cut-out
// surfaces let camera and shadow rays through and blended ones a share alpha of them; the features
// are compiled only when a scene has them.
#include "light_scenes.h"
#include "render_fixture.h"
#include "test_scenes.h"

#include <kdray/render.h>

#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>

namespace kdray {
namespace {

struct SphereImage {
  Film film;
  std::vector<float> means;
  RenderStats stats;
  // Means of the three channels over the sphere pixels within `radius` (as a share of the
  // sphere's image radius) of its centre; the depth AOV tells sphere from background.
  Vec3 mean_within(float radius) const {
    const size_t channels = film.channels.size();
    double sum[3] = {0, 0, 0};
    size_t count = 0;
    const double cx = film.width / 2.0, cy = film.height / 2.0, sphere_radius = sphere_pixels_radius();
    for (uint32_t y = 0; y < film.height; ++y)
      for (uint32_t x = 0; x < film.width; ++x) {
        const float* px = &means[(size_t(y) * film.width + x) * channels];
        const double dx = x + 0.5 - cx, dy = y + 0.5 - cy;
        if (px[3] <= 0 || std::sqrt(dx * dx + dy * dy) > radius * sphere_radius) continue;
        for (int c = 0; c < 3; ++c) sum[c] += px[c];
        ++count;
      }
    EXPECT_GT(count, 20u);
    std::printf("sphere mean within %.2f: %.5f %.5f %.5f\n", radius, sum[0] / count, sum[1] / count, sum[2] / count);
    return {float(sum[0] / count), float(sum[1] / count), float(sum[2] / count)};
  }
  double sphere_pixels_radius() const {
    size_t hits = 0;
    const size_t channels = film.channels.size();
    for (size_t p = 0; p < film.pixel_count(); ++p) hits += means[p * channels + 3] > 0;
    return std::sqrt(hits / 3.14159265358979323846);
  }
};

// The sphere of light_scenes.h under a uniform environment of radiance 1.
SphereImage render_sphere(const Material& material, uint32_t spp = 256) {
  Scene scene = test::make_sphere_scene(material);
  KdTree tree = test::tree_for(scene);
  RenderSettings settings = test::tiny_settings(32, spp);
  settings.environment = test::shared_environment(uniform_environment({1, 1, 1}));
  settings.max_bounces = 8;
  settings.aov_depth = true;
  SphereImage image;
  image.film = render(scene, tree, settings, DeviceSelection{}, &image.stats);
  image.means = image.film.means();
  EXPECT_EQ(image.stats.nonfinite_values, 0u);
  return image;
}

// The mean over a sphere's projected disk under a uniform environment of radiance 1, seen from
// far enough (40 radii, a 7.2 degree field) that the view is nearly parallel: for a convex object
// that is its hemispherical albedo. Background pixels show the environment, 1, so the disk's mean
// is 1 minus the image's deficit over the disk's area, which also counts the rim's partly covered
// pixels right.
Vec3 furnace_disk_mean(const Material& material) {
  constexpr float kDistance = 40, kTanHalfFov = 0.0625f;
  constexpr uint32_t kSize = 64;
  Scene scene = test::make_sphere_scene(material, 1.0f, 64, 128);
  scene.cameras[0].position = {0, 0, kDistance};
  scene.cameras[0].vertical_fov_degrees = float(2 * std::atan(kTanHalfFov) * 180 / 3.14159265358979323846);
  KdTree tree = test::tree_for(scene);
  RenderSettings settings = test::tiny_settings(kSize, 256);
  settings.environment = test::shared_environment(uniform_environment({1, 1, 1}));
  settings.max_bounces = 8;
  RenderStats stats;
  const Film film = render(scene, tree, settings, DeviceSelection{}, &stats);
  EXPECT_EQ(stats.nonfinite_values, 0u);
  EXPECT_NE(stats.kernel_options.find("KD_FEATURE_METALLIC_ROUGHNESS"), std::string::npos);
  const std::vector<float> means = film.means();
  const size_t channels = film.channels.size();
  double deficit[3] = {0, 0, 0};
  for (size_t p = 0; p < film.pixel_count(); ++p)
    for (int c = 0; c < 3; ++c) deficit[c] += 1.0 - means[p * channels + c];
  const double radius = std::tan(std::asin(1.0 / kDistance)) / kTanHalfFov * kSize / 2;
  const double area = 3.14159265358979323846 * radius * radius;
  return {float(1 - deficit[0] / area), float(1 - deficit[1] / area), float(1 - deficit[2] / area)};
}

TEST(MetallicRoughness, WhiteFurnaceSphereReflectsWhatTheSpecificationsBrdfIntegratesTo) {
  // The glTF 2.0 specification's BRDF (Appendix B) integrated independently of kdray by
  // tests/render/gltf_brdf_reference.py: hemispherical albedos at base colours 0.8, 0.5 and 0.2
  // (the three channels of one render), perceptual roughness r (alpha = r^2), metallic 0 and 1.
  struct Case {
    float roughness, metallic;
    Vec3 want;
  };
  const Case cases[] = {
      {0.25f, 0, {0.84267f, 0.55573f, 0.26879f}}, {0.25f, 1, {0.79772f, 0.51342f, 0.22912f}},
      {0.5f, 0, {0.81839f, 0.53146f, 0.24452f}},  {0.5f, 1, {0.70959f, 0.45050f, 0.19141f}},
      {1.0f, 0, {0.78418f, 0.49724f, 0.21030f}},  {1.0f, 1, {0.32786f, 0.20595f, 0.08403f}},
  };
  for (const Case& c : cases) {
    const Vec3 got = furnace_disk_mean(test::metal_rough({0.8f, 0.5f, 0.2f}, c.metallic, c.roughness * c.roughness));
    std::printf("roughness %.2f metallic %.0f: kdray %.5f %.5f %.5f, specification %.5f %.5f %.5f\n", c.roughness,
                c.metallic, got.x, got.y, got.z, c.want.x, c.want.y, c.want.z);
    EXPECT_NEAR(got.x, c.want.x, 0.01f * c.want.x) << c.roughness << " " << c.metallic;
    EXPECT_NEAR(got.y, c.want.y, 0.01f * c.want.y) << c.roughness << " " << c.metallic;
    EXPECT_NEAR(got.z, c.want.z, 0.01f * c.want.z) << c.roughness << " " << c.metallic;
  }
}

TEST(MetallicRoughness, BlackBaseShowsTheSpecularLayerNotADiffuseSurface) {
  // Seen head-on, a smooth specular layer of index 1.5 reflects the environment with f0 = 0.04; a
  // diffuse surface of albedo 0 would be black.
  const Vec3 centre = render_sphere(test::metal_rough({0, 0, 0}, 0, 0.0f)).mean_within(0.3f);
  EXPECT_NEAR(centre.x, 0.04f, 0.004f);
  EXPECT_NEAR(centre.z, 0.04f, 0.004f);
}

TEST(MetallicRoughness, SmoothFullMetalIsAMirrorOfItsBaseColour) {
  // Near normal incidence Schlick's Fresnel is the base colour itself.
  const Vec3 base{0.9f, 0.5f, 0.2f};
  Material mirror;
  mirror.type = MaterialType::Mirror;
  mirror.base_color = base;
  const Vec3 want = render_sphere(mirror, 16).mean_within(0.4f);
  const Vec3 got = render_sphere(test::metal_rough(base, 1, 0.0f)).mean_within(0.4f);
  EXPECT_NEAR(want.x, 0.9f, 1e-4f);
  EXPECT_NEAR(got.x, want.x, 0.01f * want.x);
  EXPECT_NEAR(got.y, want.y, 0.01f * want.y);
  EXPECT_NEAR(got.z, want.z, 0.01f * want.z);
}

// A diffuse floor under a directional light shining straight down, seen from above, with a
// black quad between camera, light and floor.
constexpr float kFloorAlbedo = 0.5f, kIrradiance = 2.0f;
Film render_floor_under(const Material* occluder, RenderStats* stats) {
  Scene scene;
  test::add_floor(scene, 0.0f, 10.0f, kFloorAlbedo);
  const float s = 10;
  if (occluder) {
    scene.materials.push_back(*occluder);
    test::add_quad(scene, {{{-s, 1, -s}, {-s, 1, s}, {s, 1, s}, {s, 1, -s}}}, 1);
  }
  scene.cameras.push_back(test::camera_above_floor(10));
  scene.lights.push_back(test::directional_light({0, -1, 0}, kIrradiance));
  KdTree tree = test::tree_for(scene);
  RenderSettings settings = test::tiny_settings(8, 256);
  Film film = render(scene, tree, settings, DeviceSelection{}, stats);
  EXPECT_EQ(stats->nonfinite_values, 0u);
  return film;
}

double image_mean(const Film& film) {
  std::vector<float> means = film.means();
  double sum = 0;
  for (float v : means) sum += v;
  return sum / means.size();
}

Material black_with_alpha(AlphaMode mode, float alpha) {
  Material m;
  m.base_color = {0, 0, 0};
  m.alpha_mode = mode;
  m.alpha = alpha;
  return m;
}

TEST(Alpha, CutOutSurfaceLetsCameraAndShadowRaysThrough) {
  const double lit = kFloorAlbedo * kIrradiance / 3.14159265358979323846;
  RenderStats stats;
  EXPECT_NEAR(image_mean(render_floor_under(nullptr, &stats)), lit, 1e-4);
  EXPECT_EQ(stats.kernel_options.find("KD_FEATURE_ALPHA"), std::string::npos);
  const Material cut = black_with_alpha(AlphaMode::Mask, 0.3f);  // below the cutoff 0.5
  EXPECT_NEAR(image_mean(render_floor_under(&cut, &stats)), lit, 1e-4);
  EXPECT_NE(stats.kernel_options.find("KD_FEATURE_ALPHA"), std::string::npos);
  const Material kept = black_with_alpha(AlphaMode::Mask, 0.6f);
  EXPECT_EQ(image_mean(render_floor_under(&kept, &stats)), 0.0);
  const Material opaque = black_with_alpha(AlphaMode::Opaque, 0.0f);  // alpha unused
  EXPECT_EQ(image_mean(render_floor_under(&opaque, &stats)), 0.0);
}

TEST(Alpha, BlendedSurfaceLetsThroughOneMinusAlphaOfTheRays) {
  // Camera rays pass with probability 1 - alpha, and so do the floor's shadow rays.
  const double lit = kFloorAlbedo * kIrradiance / 3.14159265358979323846;
  RenderStats stats;
  const Material veil = black_with_alpha(AlphaMode::Blend, 0.5f);
  EXPECT_NEAR(image_mean(render_floor_under(&veil, &stats)) / lit, 0.25, 0.02);
}

}  // namespace
}  // namespace kdray
