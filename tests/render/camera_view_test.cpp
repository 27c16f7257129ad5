// The view as the asset frames it: the image size from the camera's aspect ratio, --fov alone
// keeping the camera's place, and orthographic cameras rendered as such (known answer: an
// emitter's image does not shrink with distance), on PoCL and on the host alike.
#include "render_fixture.h"
#include "test_scenes.h"

#include <kdray/render.h>

#include <gtest/gtest.h>

#include <nlohmann/json.hpp>

namespace kdray {
namespace {

Camera camera_with_aspect(float aspect) {
  Camera camera;
  camera.aspect_ratio = aspect;
  return camera;
}

std::pair<uint32_t, uint32_t> size_for(float aspect, uint32_t width, uint32_t height) {
  resolve_image_size(camera_with_aspect(aspect), width, height);
  return {width, height};
}

TEST(ImageSize, FollowsTheCamerasAspectRatio) {
  using Size = std::pair<uint32_t, uint32_t>;
  EXPECT_EQ(size_for(4.0f / 3, 320, 0), Size(320, 240));    // --width alone
  EXPECT_EQ(size_for(4.0f / 3, 0, 300), Size(400, 300));    // --height alone
  EXPECT_EQ(size_for(4.0f / 3, 0, 0), Size(512, 384));      // neither: the longer side 512
  EXPECT_EQ(size_for(0.5f, 0, 0), Size(256, 512));          // portrait
  EXPECT_EQ(size_for(4.0f / 3, 100, 100), Size(100, 100));  // both: as given
  EXPECT_EQ(size_for(0, 0, 0), Size(512, 512));             // no aspect ratio: square
  EXPECT_EQ(size_for(0, 200, 0), Size(200, 200));
  EXPECT_EQ(size_for(1000, 16, 0), Size(16, 1));            // never a zero side
}

TEST(ResolveView, AFieldOfViewAloneKeepsTheScenesCameraInPlace) {
  Scene scene;
  test::add_floor(scene, 0, 1, 0.5f);
  Camera authored = test::camera_above_floor(30);
  authored.aspect_ratio = 2;
  scene.cameras.push_back(authored);
  RenderSettings settings;
  settings.fov_degrees = 50;
  const RenderSettings resolved = resolve_view(scene, settings);
  ASSERT_TRUE(resolved.camera);
  EXPECT_EQ(resolved.camera->position.y, authored.position.y);
  EXPECT_EQ(resolved.camera->up.z, authored.up.z);
  EXPECT_EQ(resolved.camera->vertical_fov_degrees, 50.0f);
  EXPECT_EQ(resolved.width, 512u);
  EXPECT_EQ(resolved.height, 256u);
}

// A unit emitting square facing +Z at depth z, seen by an orthographic camera from +Z whose view
// is 2 x 2 units: it covers the middle quarter of the image whatever its distance.
Scene orthographic_scene(float z) {
  Scene scene;
  Material lamp;
  lamp.type = MaterialType::Emissive;
  lamp.emission = {1, 1, 1};
  scene.materials.push_back(lamp);
  test::add_quad(scene, {{{-0.5f, -0.5f, z}, {0.5f, -0.5f, z}, {0.5f, 0.5f, z}, {-0.5f, 0.5f, z}}}, 0);
  scene.emissive_triangles = {0, 1};
  Camera camera;
  camera.position = {0, 0, 1};
  camera.target = {0, 0, 0};
  camera.projection = Projection::Orthographic;
  camera.orthographic_half_height = 1;
  camera.aspect_ratio = 1;
  scene.cameras.push_back(camera);
  return scene;
}

TEST(OrthographicCamera, AnEmittersImageKeepsItsSizeAtAnyDistance) {
  for (float z : {-1.0f, -20.0f}) {
    Scene scene = orthographic_scene(z);
    const KdTree tree = test::tree_for(scene);
    RenderSettings settings = test::tiny_settings(16, 4);
    settings.max_bounces = 0;
    settings.default_light = false;
    RenderStats stats;
    const Film film = render(scene, tree, settings, DeviceSelection{"cpu"}, &stats);
    EXPECT_NE(stats.kernel_options.find("KD_FEATURE_ORTHOGRAPHIC"), std::string::npos);
    // The square spans pixels 4..11 on both axes, each wholly: exactly a quarter of the image.
    EXPECT_NEAR(film.mean_radiance(), 0.25, 1e-6) << "square at z = " << z;
    DeviceSelection host{kHostDevice};
    const Film cpu = render(scene, tree, settings, host);
    EXPECT_EQ(cpu.sums, film.sums) << "host against the kernel, square at z = " << z;
  }
}

TEST(OrthographicCamera, PerspectiveScenesDoNotCompileIt) {
  Scene scene = orthographic_scene(-1);
  scene.cameras.front().projection = Projection::Perspective;
  RenderSettings settings = test::tiny_settings(8, 1);
  EXPECT_EQ(kernel_feature_options(scene, settings, DeviceSelection{"cpu"}).find("ORTHOGRAPHIC"), std::string::npos);
}

class KdrenderView : public test::TempDirTest<::testing::Test> {};

// A glTF whose first camera is 2:1: --width alone gives a 2:1 image, and --fov alone is accepted.
TEST_F(KdrenderView, WidthAloneTakesTheHeightFromTheCamerasAspectRatio) {
  const std::string gltf = std::string(KDRAY_SOURCE_DIR) + "/tests/scene/cameras-and-extensions.gltf";
  const std::string scene = path("c.kdscene");
  ASSERT_EQ(test::run_command(test::shell_quoted(test::tool_path("kdconvert")) + " -q " + test::shell_quoted(gltf) +
                              " " + test::shell_quoted(scene))
                .exit_code,
            0);
  const std::string render = test::shell_quoted(test::tool_path("kdrender")) + " " + test::shell_quoted(scene) +
                             " --cache " + test::shell_quoted(path("cache")) + " --spp 1 --json -q -o " +
                             test::shell_quoted(path("out.exr"));
  const test::ToolRun sized = test::run_command(render + " --width 40");
  ASSERT_EQ(sized.exit_code, 0) << sized.out;
  const nlohmann::json report = nlohmann::json::parse(sized.out);
  EXPECT_EQ(report["width"], 40);
  EXPECT_EQ(report["height"], 20);
  const test::ToolRun narrower = test::run_command(render + " --height 10 --fov 20");
  ASSERT_EQ(narrower.exit_code, 0) << narrower.out;
  EXPECT_EQ(nlohmann::json::parse(narrower.out)["width"], 20);
}

}  // namespace
}  // namespace kdray
