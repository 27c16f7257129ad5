// kdtree_counters SCENE TREE [RANDOM_RAYS]: the work a ray costs in a tree, for comparing
// builders by more than the SAH: inner-node steps, leaves visited and triangle tests per ray,
// for camera rays (512x384) and random rays (seed 1), and the leaves by triangle count. It
// counts with its own plain front-to-back traversal (full stack, the ray/box and ray/triangle tests of the kernels), so
// the figures compare trees, not traversal codes. Prints JSON.
#include <kdray/kdtree.h>
#include <kdray/ray_sets.h>
#include <kdray/scene_file.h>

#include <kernels/kd_geometry.h>

#include <nlohmann/json.hpp>

#include <algorithm>
#include <cstdio>
#include <cstdlib>
#include <exception>
#include <string>
#include <vector>

namespace {

struct Counters {
  double steps = 0, leaves = 0, tests = 0, hits = 0;
};

void count_ray(const kdray::Scene& scene, const kdray::KdTree& tree, const RayRecord& record, Counters& counters) {
  KdRay ray;
  if (!kd_ray_setup(&ray, record.ox, record.oy, record.oz, record.dx, record.dy, record.dz, record.tmin,
                    record.tmax))
    return;
  const float box_min[3] = {tree.bounds.min.x, tree.bounds.min.y, tree.bounds.min.z};
  const float box_max[3] = {tree.bounds.max.x, tree.bounds.max.y, tree.bounds.max.z};
  float t_min = record.tmin, t_max = record.tmax;
  if (!kd_ray_box(&ray, box_min, box_max, &t_min, &t_max)) return;
  struct Entry {
    uint32_t node;
    float t_min, t_max;
  };
  Entry stack[kdray::BuildSettings::kMaxDepthLimit + 1];
  int size = 0;
  uint32_t node = 0;
  float best = record.tmax;
  // An empty child is no node: it is visited as the empty leaf it stands for.
  constexpr uint32_t kEmptyChild = UINT32_MAX;
  auto node_at = [&](uint32_t index) { return index == kEmptyChild ? KdNode{0, KD_LEAF_TAG} : tree.nodes[index]; };
  for (;;) {
    KdNode current = node_at(node);
    while (!kd_node_is_leaf(current)) {
      ++counters.steps;
      const uint32_t axis = kd_node_axis(current);
      const float split = kd_node_split(current);
      const float t_split = (split - ray.org[axis]) * ray.inv_dir[axis];
      const bool below_first = t_split == 0.0f ? ray.dir[axis] <= 0.0f : ray.org[axis] < split;  // kd_visit_inner's
      auto child = [&](uint32_t above) {
        return kd_node_child_empty(current, above) ? kEmptyChild : kd_node_child(current, node, above);
      };
      const uint32_t near = child(below_first ? 0 : 1);
      const uint32_t far = child(below_first ? 1 : 0);
      if (t_split > t_max || t_split <= 0.0f) {
        node = near;
      } else if (t_split < t_min) {
        node = far;
      } else {
        stack[size++] = {far, t_split, t_max};
        node = near;
        t_max = t_split;
      }
      current = node_at(node);
    }
    ++counters.leaves;
    const uint32_t first = kd_leaf_first(current), count = kd_leaf_count(current);
    counters.tests += count;
    for (uint32_t i = 0; i < count; ++i) {
      const uint32_t triangle = kd_leaf_index(tree.leaf_blocks.data() + first, kd_leaf_grouped(current), i);
      float corners[3][3];
      for (int c = 0; c < 3; ++c) {
        const kdray::Vec3& p = scene.positions[scene.indices[3 * static_cast<size_t>(triangle) + c]];
        corners[c][0] = p.x;
        corners[c][1] = p.y;
        corners[c][2] = p.z;
      }
      float t, u, v;
      if (kd_ray_triangle(&ray, corners[0], corners[1], corners[2], best, &t, &u, &v)) best = t;
    }
    if (best <= t_max * (1.0f + 1e-6f) || size == 0) break;
    --size;
    node = stack[size].node;
    t_min = stack[size].t_min;
    t_max = stack[size].t_max;
  }
  counters.hits += best < record.tmax;
}

nlohmann::json count_rays(const kdray::Scene& scene, const kdray::KdTree& tree, const std::vector<RayRecord>& rays) {
  Counters counters;
  for (const RayRecord& ray : rays) count_ray(scene, tree, ray, counters);
  const double n = static_cast<double>(rays.size());
  return {{"rays", rays.size()}, {"steps_per_ray", counters.steps / n}, {"leaves_per_ray", counters.leaves / n},
          {"triangle_tests_per_ray", counters.tests / n}, {"hit_share", counters.hits / n}};
}

}  // namespace

int main(int argc, char** argv) {
  if (argc < 3 || argc > 4) {
    std::fprintf(stderr, "usage: kdtree_counters SCENE TREE [RANDOM_RAYS]\n");
    return 2;
  }
  try {
    const kdray::Scene scene = kdray::read_scene(argv[1]);
    const kdray::KdTree tree = kdray::read_tree(argv[2]);
    kdray::check_tree_matches_scene(tree, argv[2], kdray::geometry_of(scene), argv[1]);
    const size_t random_count = argc == 4 ? std::strtoull(argv[3], nullptr, 10) : 200000;
    // Leaves by triangle count (0, 1, 2, 3, 4 or more): what a compact leaf encoding would save.
    uint64_t leaves_by_count[5] = {tree.stats.empty_leaves};
    for (const KdNode& node : tree.nodes)
      if (kd_node_is_leaf(node) && kd_leaf_count(node) > 0)
        ++leaves_by_count[std::min<uint32_t>(kd_leaf_count(node), 4)];
    const nlohmann::json out = {
        {"leaves_by_triangle_count", leaves_by_count},
        {"camera", count_rays(scene, tree, kdray::camera_rays(scene, 512, 384))},
        {"random", count_rays(scene, tree, kdray::random_rays(tree.bounds, random_count, 1))}};
    std::printf("%s\n", out.dump(2).c_str());
  } catch (const std::exception& error) {
    std::fprintf(stderr, "kdtree_counters: error: %s\n", error.what());
    return 1;
  }
  return 0;
}
