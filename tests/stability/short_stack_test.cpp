// Trees deeper than the short stack: with the stack forced down to one entry (a restart after
// nearly every leaf), traversal and the rendered image are exactly those of the full stack.
#include "brute_force.h"
#include "generated_scenes.h"
#include "tool_pipeline.h"

#include <kdray/kdtree.h>
#include <kdray/ray_sets.h>
#include <kdray/traverse.h>

#include <gtest/gtest.h>

#include <cmath>
#include <cstring>

namespace {

using kdray::Scene;

// A finely tessellated sphere (5120 triangles): its tree is far deeper than KD_SHORT_STACK_SIZE (8).
Scene deep_scene_mesh() { return kdray::test::transformed(kdray::test::icosphere_scene(4, {0, 0, 0}, 1.0f), 30, {0, 30, 0}); }

constexpr uint32_t kShortStack = 8;

}  // namespace

TEST(ShortStack, OneEntryStackFindsTheHitsOfTheFullStack) {
  const Scene scene = deep_scene_mesh();
  const kdray::KdTree tree = kdray::build_kdtree(scene, kdray::BuildSettings{});
  ASSERT_GT(tree.stats.max_depth, 2 * kShortStack) << "the tree must be deeper than the short stack";

  std::vector<RayRecord> rays = kdray::random_rays(kdray::scene_bounds(scene), 20000, 31);
  const std::vector<RayRecord> inside = kdray::rays_toward_surface(scene, {0, 30, 0}, 20000, 32);
  rays.insert(rays.end(), inside.begin(), inside.end());
  std::vector<HitRecord> full, one_entry, short_stack;
  kdray::trace_closest(tree, rays, full, {0, kdray::TraversalStack::Full});
  kdray::trace_closest(tree, rays, one_entry, {0, kdray::TraversalStack::Depth1});
  kdray::trace_closest(tree, rays, short_stack, {0, kdray::TraversalStack::Short});

  // Restarting may resolve a tie differently: a ray through a shared vertex can report either
  // triangle, a float ulp apart. Anything else counts as a difference: both answers must
  // agree with brute force and with each other up to float tolerance.
  const double magnitude = kdray::test::scene_magnitude(scene);
  for (const auto* other : {&one_entry, &short_stack}) {
    size_t ties = 0;
    std::vector<std::string> wrong;
    for (size_t i = 0; i < rays.size(); ++i) {
      const HitRecord& a = full[i];
      const HitRecord& b = (*other)[i];
      if (std::memcmp(&a, &b, sizeof(HitRecord)) == 0) continue;
      const bool tie = a.triangle != KD_NO_HIT && b.triangle != KD_NO_HIT &&
                       std::abs(double(a.t) - double(b.t)) <= kdray::test::t_tolerance(rays[i], magnitude, a.t) &&
                       kdray::test::disagreement(scene, rays[i], b, magnitude).empty();
      if (tie) {
        ++ties;
      } else {
        wrong.push_back(kdray::test::describe_ray(rays[i]) + ": full stack triangle " + std::to_string(a.triangle) +
                        " t=" + std::to_string(a.t) + ", other triangle " + std::to_string(b.triangle) +
                        " t=" + std::to_string(b.t));
      }
    }
    const char* name = other == &one_entry ? "one-entry stack" : "short stack";
    EXPECT_EQ(wrong.size(), 0u) << name << ", of " << rays.size() << " rays (" << ties << " ties)";
    for (size_t k = 0; k < wrong.size() && k < 3; ++k) ADD_FAILURE() << name << ": " << wrong[k];
  }
}

TEST(ShortStack, KdrenderWithAOneEntryStackRendersTheSameImage) {
  const kdray::test::ToolPipeline tools;
  const Scene sphere = deep_scene_mesh();
  const Scene floor = kdray::test::make_scene({{-100, 0, -100}, {-100, 0, 100}, {100, 0, 100}, {100, 0, -100}},
                                              {0, 1, 2, 0, 2, 3});
  const Scene light = kdray::test::make_scene({{-20, 100, -20}, {20, 100, -20}, {20, 100, 20}, {-20, 100, 20}},
                                              {0, 1, 2, 0, 2, 3});
  const std::string obj = tools.path("deep.obj");
  kdray::test::write_obj(obj,
                         kdray::test::obj_mesh(sphere, "white", 0) +
                             kdray::test::obj_mesh(floor, "white", sphere.positions.size()) +
                             kdray::test::obj_mesh(light, "light", sphere.positions.size() + 4),
                         kdray::test::white_and_light_mtl(10.0f));
  tools.convert_and_build(obj, "deep");
  const std::string settings =
      " --cam-pos 0,50,150 --cam-target 0,30,0 --cam-up 0,1,0 --fov 45 --width 24 --height 24 --spp 4 --max-bounces 3";
  tools.render("deep", tools.path("full.exr"), "--stack-size 64" + settings);
  tools.render("deep", tools.path("one.exr"), "--stack-size 1" + settings);
  // Every pixel's radiance identical: max |difference| exactly 0.
  const kdray::test::ToolRun same = kdray::test::run_command(
      kdray::test::shell_quoted(kdray::test::tool_path("kdcompare")) + " " +
      kdray::test::shell_quoted(tools.path("one.exr")) + " " + kdray::test::shell_quoted(tools.path("full.exr")) +
      " --threshold max_abs=0");
  EXPECT_EQ(same.exit_code, 0) << same.out;
}
