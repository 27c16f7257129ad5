// Normal maps in the kernel use the scene's per-vertex tangents: a flat floor under a directional
// light has the radiance its mapped normal gives in the authored tangent frame (a known answer),
// and a floor whose two triangles have different UV derivatives shows no step along their shared
// edge, where a frame built per triangle from its own dp/du would.
#include "render_fixture.h"
#include "test_scenes.h"

#include <kdray/render.h>
#include <kdray/tangents.h>

#include <gtest/gtest.h>

#include <cmath>

namespace kdray {
namespace {

constexpr float kAlbedo = 0.5f;
constexpr double kPi = 3.14159265358979323846;
// The normal map's one texel: tilted towards +x of tangent space (byte / 255 * 2 - 1 each).
constexpr uint8_t kTexel[4] = {191, 128, 238, 255};
// The light shines along (-0.6, -0.8, 0): towards it is L = (0.6, 0.8, 0).
constexpr double kIrradiance = 2;
const Vec3 kToLight{0.6f, 0.8f, 0};

// A 2s x 2s floor at y = 0 (two triangles, corners p0..p3 counter-clockwise seen from +y) seen
// straight down from (0, 4, 0) through a narrow view, a normal-mapped diffuse material and the
// directional light.
Scene floor_scene(std::vector<Vec2> uvs) {
  Scene scene;
  Material m;
  m.base_color = {kAlbedo, kAlbedo, kAlbedo};
  m.normal_texture = 0;
  scene.materials.push_back(m);
  scene.textures.push_back({"tilt.png", 1, 1, {kTexel[0], kTexel[1], kTexel[2], kTexel[3]}});
  const float s = 10;
  scene.positions = {{-s, 0, s}, {s, 0, s}, {s, 0, -s}, {-s, 0, -s}};
  scene.normals.assign(4, Vec3{0, 1, 0});
  scene.uvs = std::move(uvs);
  scene.indices = {0, 1, 2, 0, 2, 3};
  scene.material_ids = {0, 0};
  scene.cameras.push_back(test::camera_above_floor(10));
  scene.lights.push_back(test::directional_light({-kToLight.x, -kToLight.y, -kToLight.z}, float(kIrradiance)));
  return scene;
}

Film render_floor(Scene& scene, uint32_t size) {
  KdTree tree = test::tree_for(scene);
  RenderStats stats;
  Film film = render(scene, tree, test::tiny_settings(size, 2), DeviceSelection{}, &stats);
  EXPECT_NE(stats.kernel_options.find("KD_FEATURE_NORMAL_MAP"), std::string::npos);
  EXPECT_EQ(stats.nonfinite_values, 0u);
  return film;
}

// The radiance of the floor whose tangent frame is (t, w) at normal n = +y.
double expected_radiance(const Vec3& t, float w) {
  double m[3];
  for (int k = 0; k < 3; ++k) m[k] = kTexel[k] / 255.0 * 2 - 1;
  const Vec3 b{w * (1 * t.z - 0 * t.y), w * (0 * t.x - 0 * t.z), w * (0 * t.y - 1 * t.x)};  // w * cross(+y, t)
  const double mapped[3] = {m[0] * t.x + m[1] * b.x, m[0] * t.y + m[1] * b.y + m[2], m[0] * t.z + m[1] * b.z};
  const double length = std::sqrt(mapped[0] * mapped[0] + mapped[1] * mapped[1] + mapped[2] * mapped[2]);
  const double cos_theta = (mapped[0] * kToLight.x + mapped[1] * kToLight.y + mapped[2] * kToLight.z) / length;
  return kAlbedo * kIrradiance * cos_theta / kPi;
}

TEST(NormalMap, AuthoredTangentsOrientTheMap) {
  // +u runs along +x, but the asset's tangents say +z: the map tilts the normal towards +z,
  // across the light, not towards it.
  Scene scene = floor_scene({{0, 0}, {1, 0}, {1, 1}, {0, 1}});
  scene.tangents.assign(4, Tangent{0, 0, 1, 1});
  const Film film = render_floor(scene, 8);
  const double want = expected_radiance({0, 0, 1}, 1);
  ASSERT_LT(want, 0.9 * expected_radiance({1, 0, 0}, 1));  // the frame of +u would be clearly brighter
  for (float value : film.means()) ASSERT_NEAR(value, want, 1e-4 * want);
}

TEST(NormalMap, ComputedTangentsLeaveNoStepBetweenTrianglesWithDifferentUvDerivatives) {
  // Corner p1's v is lifted: triangle (p0, p1, p2) has dp/du along (1, 0, 1), triangle
  // (p0, p2, p3) along (1, 0, 0). Their shared edge p0-p2 runs through the middle of the view,
  // along the image's anti-diagonal. Per-triangle frames differ by 45 degrees there, about 9% of
  // the radiance under this light; vertex tangents are the same on both sides of the edge.
  Scene scene = floor_scene({{0, 0}, {1, 0.5f}, {1, 1}, {0, 1}});
  // What per-triangle frames would give on the two sides (+v runs along -z on both):
  const double r = 1 / std::sqrt(2.0);
  ASSERT_GT(std::abs(expected_radiance({float(r), 0, float(r)}, 1) / expected_radiance({1, 0, 0}, 1) - 1), 0.05);
  complete_tangents(scene);  // as kdconvert does
  constexpr uint32_t kSize = 32;
  const Film film = render_floor(scene, kSize);
  const std::vector<float> means = film.means();
  double side_sum[2] = {0, 0};
  int side_count[2] = {0, 0};
  for (uint32_t y = 0; y < kSize; ++y)
    for (uint32_t x = 0; x < kSize; ++x) {
      if (x + y == kSize - 1) continue;  // pixels the edge crosses
      const int side = x + y >= kSize ? 1 : 0;
      side_sum[side] += means[(size_t(y) * kSize + x) * 3];
      ++side_count[side];
    }
  const double a = side_sum[0] / side_count[0], b = side_sum[1] / side_count[1];
  EXPECT_GT(a, 0);
  EXPECT_NEAR(a, b, 0.005 * a) << "a step between the two triangles";
}

}  // namespace
}  // namespace kdray
