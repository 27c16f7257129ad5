// OBJ import through tinyobjloader. Polygons are read untriangulated and ear-clipped here
// (polygon.cpp): the library's own triangulation is a fan, wrong for concave faces.
#include "importers.h"

#include "material_mapping.h"
#include "mesh_builder.h"
#include "polygon.h"

#include <kdray/error.h>

#include <tiny_obj_loader.h>

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <limits>
#include <filesystem>
#include <fstream>
#include <map>
#include <unordered_map>

namespace kdray {
namespace {

// One OBJ corner (v/vt/vn); corners that agree on all three share a scene vertex.
struct CornerKey {
  int position, uv, normal;
  bool operator==(const CornerKey& other) const {
    return position == other.position && uv == other.uv && normal == other.normal;
  }
};
struct CornerKeyHash {
  size_t operator()(const CornerKey& key) const {
    return (size_t(uint32_t(key.position)) * 0x9E3779B97F4A7C15ull) ^ (size_t(uint32_t(key.uv)) * 0xC2B2AE3D27D4EB4Full) ^
           (size_t(uint32_t(key.normal)) * 0x165667B19E3779F9ull);
  }
};

SourceMaterial source_material(const tinyobj::material_t& mtl) {
  SourceMaterial source;
  source.name = mtl.name;
  source.diffuse = {mtl.diffuse[0], mtl.diffuse[1], mtl.diffuse[2]};
  source.specular = {mtl.specular[0], mtl.specular[1], mtl.specular[2]};
  source.emission = {mtl.emission[0], mtl.emission[1], mtl.emission[2]};
  source.shininess = mtl.shininess;
  source.ior = mtl.ior;
  source.opacity = mtl.dissolve;
  source.illum = mtl.illum;
  source.diffuse_texture = mtl.diffuse_texname;
  source.normal_texture = mtl.normal_texname;  // MTL `norm`: a tangent-space normal map
  return source;
}

struct ObjData {
  tinyobj::attrib_t attrib;
  std::vector<tinyobj::shape_t> shapes;
  std::vector<tinyobj::material_t> materials;
};

// Finds `mtllib` files relative to the OBJ, and failing that by their bare name beside it:
// exporters sometimes write a path relative to some other root (CornellBox-Glossy.obj).
class MtlReader : public tinyobj::MaterialReader {
 public:
  explicit MtlReader(std::filesystem::path obj_directory) : obj_directory_(std::move(obj_directory)) {}

  bool operator()(const std::string& name, std::vector<tinyobj::material_t>* materials,
                  std::map<std::string, int>* index_of, std::string* warnings, std::string* errors) override {
    const std::filesystem::path candidates[] = {obj_directory_ / name,
                                                obj_directory_ / std::filesystem::path(name).filename()};
    for (const std::filesystem::path& candidate : candidates) {
      std::ifstream stream(candidate);
      if (!stream) continue;
      tinyobj::LoadMtl(index_of, materials, &stream, warnings, errors);  // replaces *warnings
      if (candidate != candidates[0])
        *warnings += "material file " + name + " not found; using " + candidate.filename().string() + " beside the OBJ\n";
      directory_ = candidate.parent_path();
      return true;
    }
    *warnings += "material file " + name + " not found\n";
    return false;
  }

  // Where map_Kd paths are resolved: the directory of the material file that was read.
  const std::filesystem::path& directory() const { return directory_.empty() ? obj_directory_ : directory_; }

 private:
  std::filesystem::path obj_directory_;
  std::filesystem::path directory_;
};

// tinyobjloader reads `nan` and `inf` coordinates as 0, which would turn a broken vertex into
// a plausible one. This pass finds the `v` records with a non-finite coordinate (as strtod
// reads them) and makes those vertices NaN again, so the mesh builder drops their triangles.
void restore_non_finite_vertices(const std::string& path, tinyobj::attrib_t& attrib) {
  std::ifstream file(path, std::ios::binary);
  std::string line;
  size_t vertex = 0;
  while (std::getline(file, line)) {
    const size_t start = line.find_first_not_of(" \t");
    if (start == std::string::npos || line[start] != 'v' || start + 1 >= line.size() ||
        (line[start + 1] != ' ' && line[start + 1] != '\t'))
      continue;
    const char* cursor = line.c_str() + start + 1;
    bool finite = true;
    for (int axis = 0; axis < 3; ++axis) {
      char* end = nullptr;
      const double value = std::strtod(cursor, &end);
      if (end == cursor) break;
      finite = finite && std::isfinite(value);
      cursor = end;
    }
    if (!finite && 3 * vertex + 2 < attrib.vertices.size())
      for (int axis = 0; axis < 3; ++axis) attrib.vertices[3 * vertex + axis] = std::numeric_limits<float>::quiet_NaN();
    ++vertex;
  }
}

class ObjConverter {
 public:
  ObjConverter(const std::string& path, const ObjData& obj, const std::filesystem::path& texture_directory, Scene& scene)
      : path_(path), attrib_(obj.attrib), scene_(scene), builder_(scene.import_stats) {
    TextureCache textures(scene);
    for (const tinyobj::material_t& mtl : obj.materials) {
      SourceMaterial source = source_material(mtl);
      Material material = map_material(source);
      if (!source.diffuse_texture.empty())
        material.diffuse_texture = textures.from_file((texture_directory / source.diffuse_texture).string(), source.diffuse_texture);
      if (!source.normal_texture.empty())
        material.normal_texture = textures.from_file((texture_directory / source.normal_texture).string(), source.normal_texture);
      scene.materials.push_back(material);
    }
  }

