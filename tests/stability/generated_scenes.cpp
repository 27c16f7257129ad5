#include "generated_scenes.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <map>
#include <stdexcept>

namespace kdray::test {

Scene make_scene(std::vector<Vec3> positions, std::vector<uint32_t> indices) {
  Scene scene = mesh_scene(std::move(positions), std::move(indices));
  scene.cameras.push_back(Camera{});
  scene.content_hash = compute_content_hash(scene);
  return scene;
}

void append_mesh(Scene& scene, const Scene& extra) {
  const uint32_t base = uint32_t(scene.positions.size());
  scene.positions.insert(scene.positions.end(), extra.positions.begin(), extra.positions.end());
  for (uint32_t index : extra.indices) scene.indices.push_back(base + index);
  scene.material_ids.resize(scene.triangle_count(), 0);
  scene.content_hash = compute_content_hash(scene);
  scene.geometry_hash = compute_geometry_hash(scene);
}

Scene make_grid_box(float lo, float hi, int cells) {
  // Grid coordinates are exact: lo + (hi - lo) * i / cells in double, rounded once, and every
  // vertex is shared by the faces that meet there.
  std::map<std::array<int, 3>, uint32_t> vertex_of;
  std::vector<Vec3> positions;
  auto coordinate = [&](int i) { return float(double(lo) + (double(hi) - double(lo)) * i / cells); };
  auto vertex = [&](std::array<int, 3> grid) {
    auto found = vertex_of.find(grid);
    if (found != vertex_of.end()) return found->second;
    positions.push_back({coordinate(grid[0]), coordinate(grid[1]), coordinate(grid[2])});
    return vertex_of[grid] = uint32_t(positions.size() - 1);
  };
  std::vector<uint32_t> indices;
  for (int axis = 0; axis < 3; ++axis) {
    const int u_axis = (axis + 1) % 3, v_axis = (axis + 2) % 3;
    for (int side = 0; side <= cells; side += cells) {
      for (int i = 0; i < cells; ++i) {
        for (int j = 0; j < cells; ++j) {
          std::array<uint32_t, 4> corner;
          for (int k = 0; k < 4; ++k) {
            std::array<int, 3> grid;
            grid[axis] = side;
            grid[u_axis] = i + (k == 1 || k == 2);
            grid[v_axis] = j + (k >= 2);
            corner[k] = vertex(grid);
          }
          indices.insert(indices.end(), {corner[0], corner[1], corner[2], corner[0], corner[2], corner[3]});
        }
      }
    }
  }
  return make_scene(std::move(positions), std::move(indices));
}

Scene transformed(const Scene& scene, double scale, const Vec3& offset) {
  Scene result = scene;
  for (Vec3& p : result.positions) {
    p = {float(double(p.x) * scale + offset.x), float(double(p.y) * scale + offset.y),
         float(double(p.z) * scale + offset.z)};
  }
  result.content_hash = compute_content_hash(result);
  result.geometry_hash = compute_geometry_hash(result);
  return result;
}

std::vector<std::pair<uint32_t, uint32_t>> mesh_edges(const Scene& scene) {
  std::vector<std::pair<uint32_t, uint32_t>> edges;
  for (size_t t = 0; t < scene.triangle_count(); ++t) {
    for (int k = 0; k < 3; ++k) {
      edges.push_back(std::minmax(scene.indices[3 * t + k], scene.indices[3 * t + (k + 1) % 3]));
    }
  }
  std::sort(edges.begin(), edges.end());
  edges.erase(std::unique(edges.begin(), edges.end()), edges.end());
  return edges;
}

std::vector<float> split_positions(const KdTree& tree, int axis) {
  std::vector<float> splits;
  for (const KdNode& node : tree.nodes) {
    if (!kd_node_is_leaf(node) && int(kd_node_axis(node)) == axis) splits.push_back(kd_node_split(node));
  }
  std::sort(splits.begin(), splits.end());
  splits.erase(std::unique(splits.begin(), splits.end()), splits.end());
  return splits;
}

std::string obj_mesh(const Scene& mesh, const std::string& material, size_t vertices_before) {
  std::string text = "usemtl " + material + "\n";
  char line[128];
  for (const Vec3& p : mesh.positions) {
    std::snprintf(line, sizeof line, "v %.9g %.9g %.9g\n", p.x, p.y, p.z);
    text += line;
  }
  for (size_t t = 0; t < mesh.triangle_count(); ++t) {
    std::snprintf(line, sizeof line, "f %zu %zu %zu\n", vertices_before + mesh.indices[3 * t] + 1,
                  vertices_before + mesh.indices[3 * t + 1] + 1, vertices_before + mesh.indices[3 * t + 2] + 1);
    text += line;
  }
  return text;
}

std::string white_and_light_mtl(float radiance) {
  char text[256];
  std::snprintf(text, sizeof text, "newmtl white\nKd 0.8 0.8 0.8\n\nnewmtl light\nKd 0 0 0\nKe %g %g %g\n", radiance,
                radiance, radiance);
  return text;
}

void write_obj(const std::string& path, const std::string& obj, const std::string& mtl) {
  const std::filesystem::path mtl_path = std::filesystem::path(path).replace_extension(".mtl");
  if (!mtl.empty()) std::ofstream(mtl_path) << mtl;
  std::ofstream out(path);
  if (!mtl.empty()) out << "mtllib " << mtl_path.filename().string() << "\n";
  out << obj;
  if (!out) throw std::runtime_error("cannot write " + path);
}

}  // namespace kdray::test
