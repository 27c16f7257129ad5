// Every mesh of the shared corpus converts with the triangle count SOURCES.md states, and the
// OBJ files give the same triangles through tinyobjloader and through Assimp.
#include <kdray/import.h>
#include <kdray/scene_file.h>

#include "test_corpus.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cctype>
#include <cmath>
#include <fstream>
#include <map>
#include <iterator>

namespace kdray {
namespace {

struct CorpusMesh {
  std::string path;  // relative to the corpus
  uint64_t triangles;
};

// Rows "| `file.obj` | 1,234 | ..." of the mesh tables in SOURCES.md and large/README.md.
std::vector<CorpusMesh> meshes_listed_in(const std::string& document, const std::string& prefix) {
  std::vector<CorpusMesh> meshes;
  std::ifstream file(std::string(KDRAY_CORPUS_DIR) + "/" + document);
  std::string line;
  while (std::getline(file, line)) {
    if (line.rfind("| `", 0) != 0) continue;
    const size_t name_end = line.find('`', 3);
    if (name_end == std::string::npos || line.compare(name_end, 4, "` | ") != 0) continue;
    const std::string name = line.substr(3, name_end - 3);
    const std::string extension = name.size() > 4 ? name.substr(name.size() - 4) : "";
    if (extension != ".obj" && extension != ".ply") continue;
    std::string digits;
    size_t at = name_end + 4;
    for (; at < line.size() && (std::isdigit(static_cast<unsigned char>(line[at])) || line[at] == ','); ++at)
      if (line[at] != ',') digits += line[at];
    if (digits.empty() || line.compare(at, 2, " |") != 0) continue;  // a size column, not a count
    meshes.push_back({prefix + name, std::stoull(digits)});
  }
  return meshes;
}

std::vector<CorpusMesh> regular_meshes() { return meshes_listed_in("SOURCES.md", ""); }
std::vector<CorpusMesh> large_meshes() { return meshes_listed_in("large/README.md", "large/"); }

std::string test_name(const ::testing::TestParamInfo<CorpusMesh>& info) {
  std::string name = info.param.path;
  std::replace_if(name.begin(), name.end(), [](char c) { return !std::isalnum(static_cast<unsigned char>(c)); }, '_');
  return name;
}

void expect_converts_with_listed_count(const CorpusMesh& mesh) {
  std::string path;
  KDRAY_CORPUS_FILE(path, mesh.path);
  const Scene scene = import_scene(path, {});
  // The corpus meshes have nothing to drop: the documented drops are all zero here.
  EXPECT_EQ(scene.triangle_count(), mesh.triangles);
  EXPECT_EQ(scene.import_stats.source_triangles, mesh.triangles);
  EXPECT_EQ(scene.import_stats.dropped_degenerate, 0u);
  EXPECT_EQ(scene.import_stats.dropped_non_finite, 0u);
  EXPECT_FALSE(scene.cameras.empty());
}

TEST(CorpusListing, SourcesListTheMeshes) {
  if (!test::running_in_ci() && regular_meshes().empty()) GTEST_SKIP() << "corpus not available";
  EXPECT_GE(regular_meshes().size(), 19u);
  EXPECT_EQ(large_meshes().size(), 2u);
}

class CorpusMeshes : public ::testing::TestWithParam<CorpusMesh> {};

TEST_P(CorpusMeshes, ConvertsWithTheListedTriangleCount) { expect_converts_with_listed_count(GetParam()); }

INSTANTIATE_TEST_SUITE_P(Sources, CorpusMeshes, ::testing::ValuesIn(regular_meshes()), test_name);
GTEST_ALLOW_UNINSTANTIATED_PARAMETERIZED_TEST(CorpusMeshes);

// The 1M+ triangle meshes, converted once each.
class LargeCorpusMeshes : public ::testing::TestWithParam<CorpusMesh> {};

TEST_P(LargeCorpusMeshes, ConvertsWithTheListedTriangleCount) {
  expect_converts_with_listed_count(GetParam());
}

INSTANTIATE_TEST_SUITE_P(Large, LargeCorpusMeshes, ::testing::ValuesIn(large_meshes()), test_name);
GTEST_ALLOW_UNINSTANTIATED_PARAMETERIZED_TEST(LargeCorpusMeshes);

// Positions of one scene, numbered by exact value, with a grid to find the one near a point
// of another scene: the two parsers may round the same text an ulp apart.
class PositionIndex {
 public:
  PositionIndex(const Scene& scene, double tolerance) : tolerance_(tolerance) {
    for (const Vec3& p : scene.positions) {
      const auto [slot, inserted] = id_of_.try_emplace(key(p), int64_t(id_of_.size()));
      if (inserted) grid_[cell(p)].push_back({p, slot->second});
    }
  }

  int64_t exact(const Vec3& p) const { return id_of_.at(key(p)); }

