// kdrender's light options: the default-light warning and --no-default-light, --env and its
// companions, and their refusals (a missing map, options that need --env).
#include "render_fixture.h"

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include <fstream>

namespace kdray {
namespace {

class KdrenderLights : public test::SuiteDirTest<KdrenderLights> {
 protected:
  static void SetUpTestSuite() {
    SuiteDirTest::SetUpTestSuite();
    // One unlit diffuse triangle, no camera: the default light and the default camera.
    Scene scene;
    scene.positions = {{-1, -1, 0}, {1, -1, 0}, {0, 1, 0}};
    scene.indices = {0, 1, 2};
    scene.material_ids = {0};
    scene.materials.push_back(Material{});
    KdTree tree = test::tree_for(scene);
    write_scene(path("unlit.kdscene"), scene);
    write_tree(path("unlit.kdtree"), tree);
  }
  static test::ToolRun kdrender(const std::string& arguments) {
    return test::run_command(test::shell_quoted(test::tool_path("kdrender")) + " " +
                             test::shell_quoted(path("unlit.kdscene")) + " " + test::shell_quoted(path("unlit.kdtree")) +
                             " -o " + test::shell_quoted(path("out.exr")) + " --width 8 --height 8 --spp 1 --json " +
                             arguments + " 2>&1");
  }
};

TEST_F(KdrenderLights, AnUnlitSceneWarnsAndGetsTheDefaultLight) {
  test::ToolRun run = kdrender("");
  ASSERT_EQ(run.exit_code, 0) << run.out;
  EXPECT_NE(run.out.find("kdrender: warning: "), std::string::npos) << run.out;
  EXPECT_NE(run.out.find("--no-default-light"), std::string::npos) << run.out;
  const std::string json = run.out.substr(run.out.find('{'));
  EXPECT_EQ(nlohmann::json::parse(json)["environment"], "default");
  EXPECT_GT(nlohmann::json::parse(json)["mean_radiance"].get<double>(), 0.5);
}

TEST_F(KdrenderLights, NoDefaultLightRendersBlackWithoutWarning) {
  test::ToolRun run = kdrender("--no-default-light");
  ASSERT_EQ(run.exit_code, 0) << run.out;
  EXPECT_EQ(run.out.find("warning"), std::string::npos) << run.out;
  EXPECT_EQ(nlohmann::json::parse(run.out)["mean_radiance"].get<double>(), 0.0);
}

TEST_F(KdrenderLights, EnvColorLightsTheSceneWithoutWarning) {
  test::ToolRun run = kdrender("--env-color 0.5,0.5,0.5 --env-strength 2");
  ASSERT_EQ(run.exit_code, 0) << run.out;
  EXPECT_EQ(run.out.find("warning"), std::string::npos) << run.out;
  nlohmann::json report = nlohmann::json::parse(run.out);
  EXPECT_EQ(report["environment"], "uniform");
  EXPECT_NE(report["kernel_options"].get<std::string>().find("KD_FEATURE_ENVIRONMENT"), std::string::npos);
}

TEST_F(KdrenderLights, AMissingMapIsAnErrorNamingIt) {
  test::ToolRun run = kdrender("--env " + test::shell_quoted(path("missing.exr")));
  EXPECT_EQ(run.exit_code, 1) << run.out;
  EXPECT_NE(run.out.find("kdrender: error: "), std::string::npos) << run.out;
  EXPECT_NE(run.out.find("missing.exr"), std::string::npos) << run.out;
}

TEST_F(KdrenderLights, InconsistentLightOptionsAreUsageErrors) {
  EXPECT_EQ(kdrender("--env-strength 2").exit_code, 2);
  EXPECT_EQ(kdrender("--env-rotate 30").exit_code, 2);
  EXPECT_EQ(kdrender("--env a.exr --env-color 1,1,1").exit_code, 2);
  EXPECT_EQ(kdrender("--env-color 1,1").exit_code, 2);
  EXPECT_EQ(kdrender("--env-color=-1,0,0").exit_code, 2);
}

}  // namespace
}  // namespace kdray
