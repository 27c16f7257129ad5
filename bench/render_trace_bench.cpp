// render_trace_bench SCENE.kdscene SCENE.kdtree [RAYS]: OpenCL traversal-kernel Mrays/s for
// camera rays (a square image of about RAYS pixels) and RAYS random rays (libkdtree's ray
// sets), median of 3 kernel runs each after one warm-up; one JSON line on stdout.
// Used by bench/render.sh.
#include <kdray/kdtree.h>
#include <kdray/ray_sets.h>
#include <kdray/scene_file.h>
#include <kdray/trace_opencl.h>

#include <nlohmann/json.hpp>

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <iostream>

namespace {

double median_mrays(const kdray::KdTree& tree, const std::vector<RayRecord>& rays) {
  kdray::trace_rays_opencl(tree, rays, {});  // warm-up: program build, first touch
  std::vector<double> rates;
  for (int run = 0; run < 3; ++run) {
    kdray::TraceOpenClStats stats;
    kdray::trace_rays_opencl(tree, rays, {}, &stats);
    rates.push_back(double(rays.size()) / stats.trace_seconds * 1e-6);
  }
  std::sort(rates.begin(), rates.end());
  return rates[1];
}

}  // namespace

int main(int argc, char** argv) {
  if (argc < 3) {
    std::cerr << "usage: render_trace_bench SCENE.kdscene SCENE.kdtree [RAYS]\n";
    return 2;
  }
  try {
    size_t count = argc > 3 ? std::strtoull(argv[3], nullptr, 10) : 1000000;
    kdray::Scene scene = kdray::read_scene(argv[1]);
    kdray::KdTree tree = kdray::read_tree(argv[2]);
    kdray::check_tree_matches_scene(tree, argv[2], kdray::geometry_of(scene), argv[1]);
    uint32_t side = static_cast<uint32_t>(std::sqrt(double(count)));
    double camera = median_mrays(tree, kdray::camera_rays(scene, side, side));
    double random = median_mrays(tree, kdray::random_rays(tree.bounds, count, 1));
    nlohmann::json report = {{"scene", argv[1]},
                             {"triangles", scene.triangle_count()},
                             {"camera_rays", side * side},
                             {"camera_mrays_per_s", camera},
                             {"random_rays", count},
                             {"random_mrays_per_s", random},
                             {"device", kdray::select_device({}).name}};
    std::cout << report.dump() << std::endl;
    return 0;
  } catch (const std::exception& error) {
    std::cerr << "render_trace_bench: error: " << error.what() << "\n";
    return 1;
  }
}
