#include <kdray/scene_file.h>

#include <kdray/container_file.h>
#include <kdray/error.h>
#include <kdray/huge_pages.h>
#include <kdray/tangents.h>

#include "scene_encoding.h"
#include "scene_hash.h"

#include <algorithm>
#include <cmath>
#include <optional>

namespace kdray {
namespace {

using namespace format;

constexpr uint64_t kKnownFlags =
    kSceneHasNormals | kSceneHasUVs | kSceneHasTextures | kSceneHasEmissive | kSceneHasLights | kSceneHasTangents;

bool finite(const Vec3& v) { return std::isfinite(v.x) && std::isfinite(v.y) && std::isfinite(v.z); }

bool any_at_least(const std::vector<uint32_t>& values, uint64_t limit) {
  uint32_t largest = 0;
  for (uint32_t value : values) largest = std::max(largest, value);
  return !values.empty() && largest >= limit;
}

uint64_t first_at_least(const std::vector<uint32_t>& values, uint64_t limit) {
  return uint64_t(std::find_if(values.begin(), values.end(), [&](uint32_t v) { return v >= limit; }) - values.begin());
}

// Whether each array is consistent with the mesh it belongs to; false means the scene in
// memory (on write) or the file (on read) cannot be trusted.
std::string first_inconsistency(const Scene& scene) {
  const uint64_t vertices = scene.positions.size();
  const uint64_t triangles = scene.indices.size() / 3;
  if (scene.indices.size() % 3 != 0) return "the index count is not a multiple of 3";
  if (scene.material_ids.size() != triangles)
    return std::to_string(scene.material_ids.size()) + " material ids for " + std::to_string(triangles) + " triangles";
  if (!scene.normals.empty() && scene.normals.size() != vertices)
    return std::to_string(scene.normals.size()) + " normals for " + std::to_string(vertices) + " vertices";
  if (!scene.uvs.empty() && scene.uvs.size() != vertices)
    return std::to_string(scene.uvs.size()) + " UVs for " + std::to_string(vertices) + " vertices";
  if (!scene.tangents.empty() && scene.tangents.size() != vertices)
    return std::to_string(scene.tangents.size()) + " tangents for " + std::to_string(vertices) + " vertices";
  if (!scene.tangents.empty() && scene.uvs.empty()) return "tangents without UVs";
  for (size_t v = 0; v < scene.tangents.size(); ++v) {
    const Tangent& t = scene.tangents[v];
    if (!finite({t.x, t.y, t.z}) || !(std::abs(t.x * t.x + t.y * t.y + t.z * t.z - 1) < 1e-3f) ||
        (t.w != 1 && t.w != -1))
      return "tangent " + std::to_string(v) + " is not a unit vector with handedness +1 or -1";
  }
  // A branch-free maximum first (it vectorises, and loading 1M triangles is close to a file
  // read), then a search for the culprit only when there is one.
  if (any_at_least(scene.indices, vertices)) {
    const uint64_t i = first_at_least(scene.indices, vertices);
    return "triangle " + std::to_string(i / 3) + " refers to vertex " + std::to_string(scene.indices[i]) + " of " +
           std::to_string(vertices);
  }
  if (any_at_least(scene.material_ids, scene.materials.size())) {
    const uint64_t t = first_at_least(scene.material_ids, scene.materials.size());
    return "triangle " + std::to_string(t) + " has material " + std::to_string(scene.material_ids[t]) + " of " +
           std::to_string(scene.materials.size());
  }
  for (uint32_t triangle : scene.emissive_triangles)
    if (triangle >= triangles) return "emissive triangle " + std::to_string(triangle) + " does not exist";
  for (const Material& material : scene.materials)
    for (int32_t texture : {material.diffuse_texture, material.metal_rough_texture, material.normal_texture,
                            material.emissive_texture})
      if (texture < -1 || texture >= int64_t(scene.textures.size()))
        return "material '" + material.name + "' refers to texture " + std::to_string(texture) + " of " +
               std::to_string(scene.textures.size());
  for (const Light& light : scene.lights) {
    const float length2 = light.direction.x * light.direction.x + light.direction.y * light.direction.y +
                          light.direction.z * light.direction.z;
    if (!finite(light.position) || !finite(light.color) || !(std::abs(length2 - 1) < 1e-3f) ||
        !(light.color.x >= 0 && light.color.y >= 0 && light.color.z >= 0) ||
        !(light.inner_cone_radians >= 0 && light.inner_cone_radians <= light.outer_cone_radians &&
          light.outer_cone_radians <= 3.14159265f))
      return "light '" + light.name + "' is not finite, has no unit direction, a negative colour or bad cone angles";
  }
  for (const Camera& camera : scene.cameras) {
    const bool orthographic = camera.projection == Projection::Orthographic;
    if (!(camera.aspect_ratio >= 0 && std::isfinite(camera.aspect_ratio)) ||
        (orthographic && !(camera.orthographic_half_height > 0 && std::isfinite(camera.orthographic_half_height))))
      return "camera '" + camera.name + "' has a negative or non-finite aspect ratio or orthographic height";
  }
  for (const Texture& texture : scene.textures)
    if (texture.rgba.size() != uint64_t(texture.width) * texture.height * 4)
      return "texture '" + texture.name + "' has the wrong pixel count";
  return {};
}

uint64_t flags_of(const Scene& scene) {
  uint64_t flags = 0;
  if (!scene.normals.empty()) flags |= kSceneHasNormals;
  if (!scene.uvs.empty()) flags |= kSceneHasUVs;
  if (!scene.textures.empty()) flags |= kSceneHasTextures;
  if (!scene.emissive_triangles.empty()) flags |= kSceneHasEmissive;
  if (!scene.lights.empty()) flags |= kSceneHasLights;
  if (!scene.tangents.empty()) flags |= kSceneHasTangents;
  return flags;
}

template <typename T>
SectionData array_section(uint32_t id, const std::vector<T>& array) {
  return {id, array.data(), array.size() * sizeof(T)};
}

SectionData text_section(uint32_t id, const std::string& bytes) { return {id, bytes.data(), bytes.size()}; }

// Copies each section of a mapped file into the scene, sizing it from the section size
// (already checked against the file size by the container reader). Copied from the mapping,
// the arrays are written once, not zero-filled first. With Sections::InfoOnly every section's
// size is checked but only the scene info is copied (read_scene_geometry).
class SectionCollector {
 public:
  enum class Sections { All, InfoOnly };
  SectionCollector(const std::string& path, Scene& scene, Sections kept = Sections::All)
      : path_(path), scene_(scene), kept_(kept) {}

