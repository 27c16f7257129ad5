// The C++ build of the path tracer against the kernel (tests/render/cpu_integrator.h) in the
// feature room: emission, mirror, rough conductor, glass, a checker texture and per-vertex normals,
// with every AOV.

#include "cpu_integrator.h"
#include "test_scenes.h"

namespace kdray::test {
namespace {

TEST(CpuIntegrator, FeatureRoomMatchesTheKernelBitForBit) {
  Scene scene = make_feature_room();
  RenderSettings settings = tiny_settings(24, 4);
  settings.aov_albedo = settings.aov_normal = settings.aov_depth = true;
  EXPECT_GT(expect_host_matches_kernel(scene, settings,
                                       {"-DKD_FEATURE_EMISSION", "-DKD_FEATURE_MIRROR", "-DKD_FEATURE_GLOSSY",
                                        "-DKD_FEATURE_GLASS", "-DKD_FEATURE_TEXTURES", "-DKD_FEATURE_NORMALS"}),
            24u * 24u / 2);
}

}  // namespace
}  // namespace kdray::test
