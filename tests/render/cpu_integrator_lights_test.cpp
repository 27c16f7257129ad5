// The C++ build of the path tracer against the kernel (tests/render/cpu_integrator.h) with the
// lights other than emissive triangles: an environment map and point, spot and directional
// lights over a glTF metallic-roughness sphere on a diffuse floor.

#include "cpu_integrator.h"
#include "light_scenes.h"
#include "test_scenes.h"

namespace kdray::test {
namespace {

TEST(CpuIntegrator, EnvironmentAndPunctualLightsMatchTheKernelBitForBit) {
  Scene scene = make_sphere_scene(metal_rough({0.8f, 0.5f, 0.3f}, 0.4f, 0.35f));
  add_floor(scene, -1.0f, 3.0f, 0.6f);
  Light point;
  point.type = LightType::Point;
  point.position = {1.5f, 2.0f, 1.5f};
  point.color = {20, 18, 15};
  Light spot;
  spot.type = LightType::Spot;
  spot.position = {-1.5f, 2.5f, 1.0f};
  spot.direction = {0.48f, -0.8f, -0.36f};
  spot.color = {30, 30, 40};
  spot.inner_cone_radians = 0.3f;
  spot.outer_cone_radians = 0.5f;
  Light sun;
  sun.type = LightType::Directional;
  sun.direction = {0.0f, -0.8f, -0.6f};
  sun.color = {2, 2, 2};
  scene.lights = {point, spot, sun};
  RenderSettings settings = tiny_settings(24, 4);
  Environment env = sun_environment();
  env.rotate_degrees = 30;
  settings.environment = shared_environment(env);
  EXPECT_GT(expect_host_matches_kernel(
                scene, settings,
                {"-DKD_FEATURE_METALLIC_ROUGHNESS", "-DKD_FEATURE_ENVIRONMENT", "-DKD_FEATURE_PUNCTUAL"}),
            24u * 24u / 2);
}

}  // namespace
}  // namespace kdray::test