  void take(uint32_t id, const char* bytes, uint64_t size) {
    if (id >= seen_.size()) return;  // a section a newer writer added: not ours to read
    if (seen_[id]) throw Error(path_, "section " + std::to_string(id) + " appears twice");
    seen_[id] = true;
    keep_ = kept_ == Sections::All || id == kSceneInfo;
    if (id == kSceneIndices) triangles = size / 12;
    switch (id) {
      case kScenePositions: return copy(scene_.positions, bytes, size, sizeof(Vec3), "positions");
      case kSceneIndices: return copy(scene_.indices, bytes, size, 12, "indices");
      case kSceneMaterialIds: return copy(scene_.material_ids, bytes, size, sizeof(uint32_t), "material ids");
      case kSceneNormals: return copy(scene_.normals, bytes, size, sizeof(Vec3), "normals");
      case kSceneUVs: return copy(scene_.uvs, bytes, size, sizeof(scene_.uvs[0]), "UVs");
      case kSceneEmissive: return copy(scene_.emissive_triangles, bytes, size, sizeof(uint32_t), "emissive triangles");
      case kSceneMaterials: return copy(materials, bytes, size, 1, "materials");
      case kSceneCameras: return copy(cameras, bytes, size, 1, "cameras");
      case kSceneTextures: return copy(textures, bytes, size, 1, "textures");
      case kSceneInfo: return copy(info, bytes, size, 1, "scene info");
      case kSceneLights: return copy(lights, bytes, size, 1, "lights");
      case kSceneTangents: return copy(scene_.tangents, bytes, size, sizeof(scene_.tangents[0]), "tangents");
      default: return;
    }
  }

