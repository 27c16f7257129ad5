#include "test_scenes.h"

#include <kdray/import.h>
#include <kdray/ray_sets.h>

#include <kernels/kd_geometry.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstring>
#include <map>
#include <utility>

namespace kdray::test {
namespace {

Scene finish(Scene scene) { return mesh_scene(std::move(scene.positions), std::move(scene.indices)); }

void add_quad(Scene& scene, Vec3 a, Vec3 b, Vec3 c, Vec3 d) {
  const uint32_t base = static_cast<uint32_t>(scene.positions.size());
  scene.positions.insert(scene.positions.end(), {a, b, c, d});
  scene.indices.insert(scene.indices.end(), {base, base + 1, base + 2, base, base + 2, base + 3});
}

// The 6 faces of an axis-aligned box, as quads with outward winding.
void add_box(Scene& scene, Vec3 lo, Vec3 hi) {
  add_quad(scene, {lo.x, lo.y, lo.z}, {lo.x, hi.y, lo.z}, {hi.x, hi.y, lo.z}, {hi.x, lo.y, lo.z});
  add_quad(scene, {lo.x, lo.y, hi.z}, {hi.x, lo.y, hi.z}, {hi.x, hi.y, hi.z}, {lo.x, hi.y, hi.z});
  add_quad(scene, {lo.x, lo.y, lo.z}, {hi.x, lo.y, lo.z}, {hi.x, lo.y, hi.z}, {lo.x, lo.y, hi.z});
  add_quad(scene, {lo.x, hi.y, lo.z}, {lo.x, hi.y, hi.z}, {hi.x, hi.y, hi.z}, {hi.x, hi.y, lo.z});
  add_quad(scene, {lo.x, lo.y, lo.z}, {lo.x, lo.y, hi.z}, {lo.x, hi.y, hi.z}, {lo.x, hi.y, lo.z});
  add_quad(scene, {hi.x, lo.y, lo.z}, {hi.x, hi.y, lo.z}, {hi.x, hi.y, hi.z}, {hi.x, lo.y, hi.z});
}

uint64_t next_random(uint64_t& state) {
  uint64_t z = (state += 0x9e3779b97f4a7c15ull);
  z = (z ^ (z >> 30)) * 0xbf58476d1ce4e5b9ull;
  z = (z ^ (z >> 27)) * 0x94d049bb133111ebull;
  return z ^ (z >> 31);
}
float unit_random(uint64_t& state) { return static_cast<float>(next_random(state) >> 40) * 0x1.0p-24f; }

}  // namespace

Scene box_room() {
  Scene scene;
  add_box(scene, {-1, 0, -1}, {1, 2, 1});
  add_box(scene, {-0.7f, 0, -0.6f}, {-0.1f, 1.2f, 0.0f});
  add_box(scene, {0.1f, 0, 0.1f}, {0.7f, 0.6f, 0.7f});
  return finish(std::move(scene));
}

Scene triangle_soup(size_t count, uint64_t seed) {
  Scene scene;
  uint64_t state = seed;
  for (size_t i = 0; i < count; ++i) {
    const Vec3 centre{unit_random(state), unit_random(state), unit_random(state)};
    const uint32_t base = static_cast<uint32_t>(scene.positions.size());
    for (int c = 0; c < 3; ++c)
      scene.positions.push_back({centre.x + 0.1f * (unit_random(state) - 0.5f), centre.y + 0.1f * (unit_random(state) - 0.5f),
                                 centre.z + 0.1f * (unit_random(state) - 0.5f)});
    scene.indices.insert(scene.indices.end(), {base, base + 1, base + 2});
  }
  return finish(std::move(scene));
}

Scene coplanar_grid(int cells) {
  Scene scene;
  for (int y = 0; y < cells; ++y)
    for (int x = 0; x < cells; ++x) {
      const float x0 = static_cast<float>(x) / cells, x1 = static_cast<float>(x + 1) / cells;
      const float y0 = static_cast<float>(y) / cells, y1 = static_cast<float>(y + 1) / cells;
      add_quad(scene, {x0, y0, 0.25f}, {x1, y0, 0.25f}, {x1, y1, 0.25f}, {x0, y1, 0.25f});
    }
  return finish(std::move(scene));
}

Scene from_triangles(const std::vector<float>& corners_xyz) {
  Scene scene;
  for (size_t i = 0; i + 2 < corners_xyz.size(); i += 3) {
    scene.positions.push_back({corners_xyz[i], corners_xyz[i + 1], corners_xyz[i + 2]});
    scene.indices.push_back(static_cast<uint32_t>(scene.indices.size()));
  }
  return finish(std::move(scene));
}

Scene mesh_file(const std::string& path) {
  Scene scene = import_scene(path, ImportOptions{});
  scene.content_hash = compute_content_hash(scene);
  scene.geometry_hash = compute_geometry_hash(scene);
  return scene;
}

bool is_origin_hit(const Scene& scene, const RayRecord& ray, const HitRecord& hit) {
  if (hit.triangle == KD_NO_HIT) return false;
  const double scale = std::max({1.0, std::fabs(double(ray.ox)), std::fabs(double(ray.oy)), std::fabs(double(ray.oz))});
  return std::fabs(intersect_double(scene, hit.triangle, ray).t) <= 1e-6 * scale;
}

HitRecord brute_force_float(const Scene& scene, const RayRecord& record, bool skip_origin_hits) {
  HitRecord best{INFINITY, KD_NO_HIT, 0, 0};
  KdRay ray;
  if (!kd_ray_setup(&ray, record.ox, record.oy, record.oz, record.dx, record.dy, record.dz, record.tmin, record.tmax))
    return best;
  float t_max = record.tmax;
  for (uint32_t triangle = 0; triangle < scene.triangle_count(); ++triangle) {
    const float* a = &scene.positions[scene.indices[3 * triangle]].x;
    const float* b = &scene.positions[scene.indices[3 * triangle + 1]].x;
    const float* c = &scene.positions[scene.indices[3 * triangle + 2]].x;
    float t, u, v;
    if (kd_ray_triangle(&ray, a, b, c, t_max, &t, &u, &v)) {
      if (skip_origin_hits && is_origin_hit(scene, record, HitRecord{t, triangle, u, v})) continue;
      best = HitRecord{t, triangle, u, v};
      t_max = t;
    }
  }
  return best;
}

DoubleHit brute_force_double(const Scene& scene, const RayRecord& ray) {
  DoubleHit best;
  const double scale = std::max({1.0, std::fabs(double(ray.ox)), std::fabs(double(ray.oy)), std::fabs(double(ray.oz))});
  for (uint32_t triangle = 0; triangle < scene.triangle_count(); ++triangle) {
    const DoubleHit candidate = intersect_double(scene, triangle, ray);
    if (candidate.t <= 1e-6 * scale) continue;  // the triangle the ray starts on
    if (candidate.hit && (!best.hit || candidate.t < best.t)) best = candidate;
  }
  return best;
}

std::vector<RayRecord> ray_mix(const Scene& scene, const KdTree& tree, size_t count, uint64_t seed) {
  std::vector<RayRecord> rays = random_rays(scene_bounds(scene), count, seed);
  for (const std::vector<RayRecord>& more : {hard_case_rays(scene, tree, count, seed + 1), camera_rays(scene, 64, 48)})
    rays.insert(rays.end(), more.begin(), more.end());
  return rays;
}

std::vector<uint32_t> leaf_triangle_indices(const KdTree& tree) {
  std::vector<uint32_t> indices;
  for (const KdNode& node : tree.nodes) {
    if (!kd_node_is_leaf(node)) continue;
    const uint32_t* block = tree.leaf_blocks.data() + kd_leaf_first(node);
    for (uint32_t i = 0; i < kd_leaf_count(node); ++i) indices.push_back(kd_leaf_index(block, kd_leaf_grouped(node), i));
  }
  return indices;
}

namespace {

void add_with_empty_leaves(const KdTree& tree, uint32_t index, std::vector<KdNode>& out) {
  const KdNode node = tree.nodes[index];
  if (kd_node_is_leaf(node)) {
    out.push_back(node);
    return;
  }
  const size_t inner = out.size();
  out.push_back(KdNode{node.payload, kd_node_axis(node)});
  if (kd_node_below_empty(node))
    out.push_back(KdNode{0, KD_LEAF_TAG});
  else
    add_with_empty_leaves(tree, index + 1, out);
  out[inner].header |= static_cast<uint32_t>(out.size()) << 2;
  if (kd_node_above_empty(node))
    out.push_back(KdNode{0, KD_LEAF_TAG});
  else
    add_with_empty_leaves(tree, kd_node_far_child(node), out);
}

}  // namespace

std::vector<KdNode> nodes_with_empty_leaves(const KdTree& tree) {
  std::vector<KdNode> out;
  add_with_empty_leaves(tree, 0, out);
  return out;
}

bool same_tree_bytes(const KdTree& a, const KdTree& b) {
  return a.nodes.size() == b.nodes.size() && a.leaf_blocks.size() == b.leaf_blocks.size() &&
         std::memcmp(a.nodes.data(), b.nodes.data(), a.nodes.size() * sizeof(KdNode)) == 0 &&
         std::memcmp(a.leaf_blocks.data(), b.leaf_blocks.data(), a.leaf_blocks.size() * sizeof(uint32_t)) == 0;
}

}  // namespace kdray::test
