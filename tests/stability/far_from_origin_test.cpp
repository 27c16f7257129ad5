// Geometry far from the origin (1e5 and 1e6 units) and scaled down by 1e-4: hits still agree
// with brute force, and a lit diffuse plane shows no self-intersection acne (its rendered mean
// is the same at every placement, within noise).
#include "brute_force.h"
#include "generated_scenes.h"
#include "tool_pipeline.h"

#include <kdray/kdtree.h>
#include <kdray/ray_sets.h>
#include <kdray/traverse.h>

#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>

namespace {

using kdray::Scene;
using kdray::Vec3;

struct Placement {
  const char* name;
  double scale;
  double offset;  // added to x, y and z
};

// The base size is 100 units for the translated copies, so float spacing at 1e6 (0.0625) is
// small against the triangles, as in a real far-away model; the scaled copy shrinks the
// unit-size scene to 2e-4 across.
const Placement kPlacements[] = {
    {"at the origin", 50, 0},
    {"1e5 from the origin", 50, 1e5},
    {"1e6 from the origin", 50, 1e6},
    {"scaled by 1e-4", 1e-4, 0},
};

Scene unit_scene() {
  Scene scene = kdray::test::make_grid_box(-1.0f, 1.0f, 4);
  kdray::test::append_mesh(scene, kdray::test::icosphere_scene(2, {0, 0, 0}, 0.6f));
  return scene;
}

}  // namespace

TEST(FarFromOrigin, HitsAgreeWithBruteForceAtEveryPlacement) {
  const Scene base = unit_scene();
  for (const Placement& placement : kPlacements) {
    SCOPED_TRACE(placement.name);
    const float offset = float(placement.offset);
    const Scene scene = kdray::test::transformed(base, placement.scale, {offset, offset, offset});
    const kdray::KdTree tree = kdray::build_kdtree(scene, kdray::BuildSettings{});
    std::vector<RayRecord> rays = kdray::random_rays(kdray::scene_bounds(scene), 3000, 11);
    const std::vector<RayRecord> inside = kdray::rays_toward_surface(scene, {offset, offset, offset}, 3000, 12);
    rays.insert(rays.end(), inside.begin(), inside.end());

    const std::vector<HitRecord> hits = kdray::test::trace_checked(scene, tree, rays);
    size_t escapes = 0;
    for (size_t i = 3000; i < rays.size(); ++i) escapes += hits[i].triangle == KD_NO_HIT ? 1 : 0;
    EXPECT_EQ(escapes, 0u) << "rays from the centre leave the closed box";
  }
}

namespace {

// A 200 x 200 diffuse floor lit by a 40 x 40 emitter 100 above it, seen by a camera that does
// not see the emitter, all scaled and moved by the placement. Returns the rendered mean.
double lit_plane_mean(const kdray::test::ToolPipeline& tools, const Placement& placement, const std::string& stem) {
  auto place = [&](double x, double y, double z) {
    const double s = placement.scale / 50;  // the plane is 200 across at scale 50
    return Vec3{float(x * s + placement.offset), float(y * s + placement.offset), float(z * s + placement.offset)};
  };
  const Scene floor = kdray::test::make_scene(
      {place(-100, 0, -100), place(-100, 0, 100), place(100, 0, 100), place(100, 0, -100)}, {0, 1, 2, 0, 2, 3});
  const Scene light = kdray::test::make_scene(
      {place(-20, 100, -20), place(20, 100, -20), place(20, 100, 20), place(-20, 100, 20)}, {0, 1, 2, 0, 2, 3});
  const std::string obj = tools.path(stem + ".obj");
  kdray::test::write_obj(obj, kdray::test::obj_mesh(floor, "white", 0) + kdray::test::obj_mesh(light, "light", 4),
                         kdray::test::white_and_light_mtl(10.0f));
  tools.convert_and_build(obj, stem);

  const Vec3 eye = place(0, 60, 200), target = place(0, 0, 0);
  char camera[512];
  std::snprintf(camera, sizeof camera, "--cam-pos %.9g,%.9g,%.9g --cam-target %.9g,%.9g,%.9g --cam-up 0,1,0 --fov 40",
                eye.x, eye.y, eye.z, target.x, target.y, target.z);
  const nlohmann::json report = tools.render(stem, tools.path(stem + ".exr"),
                                             std::string(camera) + " --width 32 --height 32 --spp 16 --max-bounces 1");
  EXPECT_EQ(report["nonfinite_values"], 0);
  return report["mean_radiance"].get<double>();
}

}  // namespace

TEST(FarFromOrigin, LitPlaneRendersTheSameMeanAtEveryPlacement) {
  const kdray::test::ToolPipeline tools;
  const double reference = lit_plane_mean(tools, kPlacements[0], "origin");
  ASSERT_GT(reference, 0.05);
  for (size_t i = 1; i < std::size(kPlacements); ++i) {
    const double mean = lit_plane_mean(tools, kPlacements[i], "placement" + std::to_string(i));
    // Acne (the floor shadowing itself) darkens most of the picture; the same seed and the
    // same relative geometry otherwise give nearly the same samples.
    EXPECT_NEAR(mean, reference, 0.02 * reference) << kPlacements[i].name;
  }
}
