// kd_traverse.h's fast path against the robust traversal alone (kdtrace --traversal robust, the
// code every ray ran before it): the same hit files byte for byte, on the host and on PoCL, for
// the hard-case rays (axis-aligned with +0/-0 components, on and in split planes, through
// vertices and edges), random rays and camera rays, on the Cornell box, the bunny and a box of
// coplanar grid triangles with a sphere inside.
#include "generated_scenes.h"
#include "tool_pipeline.h"

#include <gtest/gtest.h>

#include <fstream>
#include <iterator>
#include <string>

namespace {

using kdray::test::ToolPipeline;

std::string slurp(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
}

// Traces every ray set of <stem> with both traversals on both devices and expects one hit file.
// Returns the share of the hard-case rays that took the fast path (kdtrace's per-ray count).
double expect_identical_hits(const ToolPipeline& tools, const std::string& stem) {
  double hard_fast_share = 0;
  for (const std::string set : {"hard", "random", "camera"}) {
    const std::string trace = kdray::test::shell_quoted(tools.scene(stem)) + " " +
                              kdray::test::shell_quoted(tools.tree(stem)) + " --generate " + set +
                              " --count 20000 --seed 7 --width 96 --height 64";
    const std::string robust = tools.path(stem + "." + set + ".robust.hits");
    tools.run_json("kdtrace", trace + " --traversal robust --hits " + kdray::test::shell_quoted(robust));
    const std::string expected = slurp(robust);
    EXPECT_FALSE(expected.empty()) << stem << ", " << set << " rays: no hits written";
    for (const std::string device : {"host", "cpu"}) {
      const std::string fast = tools.path(stem + "." + set + "." + device + ".hits");
      const nlohmann::json report =
          tools.run_json("kdtrace", trace + " --device " + device + " --hits " + kdray::test::shell_quoted(fast));
      EXPECT_TRUE(expected == slurp(fast)) << stem << ", " << set << " rays, fast path on " << device;
      if (set == std::string("hard")) hard_fast_share = report["per_ray"]["fast_path"].get<double>();
      if (device == std::string("cpu")) {
        const std::string pocl_robust = tools.path(stem + "." + set + ".cpu.robust.hits");
        tools.run_json("kdtrace", trace + " --device cpu --traversal robust --hits " +
                                      kdray::test::shell_quoted(pocl_robust));
        EXPECT_TRUE(expected == slurp(pocl_robust)) << stem << ", " << set << " rays, robust traversal on PoCL";
      }
    }
  }
  return hard_fast_share;
}

}  // namespace

TEST(FastPath, CornellBoxHitsAreTheRobustTraversals) {
  ToolPipeline tools;
  tools.convert_and_build(kdray::test::cornell_obj(), "cornell");
  const double share = expect_identical_hits(tools, "cornell");
  // The hard set is built to be mostly rays the fast path must refuse; some must still take it.
  EXPECT_GT(share, 0.0);
  EXPECT_LT(share, 1.0);
}

TEST(FastPath, BunnyHitsAreTheRobustTraversals) {
  std::string bunny;
  KDRAY_CORPUS_FILE(bunny, "bunny/bunny_vn_euclid.ply");
  ToolPipeline tools;
  tools.convert_and_build(bunny, "bunny");
  expect_identical_hits(tools, "bunny");
}

TEST(FastPath, CoplanarGridBoxHitsAreTheRobustTraversals) {
  kdray::Scene scene = kdray::test::make_grid_box(-1.0f, 1.0f, 8);
  kdray::test::append_mesh(scene, kdray::test::icosphere_scene(2, {0.25f, 0, 0}, 0.5f));
  ToolPipeline tools;
  const std::string obj = tools.path("grid-box.obj");
  kdray::test::write_obj(obj, kdray::test::obj_mesh(scene, "white", 0), kdray::test::white_and_light_mtl(1.0f));
  tools.convert_and_build(obj, "grid-box");
  expect_identical_hits(tools, "grid-box");
}
