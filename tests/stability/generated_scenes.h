// Scenes generated for the numerical-stability suite: closed meshes, split-plane-aligned boxes,
// translated and scaled copies, and OBJ text for the tool-level tests.
#pragma once

#include <kdray/kdtree.h>
#include <kdray/scene.h>

#include <icosphere.h>

#include <string>
#include <vector>

namespace kdray::test {

// A scene of one diffuse material with its content hash computed, ready for build_kdtree.
Scene make_scene(std::vector<Vec3> positions, std::vector<uint32_t> indices);

// Triangles of `extra` appended to `scene` (vertices re-indexed), hash recomputed.
void append_mesh(Scene& scene, const Scene& extra);

// A closed axis-aligned box [lo, hi]^3 whose faces are `cells` x `cells` grids of quads (two
// triangles each), so grid lines give the builder many candidate split planes in the faces.
Scene make_grid_box(float lo, float hi, int cells);

// Every position multiplied by `scale`, then `offset` added (in double, rounded once to float).
Scene transformed(const Scene& scene, double scale, const Vec3& offset);

// Unique undirected edges of an indexed mesh, as vertex-index pairs.
std::vector<std::pair<uint32_t, uint32_t>> mesh_edges(const Scene& scene);

// Split positions of the tree's inner nodes on `axis`, sorted and unique.
std::vector<float> split_positions(const KdTree& tree, int axis);

// OBJ lines of `mesh` with material `material`; vertex numbers continue after `vertices_before`
// vertices already written. Coordinates are printed with 9 significant digits (exact for float).
std::string obj_mesh(const Scene& mesh, const std::string& material, size_t vertices_before);

// An MTL with "white" (Lambertian, albedo 0.8) and "light" (emitting `radiance` in R, G, B).
std::string white_and_light_mtl(float radiance);

// Writes `path` and, when `mtl` is not empty, <stem>.mtl beside it, referenced by the OBJ.
void write_obj(const std::string& path, const std::string& obj, const std::string& mtl = "");

}  // namespace kdray::test
