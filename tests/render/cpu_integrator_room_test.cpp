// The C++ build of the path tracer against the kernel (tests/render/cpu_integrator.h) in the
// feature room: emission, mirror, rough conductor, glass, a checker texture and per-vertex normals,
// with every AOV.
#define KD_FEATURE_EMISSION
#define KD_FEATURE_MIRROR
#define KD_FEATURE_GLOSSY
#define KD_FEATURE_GLASS
#define KD_FEATURE_TEXTURES
#define KD_FEATURE_NORMALS

#include "cpu_integrator.h"
#include "test_scenes.h"

namespace kdray::test {
namespace {

TEST(CpuIntegrator, FeatureRoomMatchesTheKernelBitForBit) {
  Scene scene = make_feature_room();
  RenderSettings settings = tiny_settings(24, 4);
  settings.aov_albedo = settings.aov_normal = settings.aov_depth = true;
  EXPECT_GT(expect_cpu_matches_kernel(scene, settings), 24u * 24u / 2);
}

}  // namespace
}  // namespace kdray::test
