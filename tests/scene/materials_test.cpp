// glTF metallic-roughness materials: the mapping of Assimp's glTF keys (alpha modes, transmission
// and KHR_materials_ior, metals, plastics), textures of Debian's assimp-testmodels, the format
// version 3 material fields and their round trip, and version 1 and 2 files still read.
#include "scene_test_util.h"

#include <kdray/format.h>
#include <kdray/import.h>
#include <kdray/scene_file.h>

#include <test_corpus.h>

#include <gtest/gtest.h>

#include <cstddef>
#include <filesystem>
#include <fstream>

namespace kdray {
namespace {

const std::string kMaterialsGltf = std::string(KDRAY_SOURCE_DIR) + "/tests/scene/materials-gltf.gltf";
// Written by the version 2 kdconvert from materials-gltf.gltf (its mapping made the masked and
// blended materials glass).
const std::string kVersion2File = std::string(KDRAY_SOURCE_DIR) + "/tests/scene/fixtures/version-2-materials.kdscene";
// Debian's assimp-testmodels (scripts/install-deps.sh), where tests/CMakeLists.txt says.
const std::filesystem::path kAssimpModels = std::filesystem::path(KDRAY_ASSIMP_MODELS_DIR) / "glTF2";

const Material& named(const Scene& scene, const std::string& name) {
  for (const Material& material : scene.materials)
    if (material.name == name) return material;
  throw std::runtime_error("no material " + name);
}

// The Assimp test models are a package, not corpus files: missing is a failure under CI=true.
#define KDRAY_ASSIMP_MODEL(var, relative)                                                        \
  do {                                                                                           \
    var = (kAssimpModels / (relative)).string();                                                 \
    if (!std::filesystem::exists(var)) {                                                         \
      if (::kdray::test::running_in_ci()) FAIL() << "assimp-testmodels file missing in CI: " << var; \
      GTEST_SKIP() << "assimp-testmodels file missing: " << var;                                 \
    }                                                                                            \
  } while (0)

TEST(ImportMaterials, GltfAlphaModesAreAlphaNotGlass) {
  Scene scene = import_scene(kMaterialsGltf, {});
  const Material& masked = named(scene, "masked");
  EXPECT_EQ(masked.type, MaterialType::MetallicRoughness);
  EXPECT_EQ(masked.alpha_mode, AlphaMode::Mask);
  EXPECT_FLOAT_EQ(masked.alpha, 0.3f);
  EXPECT_FLOAT_EQ(masked.alpha_cutoff, 0.4f);
  EXPECT_FLOAT_EQ(masked.base_color.y, 0.6f);
  EXPECT_FLOAT_EQ(masked.roughness, 0.25f);  // alpha = perceptual roughness squared
  const Material& veil = named(scene, "veil");
  EXPECT_EQ(veil.type, MaterialType::MetallicRoughness);
  EXPECT_EQ(veil.alpha_mode, AlphaMode::Blend);
  EXPECT_FLOAT_EQ(veil.alpha, 0.25f);
  EXPECT_FLOAT_EQ(veil.metallic, 0.25f);
  EXPECT_EQ(named(scene, "plastic").alpha_mode, AlphaMode::Opaque);
}

TEST(ImportMaterials, GltfTransmissionAndIorMakeGlass) {
  Scene scene = import_scene(kMaterialsGltf, {});
  const Material& water = named(scene, "water");
  EXPECT_EQ(water.type, MaterialType::Dielectric);
  EXPECT_FLOAT_EQ(water.ior, 1.33f);
}

TEST(ImportMaterials, SmoothFullMetalIsAMirrorOfItsBaseColour) {
  Scene scene = import_scene(kMaterialsGltf, {});
  const Material& polished = named(scene, "polished");
  EXPECT_EQ(polished.type, MaterialType::Mirror);
  EXPECT_FLOAT_EQ(polished.base_color.x, 0.9f);
  EXPECT_FLOAT_EQ(polished.base_color.z, 0.2f);
}

TEST(ImportMaterials, RoughNonMetalIsAMetallicRoughnessMaterial) {
  Scene scene = import_scene(kMaterialsGltf, {});
  const Material& plastic = named(scene, "plastic");
  EXPECT_EQ(plastic.type, MaterialType::MetallicRoughness);
  EXPECT_FLOAT_EQ(plastic.metallic, 0.0f);
  EXPECT_NEAR(plastic.roughness, 0.09f, 1e-6);
  EXPECT_FLOAT_EQ(plastic.ior, 1.5f);  // glTF's default
}

TEST(ImportMaterials, AssimpTestModelBaseColourTexture) {
  std::string path;
  KDRAY_ASSIMP_MODEL(path, "BoxTextured-glTF/BoxTextured.gltf");
  Scene scene = import_scene(path, {});
  const Material& material = named(scene, "Texture");
  EXPECT_EQ(material.type, MaterialType::MetallicRoughness);
  ASSERT_GE(material.diffuse_texture, 0);
  EXPECT_EQ(scene.textures[material.diffuse_texture].name, "CesiumLogoFlat.png");
  EXPECT_GT(scene.textures[material.diffuse_texture].width, 0u);
  EXPECT_FALSE(scene.uvs.empty());
}

TEST(ImportMaterials, AssimpTestModelNormalAndMetallicRoughnessTextures) {
  std::string path;
  KDRAY_ASSIMP_MODEL(path, "ClearCoat-glTF/ClearCoatTest.gltf");
  Scene scene = import_scene(path, {});
  size_t normal_mapped = 0, metal_rough_textured = 0;
  for (const Material& material : scene.materials) {
    if (material.normal_texture >= 0) {
      ++normal_mapped;
      EXPECT_GT(scene.textures[material.normal_texture].width, 0u);
    }
    if (material.metal_rough_texture >= 0) {
      ++metal_rough_textured;
      EXPECT_EQ(scene.textures[material.metal_rough_texture].name, "RoughnessStripes.png");
    }
  }
  EXPECT_GE(normal_mapped, 5u);  // RibsNormal.png and PlasticWrap_normals.jpg
  EXPECT_EQ(metal_rough_textured, 1u);
}

class MaterialsFile : public test::TempDirTest<> {};

TEST_F(MaterialsFile, MaterialFieldsRoundTripInTheCurrentVersion) {
  Scene scene = test::make_quad_scene(true, true, true);
  Material& m = scene.materials.front();
  m.type = MaterialType::MetallicRoughness;
  m.metallic = 0.7f;
  m.alpha = 0.25f;
  m.alpha_mode = AlphaMode::Blend;
  m.alpha_cutoff = 0.3f;
  m.metal_rough_texture = 0;
  m.normal_texture = 0;
  m.emissive_texture = 0;
  scene.content_hash = compute_content_hash(scene);
  write_scene(path("current.kdscene"), scene);
  EXPECT_EQ(peek_scene(path("current.kdscene")).version, format::kSceneVersion);
  const Scene read = read_scene(path("current.kdscene"));
  const Material& r = read.materials.front();
  EXPECT_EQ(r.type, MaterialType::MetallicRoughness);
  EXPECT_EQ(r.metallic, 0.7f);
  EXPECT_EQ(r.alpha, 0.25f);
  EXPECT_EQ(r.alpha_mode, AlphaMode::Blend);
  EXPECT_EQ(r.alpha_cutoff, 0.3f);
  EXPECT_EQ(r.metal_rough_texture, 0);
  EXPECT_EQ(r.normal_texture, 0);
  EXPECT_EQ(r.emissive_texture, 0);
}

TEST_F(MaterialsFile, VersionTwoFilesReadWithOpaqueDefaults) {
  EXPECT_EQ(peek_scene(kVersion2File).version, 2u);
  Scene scene = read_scene(kVersion2File);
  const Material& masked = named(scene, "masked");
  EXPECT_EQ(masked.type, MaterialType::Dielectric);  // as version 2 mapped it
  EXPECT_EQ(masked.alpha_mode, AlphaMode::Opaque);
  EXPECT_EQ(masked.metallic, 0.0f);
  EXPECT_EQ(masked.normal_texture, -1);
}

TEST_F(MaterialsFile, VersionOneFilesStillRead) {
  // A version 1 file is a version 2 file without a lights section: patch the version field (the
  // header is outside the payload checksum) and read it back.
  std::filesystem::copy_file(kVersion2File, path("v1.kdscene"));
  {
    std::fstream file(path("v1.kdscene"), std::ios::in | std::ios::out | std::ios::binary);
    const uint32_t version = 1;
    file.seekp(offsetof(format::FileHeader, version));
    file.write(reinterpret_cast<const char*>(&version), sizeof version);
  }
  EXPECT_EQ(peek_scene(path("v1.kdscene")).version, 1u);
  EXPECT_EQ(read_scene(path("v1.kdscene")).materials.size(), 6u);
}

}  // namespace
}  // namespace kdray
