// kdconvert: an asset (OBJ, PLY, glTF, FBX, ...) becomes a checked .kdscene file.
#include <kdray/container_file.h>
#include <kdray/import.h>
#include <kdray/scene_file.h>

#include <scene_json.h>
#include <tool_main.h>

#include <chrono>
#include <cstdio>

namespace {

using kdray::ImportStats;
using kdray::Scene;

struct Timings {
  double import_seconds, write_seconds;
};

nlohmann::json summary_json(const Scene& scene, const std::string& output, const Timings& timings) {
  nlohmann::json summary = kdray::tool::import_counts_json(scene.import_stats);
  summary.update({
      {"output", output},
      {"source", scene.import_stats.source_file},
      {"triangles", scene.triangle_count()},
      {"vertices", scene.positions.size()},
      {"has_normals", !scene.normals.empty()},
      {"has_uvs", !scene.uvs.empty()},
      {"materials", scene.materials.size()},
      {"textures", scene.textures.size()},
      {"cameras", scene.cameras.size()},
      {"emissive_triangles", scene.emissive_triangles.size()},
      {"bounds", kdray::tool::bounds_json(kdray::scene_bounds(scene))},
      {"content_hash", kdray::hash_hex(scene.content_hash)},
      {"geometry_hash", kdray::hash_hex(scene.geometry_hash)},
      {"import_seconds", timings.import_seconds},
      {"write_seconds", timings.write_seconds},
  });
  return summary;
}

void print_summary(const Scene& scene, const std::string& output, const Timings& timings) {
  const ImportStats& stats = scene.import_stats;
  std::printf("%s -> %s (%s, import %.3f s, write %.3f s)\n", stats.source_file.c_str(), output.c_str(),
              stats.importer.c_str(), timings.import_seconds, timings.write_seconds);
  std::printf("  triangles  %zu kept of %llu", scene.triangle_count(), (unsigned long long)stats.source_triangles);
  if (stats.dropped_degenerate + stats.dropped_non_finite > 0)
    std::printf(" (dropped %llu degenerate, %llu non-finite)", (unsigned long long)stats.dropped_degenerate,
                (unsigned long long)stats.dropped_non_finite);
  std::printf("\n  vertices   %zu%s%s%s\n", scene.positions.size(), scene.normals.empty() ? "" : ", normals",
              scene.uvs.empty() ? "" : ", UVs", scene.tangents.empty() ? "" : ", tangents");
  if (stats.ignored_points + stats.ignored_lines > 0)
    std::printf("  ignored    %llu points, %llu lines\n", (unsigned long long)stats.ignored_points,
                (unsigned long long)stats.ignored_lines);
  std::printf("  materials  %zu, textures %zu, emissive triangles %zu, cameras %zu (first: %s)\n",
              scene.materials.size(), scene.textures.size(), scene.emissive_triangles.size(), scene.cameras.size(),
              scene.cameras.front().name.c_str());
  std::printf("  hash       %s (geometry %s)\n", kdray::hash_hex(scene.content_hash).c_str(),
              kdray::hash_hex(scene.geometry_hash).c_str());
  for (const std::string& warning : stats.warnings) std::printf("  warning: %s\n", warning.c_str());
}

}  // namespace

int main(int argc, char** argv) {
  CLI::App app{"Converts a mesh asset into a .kdscene file.\n"
               "OBJ goes through tinyobjloader, every other format through Assimp."};
  kdray::tool::OutputFlags flags;
  kdray::tool::add_contract(app, "kdconvert", flags, "Print the summary as JSON on stdout");
  std::string input, output;
  kdray::ImportOptions options;
  app.add_option("INPUT", input, "Asset to convert (OBJ, PLY, glTF, FBX, DAE, 3DS, STL, ...)")->required();
  app.add_option("OUTPUT", output, "The .kdscene file to write (written atomically)")->required();
  std::string importer = "auto", up_axis = "y";
  app.add_option("--importer", importer, "auto: tinyobj for .obj, Assimp otherwise")
      ->group("Import")
      ->check(CLI::IsMember({"auto", "assimp", "tinyobj"}))
      ->capture_default_str();
  app.add_option("--scale", options.scale, "Multiply every coordinate by this factor")
      ->group("Import")
      ->check(CLI::PositiveNumber)
      ->capture_default_str();
  app.add_option("--up-axis", up_axis, "The asset's up axis; z rotates it to kdray's +Y up")
      ->group("Import")
      ->check(CLI::IsMember({"y", "z"}))
      ->capture_default_str();
  app.add_option("--camera", options.camera, "Asset camera (name or index) to make the scene's first camera")
      ->group("Import")
      ->default_str("the asset's first, else one framing the bounding box");
  kdray::tool::add_max_memory_option(app, options.max_memory);

  return kdray::tool::run(app, argc, argv, [&] {
    const auto start = std::chrono::steady_clock::now();
    options.importer = importer == "assimp"    ? kdray::Importer::Assimp
                       : importer == "tinyobj" ? kdray::Importer::TinyObj
                                               : kdray::Importer::Auto;
    options.up_axis = up_axis == "z" ? kdray::UpAxis::Z : kdray::UpAxis::Y;
    const Scene scene = kdray::import_scene(input, options);
    const auto imported = std::chrono::steady_clock::now();
    kdray::write_scene(output, scene);  // includes the fsync that makes the file durable
    const Timings timings{std::chrono::duration<double>(imported - start).count(),
                          std::chrono::duration<double>(std::chrono::steady_clock::now() - imported).count()};
    if (flags.json)
      kdray::tool::print_json(summary_json(scene, output, timings));
    else if (!flags.quiet)
      print_summary(scene, output, timings);
    return kdray::tool::kExitOk;
  });
}
