#include "gltf_facts.h"

#include <kdray/error.h>
#include <kdray/util.h>

#include <nlohmann/json.hpp>

#include <algorithm>
#include <cstdint>
#include <fstream>
#include <iterator>
#include <optional>

namespace kdray {
namespace {

constexpr uint32_t kGlbMagic = 0x46546C67;      // "glTF"
constexpr uint32_t kGlbJsonChunk = 0x4E4F534A;  // "JSON"
constexpr size_t kGlbHeaderBytes = 12, kGlbChunkHeaderBytes = 8;

// Extensions whose meaning kdray renders: punctual lights, emission strength, and transmission
// with its index of refraction (as smooth glass).
constexpr const char* kModelledExtensions[] = {"KHR_lights_punctual", "KHR_materials_emissive_strength",
                                               "KHR_materials_transmission", "KHR_materials_ior"};

uint32_t little_endian_u32(const std::string& bytes, size_t at) {
  uint32_t value = 0;
  for (int i = 3; i >= 0; --i) value = (value << 8) | uint8_t(bytes[at + i]);
  return value;
}

// The JSON text of a .gltf, or the JSON chunk of a version 2 .glb (its first chunk, by the
// specification), read without the binary chunk that follows it; nothing for a glTF 1.0 binary.
std::optional<std::string> json_text(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in) throw Error(path, "cannot open");
  std::string header(kGlbHeaderBytes + kGlbChunkHeaderBytes, '\0');
  in.read(header.data(), std::streamsize(header.size()));
  header.resize(size_t(in.gcount()));
  if (header.size() < 4 || little_endian_u32(header, 0) != kGlbMagic) {
    in.clear();
    in.seekg(0);
    return std::string((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  }
  if (header.size() < kGlbHeaderBytes + kGlbChunkHeaderBytes) throw Error(path, "a .glb shorter than its header");
  if (little_endian_u32(header, 4) != 2) return std::nullopt;
  if (little_endian_u32(header, kGlbHeaderBytes + 4) != kGlbJsonChunk)
    throw Error(path, "a .glb whose first chunk is not its JSON");
  in.seekg(0, std::ios::end);
  const uint64_t available = uint64_t(in.tellg()) - header.size();
  const uint64_t length = little_endian_u32(header, kGlbHeaderBytes);
  if (length > available) throw Error(path, "a .glb whose JSON chunk runs past the end of the file");
  std::string json(length, '\0');
  in.seekg(std::streamoff(header.size()));
  if (!in.read(json.data(), std::streamsize(length))) throw Error(path, "cannot read its JSON chunk");
  return json;
}

const nlohmann::json* member(const nlohmann::json& object, const char* name) {
  if (!object.is_object()) return nullptr;
  const auto found = object.find(name);
  return found == object.end() ? nullptr : &*found;
}

float number_or(const nlohmann::json& object, const char* name, float fallback) {
  const nlohmann::json* value = member(object, name);
  return value && value->is_number() ? value->get<float>() : fallback;
}

GltfCamera camera_of(const nlohmann::json& camera) {
  GltfCamera result;
  const nlohmann::json* type = member(camera, "type");
  result.orthographic = type && type->is_string() && type->get<std::string>() == "orthographic";
  if (result.orthographic) {
    const nlohmann::json empty = nlohmann::json::object();
    const nlohmann::json* extents = member(camera, "orthographic");
    result.xmag = number_or(extents ? *extents : empty, "xmag", 0);
    result.ymag = number_or(extents ? *extents : empty, "ymag", 0);
  } else if (const nlohmann::json* perspective = member(camera, "perspective")) {
    result.yfov_radians = number_or(*perspective, "yfov", 0);
    result.aspect_ratio = number_or(*perspective, "aspectRatio", 0);
  }
  return result;
}

float emissive_strength_of(const nlohmann::json& material) {
  const nlohmann::json* extensions = member(material, "extensions");
  const nlohmann::json* strength = extensions ? member(*extensions, "KHR_materials_emissive_strength") : nullptr;
  return strength ? number_or(*strength, "emissiveStrength", 1) : 1;
}

}  // namespace

bool is_gltf_path(const std::string& path) {
  const std::string extension = lowercase_extension(path);
  return extension == ".gltf" || extension == ".glb";
}

std::optional<GltfFacts> read_gltf_facts(const std::string& path) {
  const std::optional<std::string> text = json_text(path);
  if (!text) return std::nullopt;
  nlohmann::json document;
  try {
    document = nlohmann::json::parse(*text);
  } catch (const nlohmann::json::exception& error) {
    throw Error(path, std::string("its glTF JSON cannot be read: ") + error.what());
  }
  if (!document.is_object()) throw Error(path, "its glTF JSON is not an object");
  const nlohmann::json* asset = member(document, "asset");
  const nlohmann::json* version = asset ? member(*asset, "version") : nullptr;
  if (!version || !version->is_string() || version->get<std::string>().rfind("2.", 0) != 0) return std::nullopt;
  GltfFacts facts;
  if (const nlohmann::json* cameras = member(document, "cameras"); cameras && cameras->is_array())
    for (const nlohmann::json& camera : *cameras) facts.cameras.push_back(camera_of(camera));
  if (const nlohmann::json* materials = member(document, "materials"); materials && materials->is_array())
    for (const nlohmann::json& material : *materials) facts.emissive_strength.push_back(emissive_strength_of(material));
  if (const nlohmann::json* used = member(document, "extensionsUsed"); used && used->is_array())
    for (const nlohmann::json& name : *used)
      if (name.is_string()) facts.extensions_used.push_back(name.get<std::string>());
  return facts;
}

std::vector<std::string> unmodelled_gltf_extensions(const std::vector<std::string>& used) {
  std::vector<std::string> unmodelled;
  for (const std::string& name : used)
    if (std::none_of(std::begin(kModelledExtensions), std::end(kModelledExtensions),
                     [&](const char* modelled) { return name == modelled; }))
      unmodelled.push_back(name);
  return unmodelled;
}

}  // namespace kdray