  void add_shape(const tinyobj::shape_t& shape) {
    const tinyobj::mesh_t& mesh = shape.mesh;
    size_t first_corner = 0;
    std::vector<uint32_t> polygon;
    std::vector<Vec3> corners;
    for (size_t face = 0; face < mesh.num_face_vertices.size(); ++face) {
      const size_t count = mesh.num_face_vertices[face];
      if (first_corner + count > mesh.indices.size()) throw Error(path_, "a face has more corners than the file lists");
      polygon.clear();
      corners.clear();
      for (size_t i = 0; i < count; ++i) {
        polygon.push_back(vertex_for(mesh.indices[first_corner + i]));
        corners.push_back(builder_.position(polygon.back()));
      }
      first_corner += count;
      if (count == 1) ++scene_.import_stats.ignored_points;
      if (count == 2) ++scene_.import_stats.ignored_lines;
      const uint32_t material = material_for(face < mesh.material_ids.size() ? mesh.material_ids[face] : -1);
      for (const auto& triangle : triangulate_polygon(corners))
        builder_.add_triangle(polygon[triangle[0]], polygon[triangle[1]], polygon[triangle[2]], material);
    }
    scene_.import_stats.ignored_lines += shape.lines.num_line_vertices.size();
    scene_.import_stats.ignored_points += shape.points.indices.size();
  }

  void finish() { builder_.finish(scene_); }

 private:
  uint32_t vertex_for(const tinyobj::index_t& index) {
    const CornerKey key{index.vertex_index, index.texcoord_index, index.normal_index};
    auto found = vertex_of_.find(key);
    if (found != vertex_of_.end()) return found->second;
    const size_t vertex_count = attrib_.vertices.size() / 3;
    if (index.vertex_index < 0 || size_t(index.vertex_index) >= vertex_count)
      throw Error(path_, "a face refers to a vertex that does not exist (number " +
                             std::to_string(int64_t(index.vertex_index) + 1) + " of " + std::to_string(vertex_count) + ")");
    const float* v = &attrib_.vertices[3 * size_t(index.vertex_index)];
    std::optional<Vec3> normal;
    if (index.normal_index >= 0 && size_t(index.normal_index) < attrib_.normals.size() / 3) {
      const float* n = &attrib_.normals[3 * size_t(index.normal_index)];
      normal = Vec3{n[0], n[1], n[2]};
    }
    std::optional<Vec2> uv;
    if (index.texcoord_index >= 0 && size_t(index.texcoord_index) < attrib_.texcoords.size() / 2) {
      const float* t = &attrib_.texcoords[2 * size_t(index.texcoord_index)];
      uv = Vec2{t[0], t[1]};
    }
    const uint32_t vertex = builder_.add_vertex({v[0], v[1], v[2]}, normal, uv);
    vertex_of_.emplace(key, vertex);
    return vertex;
  }

  // Faces without a (known) material share one default diffuse material, added when first used.
  uint32_t material_for(int material_id) {
    if (material_id >= 0 && size_t(material_id) < scene_.materials.size()) return uint32_t(material_id);
    if (default_material_ < 0) {
      default_material_ = int64_t(scene_.materials.size());
      Material fallback;
      fallback.name = "default";
      scene_.materials.push_back(fallback);
    }
    return uint32_t(default_material_);
  }

  std::string path_;
  const tinyobj::attrib_t& attrib_;
  Scene& scene_;
  MeshBuilder builder_;
  std::unordered_map<CornerKey, uint32_t, CornerKeyHash> vertex_of_;
  int64_t default_material_ = -1;
};

}  // namespace

Scene import_with_tinyobj(const std::string& path) {
  std::ifstream file(path, std::ios::binary);
  if (!file) throw Error(path, "cannot open");
  Scene scene;
  scene.import_stats.importer = "tinyobj";
  ObjData obj;
  MtlReader mtl_reader(std::filesystem::path(path).parent_path());
  std::string warnings, error;
  if (!tinyobj::LoadObj(&obj.attrib, &obj.shapes, &obj.materials, &warnings, &error, &file, &mtl_reader,
                        /*triangulate=*/false, /*default_vcols_fallback=*/false)) {
    while (!error.empty() && (error.back() == '\n' || error.back() == '\r')) error.pop_back();
    throw Error(path, "tinyobjloader cannot read it: " + (error.empty() ? std::string("unknown error") : error));
  }
  for (size_t start = 0, end; start < warnings.size(); start = end + 1) {
    end = std::min(warnings.find('\n', start), warnings.size());
    if (end > start) scene.import_stats.warnings.push_back("tinyobjloader: " + warnings.substr(start, end - start));
  }
  restore_non_finite_vertices(path, obj.attrib);
  ObjConverter converter(path, obj, mtl_reader.directory(), scene);
  for (const tinyobj::shape_t& shape : obj.shapes) converter.add_shape(shape);
  converter.finish();
  return scene;
}

}  // namespace kdray
