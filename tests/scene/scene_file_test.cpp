// Writing and reading .kdscene files: round trips and the header-level summary.
#include <kdray/container_file.h>
#include <kdray/error.h>
#include <kdray/scene_file.h>

#include "scene_test_util.h"
#include "test_corpus.h"

#include <gtest/gtest.h>

#include <cstring>
#include <filesystem>
#include <tuple>

namespace kdray {
namespace {

// Bit-exact comparison: a round trip must not change a single bit.
template <typename T>
bool same_bytes(const T& a, const T& b) {
  return std::memcmp(&a, &b, sizeof a) == 0;
}
template <typename T>
bool same_bytes(const std::vector<T>& a, const std::vector<T>& b) {
  return a.size() == b.size() && (a.empty() || std::memcmp(a.data(), b.data(), a.size() * sizeof(T)) == 0);
}

void expect_equal_scenes(const Scene& a, const Scene& b) {
  EXPECT_TRUE(same_bytes(a.positions, b.positions));
  EXPECT_EQ(a.indices, b.indices);
  EXPECT_EQ(a.material_ids, b.material_ids);
  EXPECT_TRUE(same_bytes(a.normals, b.normals));
  EXPECT_TRUE(same_bytes(a.uvs, b.uvs));
  EXPECT_EQ(a.emissive_triangles, b.emissive_triangles);
  ASSERT_EQ(a.materials.size(), b.materials.size());
  for (size_t i = 0; i < a.materials.size(); ++i) {
    const Material &x = a.materials[i], &y = b.materials[i];
    EXPECT_EQ(x.name, y.name);
    EXPECT_EQ(x.type, y.type);
    EXPECT_TRUE(same_bytes(x.base_color, y.base_color));
    EXPECT_TRUE(same_bytes(x.emission, y.emission));
    EXPECT_EQ(x.roughness, y.roughness);
    EXPECT_EQ(x.ior, y.ior);
    EXPECT_EQ(x.diffuse_texture, y.diffuse_texture);
  }
  ASSERT_EQ(a.textures.size(), b.textures.size());
  for (size_t i = 0; i < a.textures.size(); ++i) {
    EXPECT_EQ(a.textures[i].name, b.textures[i].name);
    EXPECT_EQ(a.textures[i].width, b.textures[i].width);
    EXPECT_EQ(a.textures[i].height, b.textures[i].height);
    EXPECT_EQ(a.textures[i].rgba, b.textures[i].rgba);
  }
  ASSERT_EQ(a.cameras.size(), b.cameras.size());
  for (size_t i = 0; i < a.cameras.size(); ++i) {
    EXPECT_EQ(a.cameras[i].name, b.cameras[i].name);
    EXPECT_TRUE(same_bytes(a.cameras[i].position, b.cameras[i].position));
    EXPECT_TRUE(same_bytes(a.cameras[i].target, b.cameras[i].target));
    EXPECT_TRUE(same_bytes(a.cameras[i].up, b.cameras[i].up));
    EXPECT_EQ(a.cameras[i].vertical_fov_degrees, b.cameras[i].vertical_fov_degrees);
    EXPECT_EQ(a.cameras[i].aspect_ratio, b.cameras[i].aspect_ratio);
    EXPECT_EQ(a.cameras[i].projection, b.cameras[i].projection);
    EXPECT_EQ(a.cameras[i].orthographic_half_height, b.cameras[i].orthographic_half_height);
  }
  EXPECT_EQ(a.import_stats.source_file, b.import_stats.source_file);
  EXPECT_EQ(a.import_stats.importer, b.import_stats.importer);
  EXPECT_EQ(a.import_stats.source_triangles, b.import_stats.source_triangles);
  EXPECT_EQ(a.import_stats.dropped_degenerate, b.import_stats.dropped_degenerate);
  EXPECT_EQ(a.import_stats.warnings, b.import_stats.warnings);
  EXPECT_EQ(a.content_hash, b.content_hash);
}

class SceneFile : public test::TempDirTest<::testing::TestWithParam<std::tuple<bool, bool, bool>>> {};

TEST_P(SceneFile, RoundTripKeepsEverything) {
  const auto [normals, uvs, texture] = GetParam();
  const Scene original = test::make_quad_scene(normals, uvs, texture);
  write_scene(path("quad.kdscene"), original);
  const Scene loaded = read_scene(path("quad.kdscene"));
  expect_equal_scenes(original, loaded);
  EXPECT_EQ(compute_content_hash(loaded), loaded.content_hash);
}

INSTANTIATE_TEST_SUITE_P(Attributes, SceneFile,
                         ::testing::Combine(::testing::Bool(), ::testing::Bool(), ::testing::Bool()));

TEST_F(SceneFile, PeekReportsFlagsAndHashWithoutLoading) {
  const Scene original = test::make_quad_scene(true, false, true);
  write_scene(path("quad.kdscene"), original);
  const SceneFileSummary summary = peek_scene(path("quad.kdscene"));
  EXPECT_EQ(summary.version, format::kSceneVersion);
  EXPECT_EQ(summary.flags, format::kSceneHasNormals | format::kSceneHasTextures | format::kSceneHasEmissive);
  EXPECT_EQ(summary.content_hash, original.content_hash);
  EXPECT_EQ(summary.file_size, std::filesystem::file_size(path("quad.kdscene")));
}

TEST_F(SceneFile, GeometryIsWhatTheWholeSceneHas) {
  const Scene original = test::make_quad_scene(true, true, true);
  write_scene(path("quad.kdscene"), original);
  const SceneGeometry geometry = read_scene_geometry(path("quad.kdscene"));
  EXPECT_EQ(geometry.geometry_hash, read_scene(path("quad.kdscene")).geometry_hash);
  EXPECT_EQ(geometry.geometry_hash, compute_geometry_hash(original));
  EXPECT_EQ(geometry.triangles, original.triangle_count());
  // Files older than version 4 record no geometry hash: it is computed from their arrays.
  for (const char* fixture : {"version-2-materials.kdscene", "version-4-normal-map.kdscene"}) {
    const std::string old_file = std::string(KDRAY_SOURCE_DIR) + "/tests/scene/fixtures/" + fixture;
    SCOPED_TRACE(old_file);
    const Scene whole = read_scene(old_file);
    const SceneGeometry old_geometry = read_scene_geometry(old_file);
    EXPECT_EQ(old_geometry.geometry_hash, whole.geometry_hash);
    EXPECT_EQ(old_geometry.triangles, whole.triangle_count());
  }
}

TEST_F(SceneFile, ContentHashChangesWithGeometryMaterialsAndCameras) {
  const Scene original = test::make_quad_scene(false, false, false);
  Scene moved = original;
  moved.positions[2].x = 1.5f;
  Scene recoloured = original;
  recoloured.materials[0].base_color.y = 0.1f;
  Scene reframed = original;
  reframed.cameras[0].vertical_fov_degrees = 30;
  Scene restated = original;
  restated.import_stats.source_file = "elsewhere.obj";
  EXPECT_NE(compute_content_hash(moved), original.content_hash);
  EXPECT_NE(compute_content_hash(recoloured), original.content_hash);
  EXPECT_NE(compute_content_hash(reframed), original.content_hash);
  EXPECT_EQ(compute_content_hash(restated), original.content_hash);
}

TEST_F(SceneFile, RefusesToWriteAnInconsistentScene) {
  Scene broken = test::make_quad_scene(false, false, false);
  broken.indices[4] = 9;
  EXPECT_THROW(write_scene(path("broken.kdscene"), broken), Error);
  EXPECT_FALSE(std::filesystem::exists(path("broken.kdscene")));
  EXPECT_TRUE(std::filesystem::is_empty(dir_)) << "no temporary file may be left behind";
}

TEST_F(SceneFile, MissingFileIsAnErrorNamingIt) {
  try {
    read_scene(path("absent.kdscene"));
    FAIL() << "expected kdray::Error";
  } catch (const Error& error) {
    EXPECT_NE(std::string(error.what()).find("absent.kdscene"), std::string::npos) << error.what();
  }
}

}  // namespace
}  // namespace kdray
