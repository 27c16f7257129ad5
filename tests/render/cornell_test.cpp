// The sample Cornell box converges without fireflies that do not average away.
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

}  // namespace
}  // namespace kdray
