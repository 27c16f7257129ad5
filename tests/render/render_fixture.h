// Shared pieces of the renderer tests: trees for generated scenes, tiny render settings, the
// sample Cornell box, and running kdray tools.
#pragma once

#include <kdray/kdtree.h>
#include <kdray/render.h>
#include <kdray/scene.h>
#include <kdray/scene_file.h>

#include <subprocess.h>
#include <test_corpus.h>

#include <gtest/gtest.h>

#include <filesystem>
#include <tuple>
#include <string>

namespace kdray::test {

inline KdTree tree_for(Scene& scene) {
  scene.content_hash = compute_content_hash(scene);
  scene.geometry_hash = compute_geometry_hash(scene);
  return build_kdtree(scene, BuildSettings{});
}

inline RenderSettings tiny_settings(uint32_t size, uint32_t spp) {
  RenderSettings settings;
  settings.width = size;
  settings.height = size;
  settings.spp = spp;
  return settings;
}

// The sample Cornell box with Cornell's camera (samples/Makefile's CORNELL_VIEW).
inline Camera cornell_camera() {
  Camera camera;
  camera.position = {278, 273, -800};
  camera.target = {278, 273, 0};
  camera.up = {0, 1, 0};
  camera.vertical_fov_degrees = 39.3077f;
  return camera;
}

// Converts the sample Cornell box and builds its tree with the tools into dir; returns the
// scene and tree paths.
inline std::pair<std::string, std::string> prepare_cornell_files(const std::filesystem::path& dir) {
  std::string scene = (dir / "cornell.kdscene").string(), tree = (dir / "cornell.kdtree").string();
  if (!std::filesystem::exists(scene)) {
    ToolRun convert = run_command(shell_quoted(tool_path("kdconvert")) + " " + shell_quoted(cornell_obj()) + " " +
                                  shell_quoted(scene) + " 2>&1");
    if (convert.exit_code != 0) throw std::runtime_error("kdconvert failed: " + convert.out);
  }
  if (!std::filesystem::exists(tree)) {
    Scene loaded = read_scene(scene);
    write_tree(tree, build_kdtree(loaded, BuildSettings{}));
  }
  return {scene, tree};
}

// A test suite over the sample Cornell box converted and built by the tools, once per suite, in
// the suite's directory; Suite derives from CornellFilesTest<Suite>.
template <typename Suite>
class CornellFilesTest : public SuiteDirTest<Suite> {
 protected:
  static void SetUpTestSuite() {
    SuiteDirTest<Suite>::SetUpTestSuite();
    std::tie(scene_, tree_) = prepare_cornell_files(SuiteDirTest<Suite>::dir_);
  }
  // The shell command running kdrender with `arguments`, with a program cache of the suite's own,
  // so that cold and warm kernel builds are the suite's.
  static std::string kdrender_command(const std::string& arguments) {
    return "KDRAY_CACHE_DIR=" + shell_quoted(SuiteDirTest<Suite>::path("cache")) + " " +
           shell_quoted(tool_path("kdrender")) + " " + arguments;
  }

  static inline std::string scene_, tree_;
};

}  // namespace kdray::test
