// kdinfo's description of a .kdscene file.
#include "file_report.h"

#include <kdray/container_file.h>
#include <kdray/error.h>
#include <kdray/scene_file.h>

#include <scene_json.h>

#include <cmath>
#include <cstdio>
#include <map>
#include <optional>

namespace kdinfo {
namespace {

using kdray::Scene;
using kdray::tool::vec3_json;
using nlohmann::json;

std::vector<std::string> optional_sections(uint64_t flags) {
  std::vector<std::string> names;
  if (flags & kdray::format::kSceneHasNormals) names.push_back("normals");
  if (flags & kdray::format::kSceneHasUVs) names.push_back("uvs");
  if (flags & kdray::format::kSceneHasTextures) names.push_back("textures");
  if (flags & kdray::format::kSceneHasEmissive) names.push_back("emissive");
  if (flags & kdray::format::kSceneHasLights) names.push_back("lights");
  if (flags & kdray::format::kSceneHasTangents) names.push_back("tangents");
  return names;
}

double triangle_area(const Scene& scene, uint32_t triangle) {
  const kdray::Vec3& a = scene.positions[scene.indices[3 * triangle]];
  const kdray::Vec3& b = scene.positions[scene.indices[3 * triangle + 1]];
  const kdray::Vec3& c = scene.positions[scene.indices[3 * triangle + 2]];
  const double ux = b.x - a.x, uy = b.y - a.y, uz = b.z - a.z, vx = c.x - a.x, vy = c.y - a.y, vz = c.z - a.z;
  const double nx = uy * vz - uz * vy, ny = uz * vx - ux * vz, nz = ux * vy - uy * vx;
  return 0.5 * std::sqrt(nx * nx + ny * ny + nz * nz);
}

// Per emissive material: its triangles and their total area (the lights the renderer samples).
json lights_json(const Scene& scene) {
  std::map<uint32_t, std::pair<uint64_t, double>> per_material;
  for (uint32_t triangle : scene.emissive_triangles) {
    auto& [count, area] = per_material[scene.material_ids[triangle]];
    ++count;
    area += triangle_area(scene, triangle);
  }
  json lights = json::array();
  for (const auto& [material, totals] : per_material)
    lights.push_back({{"material", scene.materials[material].name},
                      {"emission", vec3_json(scene.materials[material].emission)},
                      {"triangles", totals.first},
                      {"area", totals.second}});
  return lights;
}

json scene_json(const Scene& scene) {
  const kdray::Bounds bounds = kdray::scene_bounds(scene);
  json import = kdray::tool::import_counts_json(scene.import_stats);
  import["source_file"] = scene.import_stats.source_file;
  json materials = json::array();
  for (const kdray::Material& m : scene.materials)
    materials.push_back({{"name", m.name},
                         {"type", kdray::material_type_name(m.type)},
                         {"base_color", vec3_json(m.base_color)},
                         {"emission", vec3_json(m.emission)},
                         {"roughness", m.roughness},
                         {"ior", m.ior},
                         {"diffuse_texture", m.diffuse_texture},
                         {"metallic", m.metallic},
                         {"alpha", m.alpha},
                         {"alpha_mode", alpha_mode_name(m.alpha_mode)},
                         {"alpha_cutoff", m.alpha_cutoff},
                         {"metal_rough_texture", m.metal_rough_texture},
                         {"normal_texture", m.normal_texture},
                         {"emissive_texture", m.emissive_texture}});
  json textures = json::array();
  for (const kdray::Texture& t : scene.textures)
    textures.push_back({{"name", t.name}, {"width", t.width}, {"height", t.height}});
  json cameras = json::array();
  for (const kdray::Camera& c : scene.cameras) {
    json camera = {{"name", c.name},
                   {"position", vec3_json(c.position)},
                   {"target", vec3_json(c.target)},
                   {"up", vec3_json(c.up)},
                   {"projection", kdray::projection_name(c.projection)},
                   {"aspect_ratio", c.aspect_ratio}};
    if (c.projection == kdray::Projection::Orthographic)
      camera["orthographic_half_height"] = c.orthographic_half_height;
    else
      camera["vertical_fov_degrees"] = c.vertical_fov_degrees;
    cameras.push_back(camera);
  }
  json punctual = json::array();
  for (const kdray::Light& l : scene.lights) {
    json light = {{"name", l.name}, {"type", kdray::light_type_name(l.type)}, {"color", vec3_json(l.color)}};
    if (l.type != kdray::LightType::Directional) light["position"] = vec3_json(l.position);
    if (l.type != kdray::LightType::Point) light["direction"] = vec3_json(l.direction);
    if (l.type == kdray::LightType::Spot) {
      light["inner_cone_degrees"] = l.inner_cone_radians * 180.0 / M_PI;
      light["outer_cone_degrees"] = l.outer_cone_radians * 180.0 / M_PI;
    }
    punctual.push_back(light);
  }
  return {
      {"geometry_hash", kdray::hash_hex(scene.geometry_hash)},
      {"triangles", scene.triangle_count()},
      {"vertices", scene.positions.size()},
      {"bounds", kdray::tool::bounds_json(bounds)},
      {"materials", materials},
      {"textures", textures},
      {"cameras", cameras},
      {"emissive_triangles", scene.emissive_triangles.size()},
      {"lights", lights_json(scene)},
      {"punctual_lights", punctual},
      {"import", import},
  };
}

std::string scene_text(const json& j) {
  std::string text;
  const json& bounds = j["bounds"];
  text += format("geometry   %s (what its k-d tree depends on)\n", j["geometry_hash"].get<std::string>().c_str());
  text += format("triangles  %llu\nvertices   %llu\n", j["triangles"].get<unsigned long long>(),
                 j["vertices"].get<unsigned long long>());
  text += format("bounds     (%g, %g, %g) .. (%g, %g, %g)\n", bounds["min"][0].get<double>(),
                 bounds["min"][1].get<double>(), bounds["min"][2].get<double>(), bounds["max"][0].get<double>(),
                 bounds["max"][1].get<double>(), bounds["max"][2].get<double>());
  text += format("materials  %zu\n", j["materials"].size());
  for (const json& m : j["materials"]) {
    text += format("  %-24s %-15s colour (%.3g, %.3g, %.3g)", m["name"].get<std::string>().c_str(),
                   m["type"].get<std::string>().c_str(), m["base_color"][0].get<double>(),
                   m["base_color"][1].get<double>(), m["base_color"][2].get<double>());
    if (m["type"] == "emissive")
      text += format(" emission (%g, %g, %g)", m["emission"][0].get<double>(), m["emission"][1].get<double>(),
                     m["emission"][2].get<double>());
    if (m["type"] == "rough-conductor") text += format(" roughness %.3g", m["roughness"].get<double>());
    if (m["type"] == "dielectric") text += format(" ior %.3g", m["ior"].get<double>());
    if (m["type"] == "metallic-roughness")
      text += format(" metallic %.3g roughness %.3g ior %.3g", m["metallic"].get<double>(), m["roughness"].get<double>(),
                     m["ior"].get<double>());
    if (m["alpha_mode"] != "opaque")
      text += format(" alpha %.3g (%s, cutoff %.3g)", m["alpha"].get<double>(),
                     m["alpha_mode"].get<std::string>().c_str(), m["alpha_cutoff"].get<double>());
    if (m["diffuse_texture"].get<int>() >= 0) text += format(" texture %d", m["diffuse_texture"].get<int>());
    if (m["metal_rough_texture"].get<int>() >= 0)
      text += format(" metal-rough texture %d", m["metal_rough_texture"].get<int>());
    if (m["normal_texture"].get<int>() >= 0) text += format(" normal map %d", m["normal_texture"].get<int>());
    if (m["emissive_texture"].get<int>() >= 0) text += format(" emissive texture %d", m["emissive_texture"].get<int>());
    text += "\n";
  }
  text += format("textures   %zu\n", j["textures"].size());
  for (const json& t : j["textures"])
    text += format("  %s (%ux%u)\n", t["name"].get<std::string>().c_str(), t["width"].get<unsigned>(),
                   t["height"].get<unsigned>());
  text += format("lights     %llu emissive triangles\n", j["emissive_triangles"].get<unsigned long long>());
  for (const json& l : j["lights"])
    text += format("  %s: %llu triangles, area %g, emission (%g, %g, %g)\n", l["material"].get<std::string>().c_str(),
                   l["triangles"].get<unsigned long long>(), l["area"].get<double>(), l["emission"][0].get<double>(),
                   l["emission"][1].get<double>(), l["emission"][2].get<double>());
  text += format("punctual   %zu (intensity W/sr for point and spot, irradiance W/m^2 for directional)\n",
                 j["punctual_lights"].size());
  for (const json& l : j["punctual_lights"]) {
    text += format("  %-24s %-11s colour x intensity (%g, %g, %g)", l["name"].get<std::string>().c_str(),
                   l["type"].get<std::string>().c_str(), l["color"][0].get<double>(), l["color"][1].get<double>(),
                   l["color"][2].get<double>());
    if (l.contains("position"))
      text += format(" at (%g, %g, %g)", l["position"][0].get<double>(), l["position"][1].get<double>(),
                     l["position"][2].get<double>());
    if (l.contains("direction"))
      text += format(" towards (%g, %g, %g)", l["direction"][0].get<double>(), l["direction"][1].get<double>(),
                     l["direction"][2].get<double>());
    if (l.contains("outer_cone_degrees"))
      text += format(" cone %g..%g deg (half-angles)", l["inner_cone_degrees"].get<double>(),
                     l["outer_cone_degrees"].get<double>());
    text += "\n";
  }
  text += format("cameras    %zu\n", j["cameras"].size());
  for (const json& c : j["cameras"]) {
    text += format("  %s at (%g, %g, %g) looking at (%g, %g, %g), ", c["name"].get<std::string>().c_str(),
                   c["position"][0].get<double>(), c["position"][1].get<double>(), c["position"][2].get<double>(),
                   c["target"][0].get<double>(), c["target"][1].get<double>(), c["target"][2].get<double>());
    text += c.contains("orthographic_half_height")
                ? format("orthographic, half-height %g", c["orthographic_half_height"].get<double>())
                : format("vertical fov %g deg", c["vertical_fov_degrees"].get<double>());
    const double aspect = c["aspect_ratio"].get<double>();
    text += aspect > 0 ? format(", aspect %g\n", aspect) : std::string(", aspect not given\n");
  }
  const json& import = j["import"];
  text += format("source     %s via %s: %llu triangles, dropped %llu degenerate and %llu non-finite, ignored %llu "
                 "points and %llu lines\n",
                 import["source_file"].get<std::string>().c_str(), import["importer"].get<std::string>().c_str(),
                 import["source_triangles"].get<unsigned long long>(),
                 import["dropped_degenerate"].get<unsigned long long>(),
                 import["dropped_non_finite"].get<unsigned long long>(),
                 import["ignored_points"].get<unsigned long long>(), import["ignored_lines"].get<unsigned long long>());
  for (const json& warning : import["warnings"]) text += "  warning: " + warning.get<std::string>() + "\n";
  return text;
}

}  // namespace

FileReport describe_scene_file(const std::string& path) {
  const kdray::SceneFileSummary summary = kdray::peek_scene(path);
  FileReport report;
  report.json = {{"file", path},
                 {"kind", "kdscene"},
                 {"format_version", summary.version},
                 {"file_size", summary.file_size},
                 {"content_hash", kdray::hash_hex(summary.content_hash)},
                 {"optional_sections", optional_sections(summary.flags)}};
  std::string optional;
  for (const std::string& name : optional_sections(summary.flags)) optional += (optional.empty() ? "" : ", ") + name;
  report.text = format("%s: kdscene version %u, %llu bytes\nhash       %s\noptional   %s\n", path.c_str(),
                       summary.version, (unsigned long long)summary.file_size,
                       kdray::hash_hex(summary.content_hash).c_str(), optional.empty() ? "none" : optional.c_str());
  add_verified_details(
      report, "checksum", [&] { return kdray::read_scene(path); }, scene_json, scene_text);
  return report;
}

}  // namespace kdinfo
