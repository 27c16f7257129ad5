// The environment light: known answers under uniform environments (white furnace, a diffuse
// sphere), the map's direction mapping and rotation, the default light, and MIS on/off agreeing.
#include "light_scenes.h"
#include "render_fixture.h"
#include "test_scenes.h"

#include <kdray/render.h>

#include <gtest/gtest.h>

#include <cmath>

namespace kdray {
namespace {

Material diffuse(float albedo) {
  Material m;
  m.base_color = {albedo, albedo, albedo};
  return m;
}

struct SphereStats {
  double sphere_mean = 0, sphere_worst = 0;  // worst relative deviation of a sphere pixel
  size_t sphere_pixels = 0, background_pixels = 0;
  bool background_exact = true;
};

// Renders the sphere scene under env and splits pixels by the albedo AOV.
SphereStats render_sphere(float albedo, const Vec3& env_color, uint32_t bounces, bool mis = true) {
  Scene scene = test::make_sphere_scene(diffuse(albedo));
  KdTree tree = test::tree_for(scene);
  RenderSettings settings = test::tiny_settings(24, 64);
  settings.environment = test::shared_environment(uniform_environment(env_color));
  settings.max_bounces = bounces;
  settings.aov_albedo = true;
  settings.mis = mis;
  RenderStats stats;
  Film film = render(scene, tree, settings, DeviceSelection{}, &stats);
  EXPECT_EQ(stats.nonfinite_values, 0u);
  EXPECT_FALSE(stats.default_light);
  std::vector<float> means = film.means();
  const size_t channels = film.channels.size();
  SphereStats out;
  const float expected[3] = {albedo * env_color.x, albedo * env_color.y, albedo * env_color.z};
  for (size_t p = 0; p < film.pixel_count(); ++p) {
    const float* px = &means[p * channels];
    if (std::abs(px[3] - albedo) < 1e-5f) {  // every sample hit the sphere (edge pixels mix both and are skipped)
      ++out.sphere_pixels;
      for (int c = 0; c < 3; ++c) {
        out.sphere_mean += px[c] / expected[c] / 3;
        out.sphere_worst = std::max(out.sphere_worst, std::abs(double(px[c]) / expected[c] - 1));
      }
    } else if (px[3] == 0) {
      ++out.background_pixels;
      out.background_exact &= px[0] == env_color.x && px[1] == env_color.y && px[2] == env_color.z;
    }
  }
  out.sphere_mean /= double(out.sphere_pixels);
  return out;
}

TEST(EnvironmentLight, WhiteFurnaceSphereDisappears) {
  // Albedo 1 under radiance L: the sphere reflects exactly what it receives, L.
  SphereStats s = render_sphere(1.0f, {0.5f, 0.5f, 0.5f}, 8);
  ASSERT_GT(s.sphere_pixels, 100u);
  ASSERT_GT(s.background_pixels, 100u);
  EXPECT_TRUE(s.background_exact);
  EXPECT_NEAR(s.sphere_mean, 1.0, 0.01);
  EXPECT_LT(s.sphere_worst, 0.15);
}

TEST(EnvironmentLight, ConvexDiffuseSphereReflectsAlbedoTimesRadiance) {
  // Convex, so every hit point sees the whole environment over its hemisphere once: a * L,
  // whatever the bounce limit (B = 0 included).
  for (uint32_t bounces : {0u, 3u}) {
    SphereStats s = render_sphere(0.6f, {1.0f, 0.5f, 0.25f}, bounces);
    EXPECT_TRUE(s.background_exact) << bounces;
    EXPECT_NEAR(s.sphere_mean, 1.0, 0.01) << bounces;
    EXPECT_LT(s.sphere_worst, 0.15) << bounces;
  }
}

TEST(EnvironmentLight, WithoutMisTheSphereConvergesToTheSameValue) {
  SphereStats s = render_sphere(0.6f, {1.0f, 0.5f, 0.25f}, 2, false);
  EXPECT_TRUE(s.background_exact);
  EXPECT_NEAR(s.sphere_mean, 1.0, 0.01);
}

// Radiance a camera ray in `direction` sees in an empty scene (a narrow view, one pixel).
Vec3 seen(const Environment& env, const Vec3& direction, const Vec3& up = {0, 1, 0}) {
  Scene scene;
  KdTree tree = test::tree_for(scene);
  RenderSettings settings = test::tiny_settings(1, 1);
  Camera camera;
  camera.position = {0, 0, 0};
  camera.target = direction;
  camera.up = up;
  camera.vertical_fov_degrees = 0.01f;
  settings.camera = camera;
  settings.environment = test::shared_environment(env);
  std::vector<float> m = render(scene, tree, settings, DeviceSelection{}).means();
  return {m[0], m[1], m[2]};
}

TEST(EnvironmentLight, DirectionToPixelMappingIsMitsubas) {
  // u = atan2(x, -z) / 2pi, v = acos(y) / pi, column centres at (i + 0.5) / W, rows on the poles
  // at j / (H - 1): an 8 x 4 map looked up bilinearly at fx = u W - 0.5, fy = v (H - 1).
  Environment env = test::coordinate_environment(8, 4);
  auto expect = [&](const Vec3& d, float fx, float fy, const Vec3& up = {0, 1, 0}) {
    Vec3 v = seen(env, d, up);
    if (fx >= 0) {
      EXPECT_NEAR(v.x, fx, 0.01) << d.x << "," << d.y << "," << d.z;
    }
    EXPECT_NEAR(v.y, fy, 0.01) << d.x << "," << d.y << "," << d.z;
  };
  expect({1, 0, 0}, 1.5f, 1.5f);    // u = 0.25
  expect({0, 0, 1}, 3.5f, 1.5f);    // u = 0.5
  expect({-1, 0, 0}, 5.5f, 1.5f);   // u = 0.75
  expect({0, 1, 0}, -1, 0.0f, {0, 0, -1});  // the top row (+Y); u is arbitrary at the pole
  expect({0, -1, 0}, -1, 3.0f, {0, 0, -1});
  // 45 degrees up from +X: v = 0.25 is row 0.75 (texel-centred rows would give 0.5).
  expect({0.70710678f, 0.70710678f, 0}, 1.5f, 0.75f);
}

TEST(EnvironmentLight, RotationTurnsTheMapCounterClockwiseSeenFromAbove) {
  // Turned by 90 degrees about +Y, what was at +X (u = 0.25) is seen towards -Z, and +X now
  // shows what was at +Z (u = 0.5).
  Environment env = test::coordinate_environment(8, 4);
  env.rotate_degrees = 90;
  EXPECT_NEAR(seen(env, {0, 0, -1}).x, 1.5f, 0.01);
  EXPECT_NEAR(seen(env, {1, 0, 0}).x, 3.5f, 0.01);
}

TEST(EnvironmentLight, StrengthScalesTheMap) {
  Environment env = uniform_environment({0.25f, 0.5f, 1.0f});
  env.strength = 4;
  Vec3 v = seen(env, {0, 0, -1});
  EXPECT_EQ(v.x, 1.0f);
  EXPECT_EQ(v.y, 2.0f);
  EXPECT_EQ(v.z, 4.0f);
}

TEST(EnvironmentLight, MisOnAndOffConvergeToTheSameImage) {
  // A diffuse sphere on a rough metal-free floor under a sky with a small sun: the two
  // estimators differ in noise, not in expectation.
  Scene scene = test::make_sphere_scene(diffuse(0.7f), 0.5f, 12, 24);
  const uint32_t base = uint32_t(scene.positions.size());
  scene.positions.insert(scene.positions.end(), {{-3, -0.5f, -3}, {-3, -0.5f, 3}, {3, -0.5f, 3}, {3, -0.5f, -3}});
  scene.indices.insert(scene.indices.end(), {base, base + 1, base + 2, base, base + 2, base + 3});
  scene.material_ids.insert(scene.material_ids.end(), {0, 0});
  KdTree tree = test::tree_for(scene);
  RenderSettings settings = test::tiny_settings(16, 512);
  settings.environment = test::shared_environment(test::sun_environment());
  settings.max_bounces = 2;
  Film with = render(scene, tree, settings, DeviceSelection{});
  settings.mis = false;
  Film without = render(scene, tree, settings, DeviceSelection{});
  // Whole-image means agree within 2%; pixels within noise on average (relative RMS).
  EXPECT_NEAR(without.mean_radiance() / with.mean_radiance(), 1.0, 0.02);
  std::vector<float> a = with.means(), b = without.means();
  double error = 0, energy = 0;
  for (size_t i = 0; i < a.size(); ++i) {
    error += (a[i] - b[i]) * (a[i] - b[i]);
    energy += a[i] * a[i];
  }
  EXPECT_LT(std::sqrt(error / energy), 0.15);
}

TEST(DefaultLight, AnUnlitSceneGetsAUniformWhiteEnvironment) {
  Scene scene;
  KdTree tree = test::tree_for(scene);
  RenderStats stats;
  Film film = render(scene, tree, test::tiny_settings(8, 2), DeviceSelection{}, &stats);
  EXPECT_TRUE(stats.default_light);
  EXPECT_NE(stats.kernel_options.find("KD_FEATURE_ENVIRONMENT"), std::string::npos);
  for (float value : film.means()) ASSERT_EQ(value, kDefaultLightRadiance);
  EXPECT_EQ(stats.nonfinite_values, 0u);
}

TEST(DefaultLight, TurnedOffAnUnlitSceneRendersBlack) {
  Scene scene;
  KdTree tree = test::tree_for(scene);
  RenderSettings settings = test::tiny_settings(8, 2);
  settings.default_light = false;
  RenderStats stats;
  Film film = render(scene, tree, settings, DeviceSelection{}, &stats);
  EXPECT_FALSE(stats.default_light);
  EXPECT_EQ(stats.kernel_options.find("KD_FEATURE_ENVIRONMENT"), std::string::npos);
  EXPECT_EQ(film.mean_radiance(), 0.0);
  EXPECT_EQ(stats.nonfinite_values, 0u);
}

TEST(DefaultLight, ASceneWithEmittersKeepsItsOwnLight) {
  Material light;
  light.type = MaterialType::Emissive;
  light.emission = {1, 1, 1};
  Scene scene = test::make_inward_cube(light);
  EXPECT_EQ(render_environment(scene, RenderSettings{}), nullptr);
  // ... and its kernel has no environment or punctual-light code at all.
  const std::string options = kernel_feature_options(scene, RenderSettings{}, {});
  EXPECT_EQ(options.find("KD_FEATURE_ENVIRONMENT"), std::string::npos);
  EXPECT_EQ(options.find("KD_FEATURE_PUNCTUAL"), std::string::npos);
}

TEST(DefaultCamera, ASceneWithoutCameraIsFramedByItsBounds) {
  Scene scene = test::make_sphere_scene(diffuse(0.5f));
  scene.cameras.clear();
  Camera camera = render_camera(scene, RenderSettings{});
  Camera expected = default_camera(scene_bounds(scene));
  EXPECT_EQ(camera.position.z, expected.position.z);
  EXPECT_GT(camera.position.z, 1.0f);
  EXPECT_EQ(camera.target.x, 0.0f);
}

}  // namespace
}  // namespace kdray
