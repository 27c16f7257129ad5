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

// Blender 3.4's own glTF exporter wrote tests/scene/fixtures/blender/blender-export.glb; its README
// gives every value below from the file's JSON.
class BlenderExport : public ::testing::Test {
 protected:
  static void SetUpTestSuite() { scene_ = new Scene(import_scene(kTests + "fixtures/blender/blender-export.glb", {})); }
  static void TearDownTestSuite() { delete scene_; }
  static const Material& material(const std::string& name) {
    for (const Material& m : scene_->materials)
      if (m.name == name) return m;
    throw std::runtime_error("no material " + name);
  }
  static const Light& light(const std::string& name) {
    for (const Light& l : scene_->lights)
      if (l.name == name) return l;
    throw std::runtime_error("no light " + name);
  }
  static inline Scene* scene_ = nullptr;
};

TEST_F(BlenderExport, TheCameraKeepsItsVerticalAngleAndAspectRatio) {
  const Camera& camera = named_camera(*scene_, "Camera");
  EXPECT_NEAR(camera.vertical_fov_degrees, 51.4814f, 1e-3);  // Assimp's route gave 54.2264
  EXPECT_NEAR(camera.aspect_ratio, 4.0f / 3, 1e-6);
  EXPECT_EQ(camera.projection, Projection::Perspective);
  EXPECT_NEAR(camera.position.y, 3, 1e-5);
  EXPECT_NEAR(camera.position.z, 6, 1e-5);
  const float dy = camera.target.y - camera.position.y, dz = camera.target.z - camera.position.z;
  EXPECT_NEAR(dy / std::sqrt(dy * dy + dz * dz), -0.34202f, 1e-5);  // 20 degrees down
}

TEST_F(BlenderExport, TheOrthographicCameraKeepsItsExtent) {
  const Camera& ortho = named_camera(*scene_, "OrthoCamera");
  EXPECT_EQ(ortho.projection, Projection::Orthographic);
  EXPECT_FLOAT_EQ(ortho.orthographic_half_height, 2.25f);
  EXPECT_FLOAT_EQ(ortho.aspect_ratio, 3.0f / 2.25f);
}

TEST_F(BlenderExport, EmissionIsTheFactorTimesTheStrength) {
  const Material& lamp = material("Lamp");
  EXPECT_EQ(lamp.type, MaterialType::Emissive);
  EXPECT_FLOAT_EQ(lamp.emission.x, 6);
  EXPECT_FLOAT_EQ(lamp.emission.y, 5.4f);
  EXPECT_FLOAT_EQ(lamp.emission.z, 4.8f);
}

TEST_F(BlenderExport, LightsAreInWattsAsCyclesRendersThem) {
  const Light& point = light("PointLight");  // 100 W: 5435.14 cd
  EXPECT_EQ(point.type, LightType::Point);
  EXPECT_NEAR(point.color.x, 7.95775f, 1e-4);
  EXPECT_NEAR(point.color.y, 6.3662f, 1e-4);
  EXPECT_NEAR(point.color.z, 4.77465f, 1e-4);
  const Light& spot = light("SpotLight");  // 50 W: 2717.57 cd
  EXPECT_EQ(spot.type, LightType::Spot);
  EXPECT_NEAR(spot.color.x, 3.97887f, 1e-4);
  EXPECT_NEAR(spot.outer_cone_radians, 0.523599f, 1e-5);
  EXPECT_NEAR(spot.inner_cone_radians, 0.418879f, 1e-5);
  const Light& sun = light("Sun");  // 3 W/m^2: 2049 lx
  EXPECT_EQ(sun.type, LightType::Directional);
  EXPECT_NEAR(sun.color.x, 3, 1e-4);
  EXPECT_NEAR(sun.color.z, 2.7f, 1e-4);
}

TEST_F(BlenderExport, MaterialsAreTheSpecificationsWithItsDefaults) {
  const Material& plastic = material("RoughPlastic");
  EXPECT_EQ(plastic.type, MaterialType::MetallicRoughness);
  EXPECT_FLOAT_EQ(plastic.base_color.x, 0.8f);
  EXPECT_EQ(plastic.metallic, 0.0f);
  EXPECT_EQ(plastic.roughness, 1.0f);  // roughnessFactor left out: 1, alpha 1
  const Material& gold = material("Gold");
  EXPECT_EQ(gold.type, MaterialType::MetallicRoughness);
  EXPECT_EQ(gold.metallic, 1.0f);  // metallicFactor left out: 1
  EXPECT_NEAR(gold.roughness, 0.09f, 1e-6);
  EXPECT_NEAR(material("HalfRough").roughness, 0.25f, 1e-6);
  const Material& glass = material("Glass");
  EXPECT_EQ(glass.type, MaterialType::Dielectric);
  EXPECT_NEAR(glass.ior, 1.45f, 1e-6);
}

TEST_F(BlenderExport, OnlyTheClearcoatIsNamedAsNotModelled) {
  EXPECT_EQ(warnings_naming(*scene_, "KHR_materials_clearcoat"), 1u);
  EXPECT_EQ(warnings_naming(*scene_, "extension"), 1u);
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
