// Punctual lights: Assimp's glTF KHR_lights_punctual import (node transforms, colour x
// intensity, spot half-angles), the .kdscene lights section and its round trip (older versions:
// materials_test.cpp).
#include "scene_test_util.h"

#include <kdray/container_file.h>
#include <kdray/error.h>
#include <kdray/format.h>
#include <kdray/import.h>
#include <kdray/scene_file.h>

#include <test_corpus.h>

#include <gtest/gtest.h>

#include <cmath>
#include <cstddef>
#include <cstring>
#include <filesystem>
#include <fstream>

namespace kdray {
namespace {

const std::string kLightsGltf = std::string(KDRAY_SOURCE_DIR) + "/tests/scene/lights-punctual.gltf";

const Light& named(const Scene& scene, const std::string& name) {
  for (const Light& light : scene.lights)
    if (light.name == name) return light;
  throw std::runtime_error("no light " + name);
}

TEST(ImportLights, GltfPunctualLightsKeepTheirNodesColoursAndHalfAnglesInWatts) {
  Scene scene = import_scene(kLightsGltf, {});
  ASSERT_EQ(scene.lights.size(), 3u);
  // Spot: node at (0, 2, 0) turned -90 degrees about X, so its -Z points down; colour
  // (1, 0.5, 0.25) x intensity 10 candela, 1/683 W/sr each; the file's innerConeAngle 0.2 and
  // outerConeAngle 0.5 are already half-angles.
  const Light& spot = named(scene, "spotnode");
  EXPECT_EQ(spot.type, LightType::Spot);
  EXPECT_NEAR(spot.position.y, 2, 1e-6);
  EXPECT_NEAR(spot.direction.y, -1, 1e-6);
  EXPECT_NEAR(spot.direction.z, 0, 1e-6);
  EXPECT_FLOAT_EQ(spot.color.x, 10 / 683.0f);
  EXPECT_FLOAT_EQ(spot.color.y, 5 / 683.0f);
  EXPECT_FLOAT_EQ(spot.color.z, 2.5f / 683.0f);
  EXPECT_FLOAT_EQ(spot.inner_cone_radians, 0.2f);
  EXPECT_FLOAT_EQ(spot.outer_cone_radians, 0.5f);
  const Light& bulb = named(scene, "bulbnode");
  EXPECT_EQ(bulb.type, LightType::Point);
  EXPECT_FLOAT_EQ(bulb.position.x, 1);
  EXPECT_FLOAT_EQ(bulb.position.y, 2);
  EXPECT_FLOAT_EQ(bulb.position.z, 3);
  EXPECT_FLOAT_EQ(bulb.color.x, 3 / 683.0f);
  // Directional: -Z turned -45 degrees about X; 2 lux, 2/683 W/m^2.
  const Light& sun = named(scene, "sunnode");
  EXPECT_EQ(sun.type, LightType::Directional);
  EXPECT_NEAR(sun.direction.y, -std::sqrt(0.5), 1e-5);
  EXPECT_NEAR(sun.direction.z, -std::sqrt(0.5), 1e-5);
  EXPECT_FLOAT_EQ(sun.color.x, 2 / 683.0f);
}

TEST(ImportLights, ZUpImportTurnsLightsWithTheGeometry) {
  ImportOptions options;
  options.up_axis = UpAxis::Z;
  options.scale = 2;
  Scene scene = import_scene(kLightsGltf, options);
  const Light& bulb = named(scene, "bulbnode");  // (1, 2, 3) -> (x, z, -y) * 2
  EXPECT_FLOAT_EQ(bulb.position.x, 2);
  EXPECT_FLOAT_EQ(bulb.position.y, 6);
  EXPECT_FLOAT_EQ(bulb.position.z, -4);
  const Light& spot = named(scene, "spotnode");  // (0, -1, 0) -> (0, 0, 1)
  EXPECT_NEAR(spot.direction.z, 1, 1e-6);
}

class LightsFile : public test::TempDirTest<> {};

TEST_F(LightsFile, RoundTripsAndEntersTheContentHash) {
  Scene scene = import_scene(kLightsGltf, {});
  write_scene(path("lights.kdscene"), scene);
  Scene loaded = read_scene(path("lights.kdscene"));
  ASSERT_EQ(loaded.lights.size(), scene.lights.size());
  for (size_t i = 0; i < scene.lights.size(); ++i) {
    EXPECT_EQ(loaded.lights[i].name, scene.lights[i].name);
    EXPECT_EQ(loaded.lights[i].type, scene.lights[i].type);
    EXPECT_EQ(std::memcmp(&loaded.lights[i].position, &scene.lights[i].position, sizeof(Vec3)), 0);
    EXPECT_EQ(loaded.lights[i].outer_cone_radians, scene.lights[i].outer_cone_radians);
  }
  EXPECT_EQ(loaded.content_hash, scene.content_hash);
  EXPECT_TRUE(peek_scene(path("lights.kdscene")).flags & format::kSceneHasLights);
  Scene brighter = scene;
  brighter.lights[0].color.x *= 2;
  EXPECT_NE(compute_content_hash(brighter), scene.content_hash);
}

TEST_F(LightsFile, ASceneWithoutLightsKeepsItsVersionOneHash) {
  // The hash of a scene without lights does not include the (empty) lights part.
  Scene scene = test::make_quad_scene(true, true, false);
  Scene with_light = scene;
  with_light.lights.push_back(Light{});
  EXPECT_NE(compute_content_hash(with_light), compute_content_hash(scene));
  EXPECT_EQ(compute_content_hash(scene), scene.content_hash);
}

TEST_F(LightsFile, ABadLightIsRefusedOnWrite) {
  Scene scene = test::make_quad_scene(false, false, false);
  Light light;
  light.direction = {0, 0, 0};  // not a unit vector
  scene.lights.push_back(light);
  EXPECT_THROW(write_scene(path("bad.kdscene"), scene), Error);
}

}  // namespace
}  // namespace kdray
