// The sample Cornell box converges without fireflies that do not average away, and its direct
// light is the same with and without MIS (next-event estimation and BSDF samples that hit the
// light weigh with the same light density, by solid angle or by area as the light subtends).
#include "render_fixture.h"

#include <kdray/import.h>

#include <gtest/gtest.h>

namespace kdray {
namespace {

TEST(SampleCornellBox, SixteenSampleMeanIsWithinTwoPercentOfTheConvergedMean) {
  Scene scene = import_scene(test::cornell_obj(), ImportOptions{});
  ASSERT_FALSE(scene.emissive_triangles.empty());
  KdTree tree = test::tree_for(scene);
  // The image mean does not depend on the resolution, so the 1024-spp reference can be small;
  // the 16-spp image has enough pixels (262k paths) that its mean's own noise is about 0.6%.
  RenderSettings noisy = test::tiny_settings(128, 16);
  RenderSettings converged = test::tiny_settings(32, 1024);
  noisy.camera = converged.camera = test::cornell_camera();
  converged.seed = 1;
  RenderStats stats;
  double noisy_mean = render(scene, tree, noisy, DeviceSelection{}, &stats).mean_radiance();
  EXPECT_EQ(stats.nonfinite_values, 0u);
  double converged_mean = render(scene, tree, converged, DeviceSelection{}, &stats).mean_radiance();
  EXPECT_EQ(stats.nonfinite_values, 0u);
  EXPECT_GT(converged_mean, 0.05);
  EXPECT_NEAR(noisy_mean, converged_mean, 0.02 * converged_mean);
}

TEST(SampleCornellBox, DirectLightIsTheSameWithAndWithoutMis) {
  Scene scene = import_scene(test::cornell_obj(), ImportOptions{});
  KdTree tree = test::tree_for(scene);
  RenderSettings settings = test::tiny_settings(48, 256);
  settings.camera = test::cornell_camera();
  settings.max_bounces = 1;  // the ceiling next to the light sees it at large solid angles
  Film with = render(scene, tree, settings, DeviceSelection{});
  settings.mis = false;
  settings.seed = 1;
  Film without = render(scene, tree, settings, DeviceSelection{});
  // Each mean has about 0.2% noise; inconsistent weights (area density on one side, solid angle
  // on the other) shift the MIS image by several percent.
  EXPECT_NEAR(with.mean_radiance(), without.mean_radiance(), 0.01 * without.mean_radiance());
}

}  // namespace
}  // namespace kdray
