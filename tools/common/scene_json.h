// Scene facts in the JSON vocabulary every tool uses (README.md): points, bounds and what the
// importer kept and dropped, the same in kdconvert's summary and kdinfo's descriptions.
#pragma once

#include <kdray/scene.h>

#include <nlohmann/json.hpp>

namespace kdray::tool {

inline nlohmann::json vec3_json(const Vec3& v) { return {v.x, v.y, v.z}; }

inline nlohmann::json bounds_json(const Bounds& bounds) {
  return {{"min", vec3_json(bounds.min)}, {"max", vec3_json(bounds.max)}};
}

// The import statistics but the source file's name, which each tool reports under its own key.
inline nlohmann::json import_counts_json(const ImportStats& stats) {
  return {
      {"importer", stats.importer},
      {"source_triangles", stats.source_triangles},
      {"dropped_degenerate", stats.dropped_degenerate},
      {"dropped_non_finite", stats.dropped_non_finite},
      {"ignored_points", stats.ignored_points},
      {"ignored_lines", stats.ignored_lines},
      {"warnings", stats.warnings},
  };
}

}  // namespace kdray::tool
