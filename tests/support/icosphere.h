// The test suites' one icosphere: an icosahedron subdivided `subdivisions` times (each
// triangle into four), vertices projected onto the sphere in double and rounded once to float.
// Midpoints are shared between neighbouring triangles, so the mesh is closed by construction.
#pragma once

#include <kdray/scene.h>

#include <cstdint>
#include <vector>

namespace kdray::test {

struct IcosphereMesh {
  std::vector<Vec3> positions;
  std::vector<uint32_t> indices;  // 3 per triangle, counter-clockwise seen from outside
};

IcosphereMesh icosphere_mesh(int subdivisions, Vec3 centre, float radius);

// A scene of these triangles with one default material, its content and geometry hashes
// computed: ready for build_kdtree and write_scene.
Scene mesh_scene(std::vector<Vec3> positions, std::vector<uint32_t> indices);

// The icosphere as such a scene.
Scene icosphere_scene(int subdivisions, Vec3 centre, float radius);

}  // namespace kdray::test
