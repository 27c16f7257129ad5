// Per-vertex tangents for normal maps: computed ones point along +u and are perpendicular to the
// normal, mirrored UVs get handedness -1 (and their shared vertices are split), tangents the
// asset authored (a glTF TANGENT accessor) are kept, OBJ `norm` maps get computed ones, scenes
// without a normal map store none, and version 4 files still read (with tangents computed).
#include "scene_test_util.h"

#include <kdray/error.h>
#include <kdray/format.h>
#include <kdray/import.h>
#include <kdray/scene_file.h>
#include <kdray/tangents.h>

#include <test_corpus.h>

#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <fstream>

namespace kdray {
namespace {

const std::string kTangentsGltf = std::string(KDRAY_SOURCE_DIR) + "/tests/scene/tangents-gltf.gltf";
// Written by the version 4 kdconvert from tangents-gltf.gltf: a normal-mapped scene without tangents.
const std::string kVersion4File = std::string(KDRAY_SOURCE_DIR) + "/tests/scene/fixtures/version-4-normal-map.kdscene";

float dot(const Tangent& t, const Vec3& v) { return t.x * v.x + t.y * v.y + t.z * v.z; }

Material normal_mapped() {
  Material material;
  material.name = "bumpy";
  material.normal_texture = 0;
  return material;
}

// A scene of the given mesh whose one material has a normal map.
Scene normal_mapped_scene(std::vector<Vec3> positions, std::vector<Vec2> uvs, std::vector<uint32_t> indices) {
  Scene scene;
  scene.positions = std::move(positions);
  scene.uvs = std::move(uvs);
  scene.indices = std::move(indices);
  scene.material_ids.assign(scene.triangle_count(), 0);
  scene.normals.assign(scene.positions.size(), Vec3{0, 0, 1});
  scene.materials = {normal_mapped()};
  scene.textures.push_back({"flat.png", 1, 1, {128, 128, 255, 255}});
  return scene;
}

TEST(Tangents, QuadTangentsPointAlongU) {
  // UVs turned a quarter: +u runs along +y and +v along -x, a right-handed frame with n = +z.
  Scene scene = normal_mapped_scene({{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0}}, {{0, 1}, {0, 0}, {1, 0}, {1, 1}},
                                    {0, 1, 2, 0, 2, 3});
  complete_tangents(scene);
  ASSERT_EQ(scene.tangents.size(), 4u);
  for (const Tangent& t : scene.tangents) {
    EXPECT_NEAR(t.x, 0, 1e-6);
    EXPECT_NEAR(t.y, 1, 1e-6);
    EXPECT_NEAR(t.z, 0, 1e-6);
    EXPECT_EQ(t.w, 1.0f);
  }
}

TEST(Tangents, SphereTangentsPointAlongUAndArePerpendicularToTheNormal) {
  // A latitude-longitude sphere, u = longitude / 2 pi, v up from the south pole, with a seam of
  // duplicated vertices at u = 0 / 1 as exporters write it.
  constexpr int kRings = 16, kSegments = 32;
  std::vector<Vec3> positions;
  std::vector<Vec2> uvs;
  for (int i = 0; i <= kRings; ++i)
    for (int j = 0; j <= kSegments; ++j) {
      const double theta = M_PI * i / kRings, phi = 2 * M_PI * j / kSegments;
      positions.push_back({float(std::sin(theta) * std::cos(phi)), float(-std::cos(theta)),
                           float(-std::sin(theta) * std::sin(phi))});
      uvs.push_back({float(j) / kSegments, float(i) / kRings});
    }
  std::vector<uint32_t> indices;
  for (int i = 0; i < kRings; ++i)
    for (int j = 0; j < kSegments; ++j) {
      const uint32_t a = i * (kSegments + 1) + j, b = a + 1, c = a + kSegments + 1, d = c + 1;
      if (i > 0) indices.insert(indices.end(), {a, b, d});
      if (i < kRings - 1) indices.insert(indices.end(), {a, d, c});
    }
  Scene scene = normal_mapped_scene(positions, uvs, indices);
  scene.normals = positions;  // a unit sphere
  complete_tangents(scene);
  ASSERT_EQ(scene.tangents.size(), positions.size());  // no mirrored triangles: nothing split
  for (int i = 1; i < kRings; ++i)  // the poles' tangents have no direction of +u to follow
    for (int j = 0; j <= kSegments; ++j) {
      const size_t v = i * (kSegments + 1) + j;
      const double phi = 2 * M_PI * j / kSegments;
      const Vec3 along_u{float(-std::sin(phi)), 0, float(-std::cos(phi))};  // d position / d phi, unit
      const Tangent& t = scene.tangents[v];
      EXPECT_NEAR(t.x * t.x + t.y * t.y + t.z * t.z, 1, 1e-5);
      EXPECT_NEAR(dot(t, scene.normals[v]), 0, 1e-5) << "vertex " << v;
      // Vertices on the seam see triangles on one side only: their tangent follows the chord of
      // half a segment, cos(pi / kSegments) from the true one.
      EXPECT_GT(dot(t, along_u), (j == 0 || j == kSegments) ? std::cos(M_PI / kSegments) - 1e-4 : 0.9999)
          << "vertex " << v;
      EXPECT_EQ(t.w, 1.0f) << "vertex " << v;
    }
}

TEST(Tangents, MirroredUvsGetNegativeHandednessAndSplitTheSharedVertices) {
  // Two quads side by side; the right one's u runs back from 1 to 0 (a mirrored half), and
  // the two share the middle column of vertices, whose UVs agree.
  Scene scene = normal_mapped_scene({{0, 0, 0}, {1, 0, 0}, {2, 0, 0}, {0, 1, 0}, {1, 1, 0}, {2, 1, 0}},
                                    {{0, 0}, {1, 0}, {0, 0}, {0, 1}, {1, 1}, {0, 1}},
                                    {0, 1, 4, 0, 4, 3, 1, 2, 5, 1, 5, 4});
  complete_tangents(scene);
  ASSERT_EQ(scene.positions.size(), 8u);  // the two middle vertices, once for each half
  ASSERT_EQ(scene.tangents.size(), 8u);
  ASSERT_EQ(scene.normals.size(), 8u);
  ASSERT_EQ(scene.uvs.size(), 8u);
  for (size_t t = 0; t < scene.triangle_count(); ++t) {
    const bool mirrored = t >= 2;
    for (int corner = 0; corner < 3; ++corner) {
      const Tangent& tangent = scene.tangents[scene.indices[3 * t + corner]];
      EXPECT_EQ(tangent.w, mirrored ? -1.0f : 1.0f) << "triangle " << t;
      EXPECT_NEAR(tangent.x, mirrored ? -1.0f : 1.0f, 1e-6) << "triangle " << t;  // +u
      // w * cross(n, t) is +v, which is +y on both halves.
      EXPECT_NEAR(tangent.w * tangent.x, 1.0f, 1e-6);
    }
  }
  // The split leaves the geometry as it was: same corner positions.
  EXPECT_EQ(scene.positions[scene.indices[6]].x, 1.0f);
}

TEST(Tangents, DegenerateUvsGiveAPerpendicularTangent) {
  // Every corner has the same UV: no direction of +u anywhere.
  Scene scene = normal_mapped_scene({{0, 0, 0}, {1, 0, 0}, {0, 1, 0}}, {{0.5f, 0.5f}, {0.5f, 0.5f}, {0.5f, 0.5f}},
                                    {0, 1, 2});
  complete_tangents(scene);
  ASSERT_EQ(scene.tangents.size(), 3u);
  for (const Tangent& t : scene.tangents) {
    EXPECT_NEAR(t.x * t.x + t.y * t.y + t.z * t.z, 1, 1e-6);
    EXPECT_NEAR(t.z, 0, 1e-6);  // perpendicular to n = +z
    EXPECT_TRUE(t.w == 1 || t.w == -1);
  }
}

TEST(Tangents, ScenesWithoutANormalMapHaveNone) {
  Scene scene = test::make_quad_scene(true, true, true);
  scene.tangents.assign(4, Tangent{1, 0, 0, 1});
  complete_tangents(scene);
  EXPECT_TRUE(scene.tangents.empty());
}

TEST(Tangents, AuthoredGltfTangentsAreKeptAndMissingOnesComputed) {
  // Node "authored" (x in [0, 1]) carries TANGENT (0, 1, 0, -1), deliberately not the direction
  // of +u; node "computed" (x in [2, 3]) has none.
  const Scene scene = import_scene(kTangentsGltf, {});
  ASSERT_EQ(scene.tangents.size(), scene.positions.size());
  ASSERT_EQ(scene.positions.size(), 8u);
  for (size_t v = 0; v < scene.positions.size(); ++v) {
    const Tangent& t = scene.tangents[v];
    if (scene.positions[v].x <= 1) {
      EXPECT_NEAR(t.y, 1, 1e-6) << "vertex " << v;
      EXPECT_EQ(t.w, -1.0f) << "vertex " << v;
    } else {
      EXPECT_NEAR(t.x, 1, 1e-6) << "vertex " << v;
      EXPECT_EQ(t.w, 1.0f) << "vertex " << v;
    }
  }
}

TEST(Tangents, UpAxisRotationTurnsAuthoredTangents) {
  ImportOptions options;
  options.up_axis = UpAxis::Z;
  const Scene scene = import_scene(kTangentsGltf, options);
  for (size_t v = 0; v < scene.positions.size(); ++v)
    if (scene.positions[v].x <= 1) {
      EXPECT_NEAR(scene.tangents[v].z, -1, 1e-6);  // (0, 1, 0) -> (0, 0, -1)
      EXPECT_EQ(scene.tangents[v].w, -1.0f);
    }
}

class TangentFiles : public test::TempDirTest<> {};

TEST_F(TangentFiles, TangentsRoundTripAndEnterTheContentHash) {
  const Scene scene = import_scene(kTangentsGltf, {});
  write_scene(path("t.kdscene"), scene);
  EXPECT_TRUE(peek_scene(path("t.kdscene")).flags & format::kSceneHasTangents);
  const Scene read = read_scene(path("t.kdscene"));
  ASSERT_EQ(read.tangents.size(), scene.tangents.size());
  for (size_t v = 0; v < read.tangents.size(); ++v) {
    EXPECT_EQ(read.tangents[v].y, scene.tangents[v].y);
    EXPECT_EQ(read.tangents[v].w, scene.tangents[v].w);
  }
  Scene flipped = read;
  flipped.tangents[0].w = -flipped.tangents[0].w;
  EXPECT_NE(compute_content_hash(flipped), read.content_hash);
}

TEST_F(TangentFiles, ScenesWithoutANormalMapWriteNoTangentSection) {
  const Scene scene = test::make_quad_scene(true, true, true);
  write_scene(path("plain.kdscene"), scene);
  EXPECT_FALSE(peek_scene(path("plain.kdscene")).flags & format::kSceneHasTangents);
  EXPECT_TRUE(read_scene(path("plain.kdscene")).tangents.empty());
}

TEST_F(TangentFiles, TangentsWithoutHandednessAreRefused) {
  Scene scene = import_scene(kTangentsGltf, {});
  scene.tangents[3].w = 0;
  EXPECT_THROW(write_scene(path("bad.kdscene"), scene), Error);
}

TEST_F(TangentFiles, VersionFourNormalMappedFilesReadWithComputedTangents) {
  EXPECT_EQ(peek_scene(kVersion4File).version, 4u);
  const Scene scene = read_scene(kVersion4File);
  ASSERT_EQ(scene.positions.size(), 8u);  // computed on the file's own vertices
  ASSERT_EQ(scene.tangents.size(), 8u);
  for (const Tangent& t : scene.tangents) {  // version 4 dropped the authored ones: all along +u
    EXPECT_NEAR(t.x, 1, 1e-6);
    EXPECT_EQ(t.w, 1.0f);
  }
}

TEST_F(TangentFiles, ObjNormalMapsGetComputedTangents) {
  // A 1x1 PNG of the flat normal (128, 128, 255).
  const unsigned char png[] = {
      0x89, 0x50, 0x4e, 0x47, 0x0d, 0x0a, 0x1a, 0x0a, 0x00, 0x00, 0x00, 0x0d, 0x49, 0x48, 0x44, 0x52, 0x00, 0x00,
      0x00, 0x01, 0x00, 0x00, 0x00, 0x01, 0x08, 0x02, 0x00, 0x00, 0x00, 0x90, 0x77, 0x53, 0xde, 0x00, 0x00, 0x00,
      0x0c, 0x49, 0x44, 0x41, 0x54, 0x78, 0xda, 0x63, 0x68, 0x68, 0xf8, 0x0f, 0x00, 0x03, 0x83, 0x02, 0x00, 0x3e,
      0x58, 0x28, 0x25, 0x00, 0x00, 0x00, 0x00, 0x49, 0x45, 0x4e, 0x44, 0xae, 0x42, 0x60, 0x82};
  std::ofstream(path("flat.png"), std::ios::binary).write(reinterpret_cast<const char*>(png), sizeof png);
  std::ofstream(path("quad.mtl")) << "newmtl bumpy\nKd 0.5 0.5 0.5\nnorm flat.png\n";
  std::ofstream(path("quad.obj")) << "mtllib quad.mtl\nv 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\n"
                                     "vt 0 1\nvt 0 0\nvt 1 0\nvt 1 1\nusemtl bumpy\nf 1/1 2/2 3/3 4/4\n";
  const Scene scene = import_scene(path("quad.obj"), {});
  ASSERT_EQ(scene.materials.front().normal_texture, 0);
  ASSERT_EQ(scene.tangents.size(), 4u);
  for (const Tangent& t : scene.tangents) {  // +u runs along +y here, +v along -x
    EXPECT_NEAR(t.y, 1, 1e-6);
    EXPECT_EQ(t.w, 1.0f);
  }
}

}  // namespace
}  // namespace kdray
