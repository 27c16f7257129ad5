// Importing small assets written by the tests: triangulation, drops, attributes, materials,
// textures, options and cameras.
#include <kdray/error.h>
#include <kdray/import.h>

#include "test_corpus.h"

#include <assimp/Exporter.hpp>
#include <assimp/scene.h>
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <fstream>

namespace kdray {
namespace {

double signed_area_z(const Scene& scene, size_t triangle) {
  const Vec3& a = scene.positions[scene.indices[3 * triangle]];
  const Vec3& b = scene.positions[scene.indices[3 * triangle + 1]];
  const Vec3& c = scene.positions[scene.indices[3 * triangle + 2]];
  return 0.5 * ((double(b.x) - a.x) * (double(c.y) - a.y) - (double(b.y) - a.y) * (double(c.x) - a.x));
}

class Import : public test::TempDirTest<> {
 protected:
  std::string write_file(const std::string& name, const std::string& text) const {
    const std::string path = (dir_ / name).string();
    std::ofstream(path, std::ios::binary) << text;
    return path;
  }

  static Scene import(const std::string& path, Importer importer = Importer::Auto) {
    ImportOptions options;
    options.importer = importer;
    return import_scene(path, options);
  }
};

// A "C" shape: 8 corners, two of them reflex; a 3x3 square with a 2x1 notch cut from its right side.
constexpr const char* kConcaveC =
    "v 0 0 0\nv 3 0 0\nv 3 1 0\nv 1 1 0\nv 1 2 0\nv 3 2 0\nv 3 3 0\nv 0 3 0\n"
    "f 1 2 3 4 5 6 7 8\n";
constexpr double kConcaveCArea = 9.0 - 2.0;  // the 3x3 square minus the 2x1 notch

TEST_F(Import, ConcavePolygonIsCoveredExactly) {
  for (Importer importer : {Importer::TinyObj, Importer::Assimp}) {
    const Scene scene = import(write_file("c.obj", kConcaveC), importer);
    ASSERT_EQ(scene.triangle_count(), 6u);
    double total = 0;
    for (size_t t = 0; t < scene.triangle_count(); ++t) {
      const double area = signed_area_z(scene, t);
      EXPECT_GT(area, 0) << "triangle " << t << " flipped or degenerate";
      total += area;
    }
    // A fan from corner 1 would cover the notch and overlap itself: its areas sum to more.
    EXPECT_NEAR(total, kConcaveCArea, 1e-6);
  }
}

TEST_F(Import, ConcavePolygonInATiltedPlaneFarFromTheOrigin) {
  // The same "C" in the plane x = y, around x = 14678 like issue-295's polygons.
  std::string text;
  const double corners[8][2] = {{0, 0}, {3, 0}, {3, 1}, {1, 1}, {1, 2}, {3, 2}, {3, 3}, {0, 3}};
  for (const auto& c : corners)
    text += "v " + std::to_string(14678 + c[0]) + " " + std::to_string(14678 + c[0]) + " " + std::to_string(9605 + c[1]) + "\n";
  text += "f 1 2 3 4 5 6 7 8\n";
  const Scene scene = import(write_file("tilted.obj", text));
  ASSERT_EQ(scene.triangle_count(), 6u);
  double total = 0;
  for (size_t t = 0; t < scene.triangle_count(); ++t) {
    const Vec3& a = scene.positions[scene.indices[3 * t]];
    const Vec3& b = scene.positions[scene.indices[3 * t + 1]];
    const Vec3& c = scene.positions[scene.indices[3 * t + 2]];
    const double ux = b.x - a.x, uy = b.y - a.y, uz = b.z - a.z, vx = c.x - a.x, vy = c.y - a.y, vz = c.z - a.z;
    const double nx = uy * vz - uz * vy, ny = uz * vx - ux * vz, nz = ux * vy - uy * vx;
    total += 0.5 * std::sqrt(nx * nx + ny * ny + nz * nz);
  }
  EXPECT_NEAR(total, kConcaveCArea * std::sqrt(2.0), 1e-2);
}

TEST_F(Import, ConvexQuadsBecomeTheFanAroundTheirFirstCorner) {
  const Scene scene = import(write_file("quad.obj", "v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\nf 1 2 3 4\n"));
  EXPECT_EQ(scene.indices, (std::vector<uint32_t>{0, 1, 2, 0, 2, 3}));
}

TEST_F(Import, DropsAndIgnoresAreCountedTheSameByBothImporters) {
  const std::string path = write_file("drops.obj",
                                      "v 0 0 0\nv 1 0 0\nv 0 1 0\nv nan 0 0\nv inf 1 1\nv 2 0 0\n"
                                      "f 1 2 3\n"   // kept
                                      "f 1 2 4\n"   // NaN corner
                                      "f 1 2 5\n"   // infinite corner
                                      "f 1 1 2\n"   // repeated index
                                      "f 1 2 6\n"   // collinear: zero area
                                      "p 1\nl 1 2\n");
  for (Importer importer : {Importer::TinyObj, Importer::Assimp}) {
    const Scene scene = import(path, importer);
    const ImportStats& stats = scene.import_stats;
    EXPECT_EQ(scene.triangle_count(), 1u);
    EXPECT_EQ(stats.source_triangles, 5u);
    EXPECT_EQ(stats.dropped_non_finite, 2u);
    EXPECT_EQ(stats.dropped_degenerate, 2u);
    EXPECT_EQ(stats.ignored_points, 1u);
    EXPECT_EQ(stats.ignored_lines, 1u);
    EXPECT_EQ(scene.positions.size(), 3u) << "vertices of dropped triangles are not kept";
  }
}

TEST_F(Import, NothingToKeepIsAnErrorThatSaysWhy) {
  const std::string path = write_file("lines.obj", "v 0 0 0\nv 1 0 0\nl 1 2\n");
  try {
    import(path);
    FAIL() << "expected kdray::Error";
  } catch (const Error& error) {
    EXPECT_NE(std::string(error.what()).find("no triangles to keep"), std::string::npos) << error.what();
    EXPECT_NE(std::string(error.what()).find("1 lines ignored"), std::string::npos) << error.what();
  }
}

TEST_F(Import, AttributesArePresentOnlyWhenTheSourceHasThem) {
  const Scene plain = import(write_file("plain.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n"));
  EXPECT_TRUE(plain.normals.empty());
  EXPECT_TRUE(plain.uvs.empty());
  const Scene full = import(write_file("full.obj",
                                       "v 0 0 0\nv 1 0 0\nv 0 1 0\nvt 0 0\nvt 1 0\nvt 0 1\nvn 0 0 1\n"
                                       "f 1/1/1 2/2/1 3/3/1\n"));
  ASSERT_EQ(full.normals.size(), 3u);
  ASSERT_EQ(full.uvs.size(), 3u);
  EXPECT_EQ(full.uvs[1].u, 1.0f);
}

TEST_F(Import, MissingNormalsAreFilledFromTheTrianglesAround) {
  // The second triangle has no normals; its lone vertex 4 gets its face normal (0, 0, 1).
  const Scene scene = import(write_file("partial.obj",
                                        "v 0 0 0\nv 1 0 0\nv 0 1 0\nv 1 1 0\nvn 0.6 0 0.8\n"
                                        "f 1//1 2//1 3//1\nf 2 4 3\n"));
  ASSERT_FALSE(scene.normals.empty());
  const Vec3& filled = scene.normals[scene.indices[4]];
  EXPECT_FLOAT_EQ(filled.x, 0);
  EXPECT_FLOAT_EQ(filled.y, 0);
  EXPECT_FLOAT_EQ(filled.z, 1);
  EXPECT_FLOAT_EQ(scene.normals[scene.indices[0]].x, 0.6f);
}

TEST_F(Import, MtlMaterialsMapOntoTheFiveTypes) {
  write_file("m.mtl",
             "newmtl wall\nKd 0.63 0.065 0.05\n"
             "newmtl light\nKd 0.78 0.78 0.78\nKe 17 12 4\n"
             "newmtl glass\nKd 1 1 1\nNi 1.33\nd 0.2\n"
             "newmtl chrome\nKd 0 0 0\nKs 0.9 0.9 0.9\nNs 2000\nillum 3\n"
             "newmtl brushed\nKd 0.05 0.05 0.05\nKs 0.8 0.6 0.2\nNs 50\n");
  std::string obj = "mtllib m.mtl\nv 0 0 0\nv 1 0 0\nv 0 1 0\n";
  for (const char* name : {"wall", "light", "glass", "chrome", "brushed"}) obj += std::string("usemtl ") + name + "\nf 1 2 3\n";
  const Scene scene = import(write_file("m.obj", obj));
  ASSERT_EQ(scene.materials.size(), 5u);
  EXPECT_EQ(scene.materials[0].type, MaterialType::Diffuse);
  EXPECT_FLOAT_EQ(scene.materials[0].base_color.y, 0.065f);
  EXPECT_EQ(scene.materials[1].type, MaterialType::Emissive);
  EXPECT_FLOAT_EQ(scene.materials[1].emission.x, 17);
  EXPECT_EQ(scene.materials[2].type, MaterialType::Dielectric);
  EXPECT_FLOAT_EQ(scene.materials[2].ior, 1.33f);
  EXPECT_EQ(scene.materials[3].type, MaterialType::Mirror);
  EXPECT_EQ(scene.materials[4].type, MaterialType::RoughConductor);
  EXPECT_NEAR(scene.materials[4].roughness, std::sqrt(2.0 / 52.0), 1e-6);
  EXPECT_FLOAT_EQ(scene.materials[4].base_color.z, 0.2f);
  EXPECT_EQ(scene.material_ids, (std::vector<uint32_t>{0, 1, 2, 3, 4}));
  EXPECT_EQ(scene.emissive_triangles, (std::vector<uint32_t>{1}));
}

TEST_F(Import, FacesWithoutAMaterialGetTheDefaultOne) {
  const Scene scene = import(write_file("bare.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n"));
  ASSERT_EQ(scene.materials.size(), 1u);
  EXPECT_EQ(scene.materials[0].name, "default");
  EXPECT_EQ(scene.materials[0].type, MaterialType::Diffuse);
}

TEST_F(Import, DiffuseTextureIsDecodedIntoTheScene) {
  write_file("checker.ppm", "P3\n2 1\n255\n255 0 0  0 128 255\n");
  write_file("t.mtl", "newmtl textured\nKd 1 1 1\nmap_Kd checker.ppm\n");
  const Scene scene = import(write_file("t.obj",
                                        "mtllib t.mtl\nv 0 0 0\nv 1 0 0\nv 0 1 0\nvt 0 0\nvt 1 0\nvt 0 1\n"
                                        "usemtl textured\nf 1/1 2/2 3/3\n"));
  ASSERT_EQ(scene.textures.size(), 1u);
  const Texture& texture = scene.textures[0];
  EXPECT_EQ(texture.name, "checker.ppm") << "named as the material wrote it, not by absolute path";
  ASSERT_EQ(texture.width, 2u);
  ASSERT_EQ(texture.height, 1u);
  EXPECT_EQ(texture.rgba, (std::vector<uint8_t>{255, 0, 0, 255, 0, 128, 255, 255}));
  EXPECT_EQ(scene.materials[0].diffuse_texture, 0);
  EXPECT_TRUE(scene.import_stats.warnings.empty());
}

// Assimp hands some formats' textures over as raw texels rather than image file bytes; written
// here as Assimp's own binary dump: two triangles whose two materials share one 2x2 texture.
TEST_F(Import, ARawEmbeddedTextureSharedByTwoMaterialsIsStoredOnce) {
  aiScene source;  // owns and frees everything below
  source.mRootNode = new aiNode();
  source.mNumMeshes = 2;
  source.mMeshes = new aiMesh*[2];
  for (unsigned m = 0; m < 2; ++m) {
    aiMesh* mesh = new aiMesh();
    mesh->mPrimitiveTypes = aiPrimitiveType_TRIANGLE;
    mesh->mNumVertices = 3;
    mesh->mVertices = new aiVector3D[3]{{float(m), 0, 0}, {float(m) + 1, 0, 0}, {float(m), 1, 0}};
    mesh->mTextureCoords[0] = new aiVector3D[3]{{0, 0, 0}, {1, 0, 0}, {0, 1, 0}};
    mesh->mNumUVComponents[0] = 2;
    mesh->mNumFaces = 1;
    mesh->mFaces = new aiFace[1];
    mesh->mFaces[0].mNumIndices = 3;
    mesh->mFaces[0].mIndices = new unsigned[3]{0, 1, 2};
    mesh->mMaterialIndex = m;
    source.mMeshes[m] = mesh;
  }
  source.mRootNode->mNumMeshes = 2;
  source.mRootNode->mMeshes = new unsigned[2]{0, 1};
  source.mNumMaterials = 2;
  source.mMaterials = new aiMaterial*[2];
  for (unsigned m = 0; m < 2; ++m) {
    source.mMaterials[m] = new aiMaterial();
    const aiString embedded("*0");
    source.mMaterials[m]->AddProperty(&embedded, AI_MATKEY_TEXTURE_DIFFUSE(0));
  }
  source.mNumTextures = 1;
  source.mTextures = new aiTexture*[1];
  source.mTextures[0] = new aiTexture();
  source.mTextures[0]->mWidth = 2;
  source.mTextures[0]->mHeight = 2;
  source.mTextures[0]->pcData = new aiTexel[4]{{10, 20, 30, 255}, {40, 50, 60, 255}, {70, 80, 90, 255}, {1, 2, 3, 4}};
  const std::string path = (dir_ / "raw-texels.assbin").string();
  ASSERT_EQ(Assimp::Exporter().Export(&source, "assbin", path), aiReturn_SUCCESS);

  const Scene scene = import(path);
  ASSERT_EQ(scene.textures.size(), 1u);
  ASSERT_EQ(scene.materials.size(), 2u);
  EXPECT_EQ(scene.materials[0].diffuse_texture, 0);
  EXPECT_EQ(scene.materials[1].diffuse_texture, 0);
  // aiTexel is stored BGRA; the scene's texels are RGBA.
  EXPECT_EQ(std::vector<uint8_t>(scene.textures[0].rgba.begin(), scene.textures[0].rgba.begin() + 4),
            (std::vector<uint8_t>{30, 20, 10, 255}));
}

TEST_F(Import, MissingTextureIsAWarningAndTheColourStays) {
  write_file("t.mtl", "newmtl textured\nKd 0.5 0.25 1\nmap_Kd absent.png\n");
  const Scene scene = import(write_file("t.obj", "mtllib t.mtl\nv 0 0 0\nv 1 0 0\nv 0 1 0\nusemtl textured\nf 1 2 3\n"));
  EXPECT_TRUE(scene.textures.empty());
  EXPECT_EQ(scene.materials[0].diffuse_texture, -1);
  EXPECT_FLOAT_EQ(scene.materials[0].base_color.y, 0.25f);
  ASSERT_EQ(scene.import_stats.warnings.size(), 1u);
  EXPECT_NE(scene.import_stats.warnings[0].find("absent.png"), std::string::npos);
}

TEST_F(Import, ScaleAndUpAxisMoveGeometryAndNormals) {
  const std::string path = write_file("z.obj", "v 0 0 0\nv 1 0 0\nv 0 0 1\nvn 0 0 1\nf 1//1 2//1 3//1\n");
  ImportOptions options;
  options.scale = 2;
  options.up_axis = UpAxis::Z;
  const Scene scene = import_scene(path, options);
  // (0, 0, 1) in a Z-up file is up: (0, 2, 0) after the rotation and the scale.
  const Vec3& top = scene.positions[scene.indices[2]];
  EXPECT_FLOAT_EQ(top.y, 2);
  EXPECT_FLOAT_EQ(top.z, 0);
  EXPECT_FLOAT_EQ(scene.normals[0].y, 1);
}

TEST_F(Import, DefaultCameraFramesTheBoundingBox) {
  const Scene scene = import(write_file("box.obj", "v -1 -1 -1\nv 1 -1 -1\nv 1 1 1\nf 1 2 3\n"));
  ASSERT_EQ(scene.cameras.size(), 1u);
  const Camera& camera = scene.cameras[0];
  EXPECT_EQ(camera.name, "default");
  EXPECT_FLOAT_EQ(camera.target.z, 0);
  EXPECT_FLOAT_EQ(camera.position.x, 0);
  // The bounding sphere (radius sqrt(3)) just fits the 45-degree vertical field of view.
  EXPECT_NEAR(camera.position.z, std::sqrt(3.0) / std::sin(22.5 * M_PI / 180), 1e-4);
}

TEST_F(Import, InstancedMeshesAreFlattenedWithTheirTransforms) {
  // One mesh used by two nodes, the second moved by +10 in x (Collada instance_geometry).
  const std::string dae = R"(<?xml version="1.0"?>
<COLLADA xmlns="http://www.collada.org/2005/11/COLLADASchema" version="1.4.1">
  <library_geometries><geometry id="tri"><mesh>
    <source id="p"><float_array id="pa" count="9">0 0 0 1 0 0 0 1 0</float_array>
      <technique_common><accessor source="#pa" count="3" stride="3">
        <param name="X" type="float"/><param name="Y" type="float"/><param name="Z" type="float"/>
      </accessor></technique_common></source>
    <vertices id="v"><input semantic="POSITION" source="#p"/></vertices>
    <triangles count="1"><input semantic="VERTEX" source="#v" offset="0"/><p>0 1 2</p></triangles>
  </mesh></geometry></library_geometries>
  <library_visual_scenes><visual_scene id="s">
    <node id="a"><instance_geometry url="#tri"/></node>
    <node id="b"><translate>10 0 0</translate><instance_geometry url="#tri"/></node>
  </visual_scene></library_visual_scenes>
  <scene><instance_visual_scene url="#s"/></scene>
</COLLADA>
)";
  const Scene scene = import(write_file("instances.dae", dae));
  ASSERT_EQ(scene.triangle_count(), 2u);
  const Bounds bounds = scene_bounds(scene);
  EXPECT_FLOAT_EQ(bounds.min.x, 0);
  EXPECT_FLOAT_EQ(bounds.max.x, 11);
}

// Path of a file from Debian's assimp-testmodels; missing fails under CI, skips elsewhere.
#define KDRAY_ASSIMP_MODEL(var, relative)                                                          \
  do {                                                                                             \
    var = std::string(KDRAY_ASSIMP_MODELS_DIR "/") + (relative);                                   \
    if (!std::filesystem::exists(var)) {                                                           \
      if (test::running_in_ci()) FAIL() << "assimp-testmodels missing in CI: " << var;             \
      GTEST_SKIP() << "assimp-testmodels not installed";                                           \
    }                                                                                              \
  } while (0)

TEST_F(Import, EmbeddedTexturesAreDecoded) {
  std::string glb, fbx;
  KDRAY_ASSIMP_MODEL(glb, "glTF2/BoxTextured-glTF-Binary/BoxTextured.glb");  // PNG inside the GLB
  KDRAY_ASSIMP_MODEL(fbx, "FBX/box_orphant_embedded_texture.fbx");          // TGA inside the FBX
  for (const std::string& path : {glb, fbx}) {
    const Scene scene = import(path);
    ASSERT_EQ(scene.textures.size(), 1u) << path;
    EXPECT_GT(scene.textures[0].width, 0u);
    EXPECT_EQ(scene.textures[0].rgba.size(), size_t(scene.textures[0].width) * scene.textures[0].height * 4);
    EXPECT_TRUE(scene.import_stats.warnings.empty()) << scene.import_stats.warnings[0];
  }
}

TEST_F(Import, AssetCamerasComeWithTheirNodeTransforms) {
  std::string path;
  KDRAY_ASSIMP_MODEL(path, "glTF2/cameras/Cameras.gltf");
  const Scene scene = import(path);
  ASSERT_EQ(scene.cameras.size(), 2u);
  EXPECT_EQ(scene.cameras[0].name, "nodes[1]");
  // The node translation (0.5, 0.5, 3), once: Assimp also copies it into mPosition.
  EXPECT_FLOAT_EQ(scene.cameras[0].position.x, 0.5f);
  EXPECT_FLOAT_EQ(scene.cameras[0].position.z, 3);
  EXPECT_NEAR(scene.cameras[0].vertical_fov_degrees, 0.7 * 180 / M_PI, 1e-3);  // glTF yfov 0.7

  ImportOptions by_index;
  by_index.camera = "1";
  EXPECT_EQ(import_scene(path, by_index).cameras[0].name, "nodes[2]");
  ImportOptions unknown;
  unknown.camera = "nowhere";
  EXPECT_THROW(import_scene(path, unknown), Error);
}

}  // namespace
}  // namespace kdray
