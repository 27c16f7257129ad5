#include "scene_encoding.h"

#include <kdray/error.h>
#include <kdray/format.h>

#include <cereal/archives/portable_binary.hpp>

#include <sstream>

namespace kdray::encoding {
namespace {

// ---- writing ---------------------------------------------------------------------------

using OutputArchive = cereal::PortableBinaryOutputArchive;

void put_string(OutputArchive& archive, const std::string& text) {
  archive(cereal::make_size_tag(static_cast<cereal::size_type>(text.size())));
  archive(cereal::binary_data(text.data(), text.size()));
}

void put_vec3(OutputArchive& archive, const Vec3& v) { archive(v.x, v.y, v.z); }

void put(OutputArchive& archive, const Material& material) {
  put_string(archive, material.name);
  archive(static_cast<uint32_t>(material.type));
  put_vec3(archive, material.base_color);
  put_vec3(archive, material.emission);
  archive(material.roughness, material.ior, material.diffuse_texture);
  archive(material.metallic, material.alpha, static_cast<uint32_t>(material.alpha_mode), material.alpha_cutoff);
  archive(material.metal_rough_texture, material.normal_texture, material.emissive_texture);
}

void put(OutputArchive& archive, const Camera& camera) {
  put_string(archive, camera.name);
  put_vec3(archive, camera.position);
  put_vec3(archive, camera.target);
  put_vec3(archive, camera.up);
  archive(camera.vertical_fov_degrees);
  archive(camera.aspect_ratio, static_cast<uint32_t>(camera.projection), camera.orthographic_half_height);
}

void put(OutputArchive& archive, const Light& light) {
  put_string(archive, light.name);
  archive(static_cast<uint32_t>(light.type));
  put_vec3(archive, light.position);
  put_vec3(archive, light.direction);
  put_vec3(archive, light.color);
  archive(light.inner_cone_radians, light.outer_cone_radians);
}

void put(OutputArchive& archive, const Texture& texture) {
  put_string(archive, texture.name);
  archive(texture.width, texture.height);
  archive(cereal::make_size_tag(static_cast<cereal::size_type>(texture.rgba.size())));
  archive(cereal::binary_data(texture.rgba.data(), texture.rgba.size()));
}

void put(OutputArchive& archive, const ImportStats& stats) {
  put_string(archive, stats.source_file);
  put_string(archive, stats.importer);
  archive(stats.source_triangles, stats.dropped_degenerate, stats.dropped_non_finite, stats.ignored_points,
          stats.ignored_lines);
  archive(cereal::make_size_tag(static_cast<cereal::size_type>(stats.warnings.size())));
  for (const std::string& warning : stats.warnings) put_string(archive, warning);
}

template <typename T>
std::string encode_list(const std::vector<T>& items) {
  std::ostringstream stream(std::ios::binary);
  {
    OutputArchive archive(stream);
    archive(cereal::make_size_tag(static_cast<cereal::size_type>(items.size())));
    for (const T& item : items) put(archive, item);
  }
  return stream.str();
}

// ---- reading ---------------------------------------------------------------------------

// A read-only stream over bytes already in memory that knows how many bytes remain,
// so a damaged count is rejected before it turns into an allocation.
class ByteSource : public std::streambuf {
 public:
  explicit ByteSource(const std::vector<char>& bytes) {
    char* begin = const_cast<char*>(bytes.data());
    setg(begin, begin, begin + bytes.size());
  }
  uint64_t remaining() const { return static_cast<uint64_t>(egptr() - gptr()); }
};

class Decoder {
 public:
  Decoder(const std::string& path, const char* section, const std::vector<char>& bytes)
      : path_(path), section_(section), source_(bytes), stream_(&source_) {
    archive_ = std::make_unique<cereal::PortableBinaryInputArchive>(stream_);
  }

  template <typename... T>
  void get(T&... values) {
    (*archive_)(values...);
  }

