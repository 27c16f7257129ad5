#include <icosphere.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <map>
#include <utility>

namespace kdray::test {

IcosphereMesh icosphere_mesh(int subdivisions, Vec3 centre, float radius) {
  const double g = (1.0 + std::sqrt(5.0)) / 2.0;
  std::vector<std::array<double, 3>> points = {{-1, g, 0}, {1, g, 0}, {-1, -g, 0}, {1, -g, 0}, {0, -1, g}, {0, 1, g},
                                               {0, -1, -g}, {0, 1, -g}, {g, 0, -1}, {g, 0, 1}, {-g, 0, -1}, {-g, 0, 1}};
  std::vector<uint32_t> faces = {0, 11, 5, 0, 5, 1, 0, 1, 7, 0, 7, 10, 0, 10, 11, 1, 5, 9, 5, 11, 4, 11, 10, 2,
                                 10, 7, 6, 7, 1, 8, 3, 9, 4, 3, 4, 2, 3, 2, 6, 3, 6, 8, 3, 8, 9, 4, 9, 5, 2, 4, 11,
                                 6, 2, 10, 8, 6, 7, 9, 8, 1};
  for (auto& p : points) {
    const double length = std::sqrt(p[0] * p[0] + p[1] * p[1] + p[2] * p[2]);
    for (double& x : p) x /= length;
  }
  for (int level = 0; level < subdivisions; ++level) {
    std::map<std::pair<uint32_t, uint32_t>, uint32_t> midpoints;
    auto midpoint = [&](uint32_t a, uint32_t b) {
      const auto key = std::minmax(a, b);
      auto found = midpoints.find(key);
      if (found != midpoints.end()) return found->second;
      std::array<double, 3> m;
      double length = 0;
      for (int k = 0; k < 3; ++k) {
        m[k] = 0.5 * (points[a][k] + points[b][k]);
        length += m[k] * m[k];
      }
      for (double& x : m) x /= std::sqrt(length);
      points.push_back(m);
      return midpoints[key] = static_cast<uint32_t>(points.size() - 1);
    };
    std::vector<uint32_t> finer;
    for (size_t f = 0; f < faces.size(); f += 3) {
      const uint32_t a = faces[f], b = faces[f + 1], c = faces[f + 2];
      const uint32_t ab = midpoint(a, b), bc = midpoint(b, c), ca = midpoint(c, a);
      finer.insert(finer.end(), {a, ab, ca, b, bc, ab, c, ca, bc, ab, bc, ca});
    }
    faces = std::move(finer);
  }
  IcosphereMesh mesh;
  for (const auto& p : points)
    mesh.positions.push_back({static_cast<float>(centre.x + radius * p[0]), static_cast<float>(centre.y + radius * p[1]),
                               static_cast<float>(centre.z + radius * p[2])});
  mesh.indices = std::move(faces);
  return mesh;
}

Scene mesh_scene(std::vector<Vec3> positions, std::vector<uint32_t> indices) {
  Scene scene;
  scene.positions = std::move(positions);
  scene.indices = std::move(indices);
  scene.material_ids.assign(scene.triangle_count(), 0);
  scene.materials.push_back(Material{});
  scene.content_hash = compute_content_hash(scene);
  scene.geometry_hash = compute_geometry_hash(scene);
  return scene;
}

Scene icosphere_scene(int subdivisions, Vec3 centre, float radius) {
  IcosphereMesh mesh = icosphere_mesh(subdivisions, centre, radius);
  return mesh_scene(std::move(mesh.positions), std::move(mesh.indices));
}

}  // namespace kdray::test
