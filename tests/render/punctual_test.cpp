// Punctual lights, known answers: a diffuse plane of albedo a under a point light of intensity I
// at distance r has radiance a I cos(theta) / (pi r^2); a spot light adds its cone; a directional
// light of irradiance E gives a E cos(theta) / pi.
#include "render_fixture.h"
#include "test_scenes.h"

#include <kdray/render.h>

#include <gtest/gtest.h>

#include <cmath>

namespace kdray {
namespace {

constexpr float kAlbedo = 0.5f;
constexpr double kPi = 3.14159265358979323846;

// A 20 x 20 diffuse floor at y = 0 seen straight down from (0, 4, 0) with a kFov degree view:
// narrow, so that a pixel's footprint is small and its jittered samples see nearly the value
// at its centre.
constexpr double kFov = 10;
Scene floor_scene() {
  Scene scene;
  Material m;
  m.base_color = {kAlbedo, kAlbedo, kAlbedo};
  scene.materials.push_back(m);
  const float s = 10;
  scene.positions = {{-s, 0, -s}, {-s, 0, s}, {s, 0, s}, {s, 0, -s}};
  scene.indices = {0, 1, 2, 0, 2, 3};
  scene.material_ids = {0, 0};
  scene.cameras.push_back(test::camera_above_floor(float(kFov)));
  return scene;
}

// The floor point a pixel centre sees (the camera of floor_scene, square image).
Vec3 floor_point(uint32_t x, uint32_t y, uint32_t size) {
  const double t = std::tan(kFov / 2 * kPi / 180);
  const double sx = (2 * (x + 0.5) / size - 1) * t, sy = (1 - 2 * (y + 0.5) / size) * t;
  // forward (0,-1,0), right = forward x up = (1,0,0), up = right x forward = (0,0,-1)
  return {float(4 * sx), 0, float(-4 * sy)};
}

Film render_floor(const Light& light, uint32_t size, uint32_t spp) {
  Scene scene = floor_scene();
  scene.lights.push_back(light);
  KdTree tree = test::tree_for(scene);
  RenderSettings settings = test::tiny_settings(size, spp);
  RenderStats stats;
  Film film = render(scene, tree, settings, DeviceSelection{}, &stats);
  EXPECT_FALSE(stats.default_light);
  EXPECT_NE(stats.kernel_options.find("KD_FEATURE_PUNCTUAL"), std::string::npos);
  EXPECT_EQ(stats.kernel_options.find("KD_FEATURE_ENVIRONMENT"), std::string::npos);
  EXPECT_EQ(stats.nonfinite_values, 0u);
  return film;
}

// Checks every pixel against expected(point on the floor) within a relative tolerance (the
// pixel footprint averages a smooth function), and exact zeros where it is zero.
template <typename Expected>
void expect_floor(const Film& film, Expected expected, double tolerance) {
  std::vector<float> means = film.means();
  for (uint32_t y = 0; y < film.height; ++y) {
    for (uint32_t x = 0; x < film.width; ++x) {
      const Vec3 want = expected(floor_point(x, y, film.width));
      const float* got = &means[(size_t(y) * film.width + x) * 3];
      const float w[3] = {want.x, want.y, want.z};
      for (int c = 0; c < 3; ++c) {
        if (w[c] == 0) continue;
        ASSERT_NEAR(got[c], w[c], tolerance * w[c]) << "pixel " << x << "," << y << " channel " << c;
      }
    }
  }
}

TEST(PointLight, DiffusePlaneRadianceIsAlbedoTimesIntensityTimesCosOverPiRSquared) {
  Light light;
  light.type = LightType::Point;
  light.position = {0.5f, 0.6f, -0.25f};  // the view spans +-0.35: cos(theta) from 0.6 to 0.95
  light.color = {3, 2, 1};  // W/sr
  Film film = render_floor(light, 16, 128);
  expect_floor(film, [&](const Vec3& p) {
    const double dx = light.position.x - p.x, dy = light.position.y - p.y, dz = light.position.z - p.z;
    const double r2 = dx * dx + dy * dy + dz * dz, cos_theta = dy / std::sqrt(r2);
    const double k = kAlbedo * cos_theta / (kPi * r2);
    return Vec3{float(k * light.color.x), float(k * light.color.y), float(k * light.color.z)};
  }, 0.02);
}

TEST(DirectionalLight, DiffusePlaneRadianceIsAlbedoTimesIrradianceTimesCosOverPi) {
  Light light;
  light.type = LightType::Directional;
  light.direction = {0.6f, -0.8f, 0};
  light.color = {2, 2, 2};  // W/m^2
  Film film = render_floor(light, 8, 2);
  const float want = float(kAlbedo * 2 * 0.8 / kPi);
  for (float value : film.means()) ASSERT_NEAR(value, want, 1e-5f);
}

TEST(SpotLight, FullInsideTheInnerConeDarkOutsideTheOuterCone) {
  Light light;
  light.type = LightType::Spot;
  light.position = {0, 0.5f, 0};
  light.direction = {0, -1, 0};
  light.color = {4, 4, 4};
  light.inner_cone_radians = 0.3f;  // half-angles: radii 0.15 and 0.21 on the floor
  light.outer_cone_radians = 0.4f;
  const uint32_t size = 32;
  Film film = render_floor(light, size, 4);
  std::vector<float> means = film.means();
  size_t inside = 0, outside = 0;
  for (uint32_t y = 0; y < size; ++y) {
    for (uint32_t x = 0; x < size; ++x) {
      const Vec3 p = floor_point(x, y, size);
      const double r = std::sqrt(p.x * p.x + p.z * p.z), angle = std::atan2(r, 0.5);
      const double pixel_angle = 0.05;  // a pixel's footprint spans less than this
      const float got = means[(size_t(y) * size + x) * 3];
      if (angle < light.inner_cone_radians - pixel_angle) {
        const double r2 = r * r + 0.25, cos_theta = 0.5 / std::sqrt(r2), want = kAlbedo * 4 * cos_theta / (kPi * r2);
        ASSERT_NEAR(got, want, 0.02 * want) << x << "," << y;
        ++inside;
      } else if (angle > light.outer_cone_radians + pixel_angle) {
        ASSERT_EQ(got, 0.0f) << x << "," << y;
        ++outside;
      }
    }
  }
  EXPECT_GT(inside, 20u);
  EXPECT_GT(outside, 20u);
}

TEST(PunctualLights, ShareNextEventEstimationWithTheEnvironmentUnbiased) {
  // Point light plus a uniform environment: the floor sees both, added.
  Light light;
  light.type = LightType::Point;
  light.position = {0, 1, 0};
  light.color = {1, 1, 1};
  Scene scene = floor_scene();
  scene.lights.push_back(light);
  KdTree tree = test::tree_for(scene);
  RenderSettings settings = test::tiny_settings(4, 4096);
  settings.camera = Camera{"", {0, 4, 0}, {0, 0, 0}, {0, 0, -1}, 2};
  settings.environment = std::make_shared<const Environment>(uniform_environment({0.25f, 0.25f, 0.25f}));
  settings.max_bounces = 0;
  Film film = render(scene, tree, settings, DeviceSelection{});
  // Near the centre: point a I / (pi r^2) with r = 1, plus the sky a * L (the plane is
  // infinite enough: it hides a 2% sliver of the upper hemisphere's cosine-weighted sky at most).
  const double want = kAlbedo * 1 / kPi + kAlbedo * 0.25;
  EXPECT_NEAR(film.mean_radiance(), want, 0.03 * want);
}

TEST(PunctualLights, WavefrontAndMegakernelGiveTheSameImageWithEveryLightKind) {
  // Emissive triangles, an environment map and a spot light: the same bytes from both forms.
  Scene scene = floor_scene();
  Material glow;
  glow.type = MaterialType::Emissive;
  glow.emission = {2, 2, 2};
  scene.materials.push_back(glow);
  const uint32_t base = uint32_t(scene.positions.size());
  scene.positions.insert(scene.positions.end(), {{-0.2f, 1, -0.2f}, {0.2f, 1, -0.2f}, {0.2f, 1, 0.2f}, {-0.2f, 1, 0.2f}});
  scene.indices.insert(scene.indices.end(), {base, base + 1, base + 2, base, base + 2, base + 3});
  scene.material_ids.insert(scene.material_ids.end(), {1, 1});
  scene.emissive_triangles = {2, 3};
  Light spot;
  spot.type = LightType::Spot;
  spot.position = {0.3f, 0.5f, 0};
  spot.direction = {0, -1, 0};
  spot.outer_cone_radians = 0.6f;
  spot.inner_cone_radians = 0.3f;
  scene.lights.push_back(spot);
  KdTree tree = test::tree_for(scene);
  RenderSettings settings = test::tiny_settings(8, 4);
  settings.camera = Camera{"", {0, 3, 3}, {0, 0, 0}, {0, 1, 0}, 60};
  Environment env = uniform_environment({0.1f, 0.2f, 0.3f});
  env.rotate_degrees = 30;
  settings.environment = std::make_shared<const Environment>(env);
  RenderStats stats;
  Film mega = render(scene, tree, settings, DeviceSelection{}, &stats);
  for (const char* feature : {"EMISSION", "ENVIRONMENT", "PUNCTUAL"})
    EXPECT_NE(stats.kernel_options.find(std::string("KD_FEATURE_") + feature), std::string::npos) << feature;
  settings.form = RenderForm::Wavefront;
  Film wave = render(scene, tree, settings, DeviceSelection{});
  EXPECT_EQ(wave.sums, mega.sums);
  EXPECT_GT(mega.mean_radiance(), 0.1);
}

}  // namespace
}  // namespace kdray
