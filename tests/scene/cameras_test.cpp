// Cameras and glTF facts as the asset's author made them: exact vertical angles at any aspect
// ratio (glTF from its JSON, Collada from Assimp), aspect ratios and orthographic projections
// kept, KHR_materials_emissive_strength applied, unmodelled extensions named, and the .kdscene
// camera fields read from files older than version 6.
#include "scene_test_util.h"

#include <kdray/format.h>
#include <kdray/import.h>
#include <kdray/scene_file.h>

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <string>

namespace kdray {
namespace {

const std::string kTests = std::string(KDRAY_SOURCE_DIR) + "/tests/scene/";

const Camera& named_camera(const Scene& scene, const std::string& name) {
  for (const Camera& camera : scene.cameras)
    if (camera.name == name) return camera;
  throw std::runtime_error("no camera " + name);
}

float degrees(double radians) { return float(radians * 180.0 / M_PI); }

size_t warnings_naming(const Scene& scene, const std::string& text) {
  const auto& warnings = scene.import_stats.warnings;
  return std::count_if(warnings.begin(), warnings.end(),
                       [&](const std::string& warning) { return warning.find(text) != std::string::npos; });
}

TEST(GltfCameras, TheVerticalAngleIsTheFilesAtANonSquareAspect) {
  const Scene scene = import_scene(kTests + "cameras-and-extensions.gltf", {});
  const Camera& wide = named_camera(scene, "wide");
  EXPECT_EQ(wide.projection, Projection::Perspective);
  EXPECT_FLOAT_EQ(wide.vertical_fov_degrees, degrees(0.9));  // not 2 atan(tan(0.9 * 2 / 2) / 2)
  EXPECT_FLOAT_EQ(wide.aspect_ratio, 2.0f);
  const Camera& unsized = named_camera(scene, "noaspect");
  EXPECT_FLOAT_EQ(unsized.vertical_fov_degrees, degrees(0.6));
  EXPECT_EQ(unsized.aspect_ratio, 0.0f);
}

TEST(GltfCameras, AnOrthographicCameraStaysOrthographic) {
  const Scene scene = import_scene(kTests + "cameras-and-extensions.gltf", {});
  const Camera& plan = named_camera(scene, "plan");
  EXPECT_EQ(plan.projection, Projection::Orthographic);
  EXPECT_FLOAT_EQ(plan.orthographic_half_height, 1.5f);  // ymag
  EXPECT_FLOAT_EQ(plan.aspect_ratio, 2.0f);              // xmag / ymag
  EXPECT_NEAR(plan.position.y, 5, 1e-6);
  EXPECT_NEAR(plan.target.y, 4, 1e-6);  // turned to look down
}

TEST(GltfMaterials, EmissiveStrengthMultipliesTheEmissiveFactor) {
  const Scene scene = import_scene(kTests + "cameras-and-extensions.gltf", {});
  const auto lamp = std::find_if(scene.materials.begin(), scene.materials.end(),
                                 [](const Material& m) { return m.name == "lamp"; });
  ASSERT_NE(lamp, scene.materials.end());
  EXPECT_EQ(lamp->type, MaterialType::Emissive);
  EXPECT_FLOAT_EQ(lamp->emission.x, 6);
  EXPECT_FLOAT_EQ(lamp->emission.y, 3);
  EXPECT_FLOAT_EQ(lamp->emission.z, 1.5f);
}

TEST(GltfExtensions, EachUnmodelledExtensionIsNamedOnce) {
  const Scene scene = import_scene(kTests + "cameras-and-extensions.gltf", {});
  EXPECT_EQ(warnings_naming(scene, "KHR_materials_clearcoat"), 1u);
  EXPECT_EQ(warnings_naming(scene, "KHR_texture_transform"), 1u);
  EXPECT_EQ(warnings_naming(scene, "KHR_materials_emissive_strength"), 0u);
  EXPECT_EQ(scene.import_stats.warnings.size(), 2u);
}

TEST(ColladaCameras, TheVerticalAngleFollowsFromTheHorizontalOneThroughTan) {
  const Scene scene = import_scene(kTests + "camera-xfov-aspect.dae", {});
  const Camera& wide = named_camera(scene, "wide");
  EXPECT_FLOAT_EQ(wide.aspect_ratio, 1.5f);
  EXPECT_NEAR(wide.vertical_fov_degrees, degrees(2 * std::atan(std::tan(M_PI / 6) / 1.5)), 1e-4);
}

TEST(SceneCameras, FilesBeforeVersionSixReadWithoutAnAspectRatio) {
  const std::string version4 = kTests + "fixtures/version-4-normal-map.kdscene";
  ASSERT_LT(peek_scene(version4).version, format::kSceneCameraAspectVersion);
  const Scene scene = read_scene(version4);
  ASSERT_FALSE(scene.cameras.empty());
  for (const Camera& camera : scene.cameras) {
    EXPECT_EQ(camera.aspect_ratio, 0.0f);
    EXPECT_EQ(camera.projection, Projection::Perspective);
  }
}

}  // namespace
}  // namespace kdray