  bool has(uint32_t id) const { return seen_[id]; }

  std::vector<char> materials, cameras, textures, info, lights;
  uint64_t triangles = 0;  // of the indices section

 private:
  template <typename T>
  void copy(std::vector<T>& array, const char* bytes, uint64_t size, uint64_t unit, const char* what) {
    if (size % unit != 0)
      throw Error(path_, std::string(what) + " section size " + std::to_string(size) + " is not a multiple of " +
                             std::to_string(unit));
    if (!keep_) return;
    const T* first = reinterpret_cast<const T*>(bytes);
    const size_t count = size / sizeof(T);
    // A million-triangle scene's arrays are thousands of 4 KiB pages, each a fault when filled.
    array.reserve(count);
    advise_huge_pages(array.data(), count * sizeof(T));
    array.assign(first, first + count);
  }

  std::string path_;
  Scene& scene_;
  const Sections kept_;
  bool keep_ = true;  // whether the section being taken is copied
  std::vector<bool> seen_ = std::vector<bool>(kSceneTangents + 1, false);
};

// Checks the sections a file has (`has`) against what every scene needs and its header's flags,
// and the header's own fields (the checksum covers the payload only).
template <typename Has>
void check_section_set(const std::string& path, const FileHeader& header, const Has& has) {
  for (uint32_t required : {kScenePositions, kSceneIndices, kSceneMaterialIds, kSceneMaterials, kSceneCameras, kSceneInfo})
    if (!has(required)) throw Error(path, "required section " + std::to_string(required) + " is missing");
  const uint64_t flags = header.flags;
  if (flags & ~kKnownFlags) throw Error(path, "unknown flag bits in the header");
  const std::pair<uint64_t, uint32_t> optional_sections[] = {
      {kSceneHasNormals, kSceneNormals}, {kSceneHasUVs, kSceneUVs},
      {kSceneHasTextures, kSceneTextures}, {kSceneHasEmissive, kSceneEmissive}, {kSceneHasLights, kSceneLights},
      {kSceneHasTangents, kSceneTangents}};
  for (const auto& [flag, section] : optional_sections)
    if (bool(flags & flag) != has(section))
      throw Error(path, "header flags disagree with the sections present (section " + std::to_string(section) + ")");
  if (header.reserved0 != 0 || header.reserved1 != 0) throw Error(path, "reserved header fields are not zero");
}

// The header's hash is outside the checksum; its copy in scene info is inside. Recomputing it
// would cost another pass over the arrays, and the checksummed copy is what was written.
void check_content_hash(const std::string& path, const FileHeader& header, const encoding::SceneInfo& info) {
  if (info.content_hash != header.content_hash)
    throw Error(path, "the content hash in the header (" + hash_hex(header.content_hash) +
                          ") does not match the one recorded in the scene info (" + hash_hex(info.content_hash) + ")");
}

// The scene of a mapped file, copied out of it and checked throughout.
Scene scene_of(const MappedContainer& file, const std::string& path) {
  Scene scene;
  SectionCollector collector(path, scene);
  const ContainerContents& contents = file.contents;
  for (const format::SectionEntry& section : contents.sections)
    collector.take(section.id, file.bytes + section.offset, section.size);
  check_section_set(path, contents.header, [&](uint32_t id) { return collector.has(id); });

  scene.materials = encoding::decode_materials(path, collector.materials, contents.header.version);
  scene.cameras = encoding::decode_cameras(path, collector.cameras, contents.header.version);
  if (collector.has(kSceneTextures)) scene.textures = encoding::decode_textures(path, collector.textures);
  if (collector.has(kSceneLights)) scene.lights = encoding::decode_lights(path, collector.lights);
  encoding::SceneInfo info = encoding::decode_scene_info(path, collector.info, contents.header.version);
  scene.import_stats = std::move(info.import_stats);

  const std::string problem = first_inconsistency(scene);
  if (!problem.empty()) throw Error(path, "inconsistent scene: " + problem);
  // Files older than version 5 have no tangents: computed here, on the vertices the file's
  // hashes and k-d tree describe.
  if (scene.tangents.empty()) scene.tangents = tangents_on_vertices(scene);
  check_content_hash(path, contents.header, info);
  scene.content_hash = info.content_hash;
  // Older files did not record it: one pass over the two arrays.
  scene.geometry_hash = contents.header.version >= kSceneGeometryHashVersion ? info.geometry_hash
                                                                            : compute_geometry_hash(scene);
  return scene;
}

}  // namespace

void write_scene(const std::string& path, const Scene& scene) {
  const std::string problem = first_inconsistency(scene);
  if (!problem.empty()) throw Error(path, "refusing to write an inconsistent scene: " + problem);
  const encoding::EncodedParts parts = encoding::encode_parts(scene);
  const uint64_t content_hash = encoding::content_hash(scene, parts);
  const std::string info =
      encoding::encode_scene_info({content_hash, compute_geometry_hash(scene), scene.import_stats});

  std::vector<SectionData> sections = {
      array_section(kScenePositions, scene.positions),
      array_section(kSceneIndices, scene.indices),
      array_section(kSceneMaterialIds, scene.material_ids),
  };
  if (!scene.normals.empty()) sections.push_back(array_section(kSceneNormals, scene.normals));
  if (!scene.uvs.empty()) sections.push_back(array_section(kSceneUVs, scene.uvs));
  if (!scene.tangents.empty()) sections.push_back(array_section(kSceneTangents, scene.tangents));
  sections.push_back(text_section(kSceneMaterials, parts.materials));
  sections.push_back(text_section(kSceneCameras, parts.cameras));
  if (!scene.textures.empty()) sections.push_back(text_section(kSceneTextures, parts.textures));
  if (!scene.emissive_triangles.empty()) sections.push_back(array_section(kSceneEmissive, scene.emissive_triangles));
  if (!scene.lights.empty()) sections.push_back(text_section(kSceneLights, parts.lights));
  sections.push_back(text_section(kSceneInfo, info));

  ContainerHeaderInfo header{kSceneMagic, kSceneVersion, flags_of(scene), content_hash};
  write_container(path, header, sections);
}

Scene read_scene(const std::string& path) {
  // The file is mapped and its sections copied into the scene and checked while the checksum is
  // computed; the scene is returned only once both pass.
  Scene scene;
  map_container(path, kSceneMagic, kSceneVersion, "kdscene", [&](const MappedContainer& file) {
    scene = scene_of(file, path);
  });
  return scene;
}

SceneGeometry read_scene_geometry(const std::string& path) {
  SceneGeometry geometry;
  bool whole_scene_needed = false;
  map_container(path, kSceneMagic, kSceneVersion, "kdscene", [&](const MappedContainer& file) {
    const ContainerContents& contents = file.contents;
    Scene arrays_not_read;
    SectionCollector collector(path, arrays_not_read, SectionCollector::Sections::InfoOnly);
    for (const format::SectionEntry& section : contents.sections)
      collector.take(section.id, file.bytes + section.offset, section.size);
    check_section_set(path, contents.header, [&](uint32_t id) { return collector.has(id); });
    const encoding::SceneInfo info = encoding::decode_scene_info(path, collector.info, contents.header.version);
    check_content_hash(path, contents.header, info);
    whole_scene_needed = contents.header.version < kSceneGeometryHashVersion;
    geometry = {info.geometry_hash, collector.triangles};
  });
  if (whole_scene_needed) {  // no hash recorded: computed from the arrays, which are read for it
    const Scene scene = read_scene(path);
    geometry = geometry_of(scene);
  }
  return geometry;
}

SceneFileSummary peek_scene(const std::string& path) {
  const ContainerContents contents = peek_container(path, kSceneMagic, kSceneVersion, "kdscene");
  return {contents.header.version, contents.header.flags, contents.header.content_hash,
          contents.header.payload_size + sizeof(FileHeader)};
}

}  // namespace kdray