  // The id of a position within the tolerance of p, or -1.
  int64_t near(const Vec3& p) const {
    const auto [cx, cy, cz] = cell(p);
    for (int64_t dx = -1; dx <= 1; ++dx)
      for (int64_t dy = -1; dy <= 1; ++dy)
        for (int64_t dz = -1; dz <= 1; ++dz) {
          auto found = grid_.find({cx + dx, cy + dy, cz + dz});
          if (found == grid_.end()) continue;
          for (const auto& [q, id] : found->second)
            if (std::fabs(p.x - q.x) <= tolerance_ && std::fabs(p.y - q.y) <= tolerance_ &&
                std::fabs(p.z - q.z) <= tolerance_)
              return id;
        }
    return -1;
  }

 private:
  using Cell = std::array<int64_t, 3>;
  static std::array<float, 3> key(const Vec3& p) { return {p.x, p.y, p.z}; }
  Cell cell(const Vec3& p) const {
    return {int64_t(std::floor(p.x / tolerance_)), int64_t(std::floor(p.y / tolerance_)), int64_t(std::floor(p.z / tolerance_))};
  }

  double tolerance_;
  std::map<std::array<float, 3>, int64_t> id_of_;
  std::map<Cell, std::vector<std::pair<Vec3, int64_t>>> grid_;
};

// A triangle as three position ids, rotated so the smallest comes first (winding kept).
using Triangle = std::array<int64_t, 3>;

template <typename IdOf>
std::vector<Triangle> canonical_triangles(const Scene& scene, IdOf id_of) {
  std::vector<Triangle> triangles(scene.triangle_count());
  for (size_t t = 0; t < triangles.size(); ++t) {
    for (int c = 0; c < 3; ++c) triangles[t][c] = id_of(scene.positions[scene.indices[3 * t + c]]);
    std::rotate(triangles[t].begin(), std::min_element(triangles[t].begin(), triangles[t].end()), triangles[t].end());
  }
  std::sort(triangles.begin(), triangles.end());
  return triangles;
}

// Triangles of `a` missing from `b` (multiset difference of sorted lists).
std::vector<Triangle> missing_from(const std::vector<Triangle>& a, const std::vector<Triangle>& b) {
  std::vector<Triangle> missing;
  std::set_difference(a.begin(), a.end(), b.begin(), b.end(), std::back_inserter(missing));
  return missing;
}

std::vector<int64_t> corners_of(const std::vector<Triangle>& triangles) {
  std::vector<int64_t> corners;
  for (const Triangle& triangle : triangles) corners.insert(corners.end(), triangle.begin(), triangle.end());
  std::sort(corners.begin(), corners.end());
  corners.erase(std::unique(corners.begin(), corners.end()), corners.end());
  return corners;
}

class CorpusObjFiles : public ::testing::TestWithParam<CorpusMesh> {};

// Equal up to the choice of diagonal in a non-planar quad, where the two triangulations are
// equally valid: triangles that differ must use the same corners on both sides (suzanne.obj
// has two such nearly flat, slightly concave quads).
TEST_P(CorpusObjFiles, TinyObjAndAssimpGiveTheSameTriangles) {
  std::string path;
  KDRAY_CORPUS_FILE(path, GetParam().path);
  ImportOptions tinyobj, assimp;
  tinyobj.importer = Importer::TinyObj;
  assimp.importer = Importer::Assimp;
  const Scene a = import_scene(path, tinyobj), b = import_scene(path, assimp);
  ASSERT_EQ(a.triangle_count(), b.triangle_count());
  const Bounds bounds = scene_bounds(a);
  const double diagonal = std::hypot(bounds.max.x - bounds.min.x, bounds.max.y - bounds.min.y, bounds.max.z - bounds.min.z);
  const PositionIndex positions(a, diagonal * 1e-6);
  const std::vector<Triangle> ta = canonical_triangles(a, [&](const Vec3& p) { return positions.exact(p); });
  const std::vector<Triangle> tb = canonical_triangles(b, [&](const Vec3& p) { return positions.near(p); });
  const std::vector<Triangle> only_a = missing_from(ta, tb), only_b = missing_from(tb, ta);
  EXPECT_EQ(only_a.size(), only_b.size());
  EXPECT_LE(only_a.size(), ta.size() / 100) << "more than 1% of the triangles differ";
  EXPECT_EQ(corners_of(only_a), corners_of(only_b)) << "differing triangles use different corners";
}

std::vector<CorpusMesh> obj_meshes() {
  std::vector<CorpusMesh> objs;
  for (const CorpusMesh& mesh : regular_meshes())
    if (mesh.path.size() > 4 && mesh.path.compare(mesh.path.size() - 4, 4, ".obj") == 0) objs.push_back(mesh);
  return objs;
}

INSTANTIATE_TEST_SUITE_P(Sources, CorpusObjFiles, ::testing::ValuesIn(obj_meshes()), test_name);
GTEST_ALLOW_UNINSTANTIATED_PARAMETERIZED_TEST(CorpusObjFiles);

}  // namespace
}  // namespace kdray
