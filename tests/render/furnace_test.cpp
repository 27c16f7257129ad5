// Known answers: the furnace (a closed emitting diffuse enclosure) and an emitter seen directly.
#include "render_fixture.h"
#include "test_scenes.h"

#include <kdray/render.h>

#include <gtest/gtest.h>

#include <cmath>

namespace kdray {
namespace {

constexpr float kAlbedo = 0.5f;
constexpr float kEmission = 0.75f;

// A cube seen from inside, every face emitting `emission` over a diffuse `albedo`.
Scene emitting_cube(const Vec3& albedo, const Vec3& emission) {
  Material material;
  material.type = MaterialType::Emissive;
  material.base_color = albedo;
  material.emission = emission;
  return test::make_inward_cube(material);
}

// Paths of up to B+1 scattering events (Cycles' count: B = 0 is direct light) see
// Le * (1 + a + ... + a^(B+1)) = Le (1 - a^(B+2)) / (1 - a).
double furnace_radiance(uint32_t max_bounces) {
  return kEmission * (1.0 - std::pow(double(kAlbedo), max_bounces + 2)) / (1.0 - kAlbedo);
}

class Furnace : public ::testing::TestWithParam<uint32_t> {};

TEST_P(Furnace, MeanRadianceMatchesTheGeometricSeriesWithinOnePercent) {
  Scene scene = emitting_cube({kAlbedo, kAlbedo, kAlbedo}, {kEmission, kEmission, kEmission});
  KdTree tree = test::tree_for(scene);
  RenderSettings settings = test::tiny_settings(32, 64);
  settings.max_bounces = GetParam();
  RenderStats stats;
  Film film = render(scene, tree, settings, DeviceSelection{}, &stats);
  EXPECT_EQ(stats.nonfinite_values, 0u);
  EXPECT_NEAR(film.mean_radiance(), furnace_radiance(GetParam()), 0.01 * furnace_radiance(GetParam()));
  for (float value : film.means()) ASSERT_TRUE(std::isfinite(value));
}

INSTANTIATE_TEST_SUITE_P(MaxBounces, Furnace, ::testing::Values(0u, 1u, 2u, 8u));

TEST(DirectEmitter, EveryPixelSeesExactlyTheEmittedRadiance) {
  // A black, purely emitting enclosure: nothing reflects, so each camera sample returns Le.
  // Le is a multiple of 2^-20, so the fixed-point film holds it exactly.
  Scene scene = emitting_cube({0, 0, 0}, {2.5f, 0.75f, 0.125f});
  KdTree tree = test::tree_for(scene);
  for (uint32_t bounces : {0u, 8u}) {
    RenderSettings settings = test::tiny_settings(16, 4);
    settings.max_bounces = bounces;
    Film film = render(scene, tree, settings, DeviceSelection{});
    std::vector<float> means = film.means();
    for (size_t pixel = 0; pixel < film.pixel_count(); ++pixel) {
      ASSERT_EQ(means[pixel * 3 + 0], 2.5f);
      ASSERT_EQ(means[pixel * 3 + 1], 0.75f);
      ASSERT_EQ(means[pixel * 3 + 2], 0.125f);
    }
  }
}

TEST(DirectEmitter, BackFacesOfEmittersDoNotEmit) {
  // The same cube with outward-facing emitters seen from inside: only the reflections of
  // nothing, so black.
  Scene scene = emitting_cube({0.5f, 0.5f, 0.5f}, {1, 1, 1});
  for (size_t t = 0; t < scene.triangle_count(); ++t) std::swap(scene.indices[3 * t + 1], scene.indices[3 * t + 2]);
  KdTree tree = test::tree_for(scene);
  Film film = render(scene, tree, test::tiny_settings(16, 4), DeviceSelection{});
  EXPECT_EQ(film.mean_radiance(), 0.0);
}

}  // namespace
}  // namespace kdray