  // An element count, checked against the bytes left: each element takes at least
  // `min_element_bytes` bytes.
  uint64_t get_count(uint64_t min_element_bytes) {
    cereal::size_type count = 0;
    (*archive_)(cereal::make_size_tag(count));
    if (count > source_.remaining() / min_element_bytes) fail("count " + std::to_string(count) + " exceeds its section");
    return count;
  }

  void get_bytes(void* data, uint64_t size) { (*archive_)(cereal::binary_data(static_cast<uint8_t*>(data), size)); }

  std::string get_string() {
    std::string text(get_count(1), '\0');
    get_bytes(text.data(), text.size());
    return text;
  }

  Vec3 get_vec3() {
    Vec3 v;
    get(v.x, v.y, v.z);
    return v;
  }

  void finish() {
    if (source_.remaining() != 0) fail(std::to_string(source_.remaining()) + " unexpected trailing bytes");
  }

  [[noreturn]] void fail(const std::string& what) const {
    throw Error(path_, std::string("malformed ") + section_ + " section: " + what);
  }

 private:
  std::string path_;
  const char* section_;
  ByteSource source_;
  std::istream stream_;
  std::unique_ptr<cereal::PortableBinaryInputArchive> archive_;
};

// Smallest encodings, used to bound counts: an empty string is its 8-byte size tag.
constexpr uint64_t kMinMaterialBytes = 8 + 4 + 24 + 4 + 4 + 4;
constexpr uint64_t kMinCameraBytes = 8 + 36 + 4;
constexpr uint64_t kMinTextureBytes = 8 + 8 + 8;
constexpr uint64_t kMinLightBytes = 8 + 4 + 36 + 8;

Light get_light(Decoder& decoder) {
  Light light;
  light.name = decoder.get_string();
  uint32_t type = 0;
  decoder.get(type);
  if (type > static_cast<uint32_t>(LightType::Directional)) decoder.fail("unknown light type " + std::to_string(type));
  light.type = static_cast<LightType>(type);
  light.position = decoder.get_vec3();
  light.direction = decoder.get_vec3();
  light.color = decoder.get_vec3();
  decoder.get(light.inner_cone_radians, light.outer_cone_radians);
  return light;
}

// Version 3 added the metallic-roughness type and the fields after diffuse_texture.
Material get_material(Decoder& decoder, uint32_t version) {
  Material material;
  material.name = decoder.get_string();
  uint32_t type = 0;
  decoder.get(type);
  const MaterialType last = version >= 3 ? MaterialType::MetallicRoughness : MaterialType::Dielectric;
  if (type > static_cast<uint32_t>(last)) decoder.fail("unknown material type " + std::to_string(type));
  material.type = static_cast<MaterialType>(type);
  material.base_color = decoder.get_vec3();
  material.emission = decoder.get_vec3();
  decoder.get(material.roughness, material.ior, material.diffuse_texture);
  if (version < 3) return material;
  uint32_t alpha_mode = 0;
  decoder.get(material.metallic, material.alpha, alpha_mode, material.alpha_cutoff);
  if (alpha_mode > static_cast<uint32_t>(AlphaMode::Blend)) decoder.fail("unknown alpha mode " + std::to_string(alpha_mode));
  material.alpha_mode = static_cast<AlphaMode>(alpha_mode);
  decoder.get(material.metal_rough_texture, material.normal_texture, material.emissive_texture);
  return material;
}

// Version 6 added the aspect ratio and the projection.
Camera get_camera(Decoder& decoder, uint32_t version) {
  Camera camera;
  camera.name = decoder.get_string();
  camera.position = decoder.get_vec3();
  camera.target = decoder.get_vec3();
  camera.up = decoder.get_vec3();
  decoder.get(camera.vertical_fov_degrees);
  if (version < format::kSceneCameraAspectVersion) return camera;
  uint32_t projection = 0;
  decoder.get(camera.aspect_ratio, projection, camera.orthographic_half_height);
  if (projection > static_cast<uint32_t>(Projection::Orthographic))
    decoder.fail("unknown camera projection " + std::to_string(projection));
  camera.projection = static_cast<Projection>(projection);
  return camera;
}

Texture get_texture(Decoder& decoder) {
  Texture texture;
  texture.name = decoder.get_string();
  decoder.get(texture.width, texture.height);
  const uint64_t bytes = decoder.get_count(1);
  if (bytes != uint64_t(texture.width) * texture.height * 4)
    decoder.fail("texture '" + texture.name + "' has " + std::to_string(bytes) + " bytes for " +
                 std::to_string(texture.width) + "x" + std::to_string(texture.height) + " RGBA pixels");
  texture.rgba.resize(bytes);
  decoder.get_bytes(texture.rgba.data(), texture.rgba.size());
  return texture;
}

template <typename T, typename GetOne>
std::vector<T> decode_list(const std::string& path, const char* section, const std::vector<char>& bytes,
                           uint64_t min_element_bytes, GetOne get_one) {
  try {
    Decoder decoder(path, section, bytes);
    std::vector<T> items(decoder.get_count(min_element_bytes));
    for (T& item : items) item = get_one(decoder);
    decoder.finish();
    return items;
  } catch (const cereal::Exception&) {
    throw Error(path, std::string("malformed ") + section + " section: it ends early");
  }
}

}  // namespace

EncodedParts encode_parts(const Scene& scene) {
  return {encode_materials(scene.materials), encode_textures(scene.textures), encode_cameras(scene.cameras),
          encode_lights(scene.lights)};
}

std::string encode_lights(const std::vector<Light>& lights) { return encode_list(lights); }
std::vector<Light> decode_lights(const std::string& path, const std::vector<char>& bytes) {
  return decode_list<Light>(path, "lights", bytes, kMinLightBytes, get_light);
}

std::string encode_materials(const std::vector<Material>& materials) { return encode_list(materials); }
std::string encode_cameras(const std::vector<Camera>& cameras) { return encode_list(cameras); }
std::string encode_textures(const std::vector<Texture>& textures) { return encode_list(textures); }

std::string encode_scene_info(const SceneInfo& info) {
  std::ostringstream stream(std::ios::binary);
  {
    OutputArchive archive(stream);
    archive(info.content_hash, info.geometry_hash);
    put(archive, info.import_stats);
  }
  return stream.str();
}

std::vector<Material> decode_materials(const std::string& path, const std::vector<char>& bytes, uint32_t version) {
  return decode_list<Material>(path, "materials", bytes, kMinMaterialBytes,
                               [version](Decoder& decoder) { return get_material(decoder, version); });
}
std::vector<Camera> decode_cameras(const std::string& path, const std::vector<char>& bytes, uint32_t version) {
  return decode_list<Camera>(path, "cameras", bytes, kMinCameraBytes,
                             [version](Decoder& decoder) { return get_camera(decoder, version); });
}
std::vector<Texture> decode_textures(const std::string& path, const std::vector<char>& bytes) {
  return decode_list<Texture>(path, "textures", bytes, kMinTextureBytes, get_texture);
}

SceneInfo decode_scene_info(const std::string& path, const std::vector<char>& bytes, uint32_t version) {
  try {
    Decoder decoder(path, "scene info", bytes);
    SceneInfo info;
    decoder.get(info.content_hash);
    if (version >= format::kSceneGeometryHashVersion) decoder.get(info.geometry_hash);
    ImportStats& stats = info.import_stats;
    stats.source_file = decoder.get_string();
    stats.importer = decoder.get_string();
    decoder.get(stats.source_triangles, stats.dropped_degenerate, stats.dropped_non_finite, stats.ignored_points,
                stats.ignored_lines);
    stats.warnings.resize(decoder.get_count(8));
    for (std::string& warning : stats.warnings) warning = decoder.get_string();
    decoder.finish();
    return info;
  } catch (const cereal::Exception&) {
    throw Error(path, "malformed scene info section: it ends early");
  }
}

}  // namespace kdray::encoding
