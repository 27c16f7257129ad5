// Reading and writing .kdscene files (formats/kdscene.md).
#pragma once

#include <kdray/format.h>
#include <kdray/scene.h>

#include <string>

namespace kdray {

// Writes atomically (temporary file + rename). Computes and records scene.content_hash.
void write_scene(const std::string& path, const Scene& scene);

// Reads and fully validates a .kdscene; throws kdray::Error naming the file and the problem.
Scene read_scene(const std::string& path);

// Header-level facts without loading the payload (no checksum verification).
struct SceneFileSummary {
  uint32_t version = 0;
  uint64_t flags = 0;
  uint64_t content_hash = 0;
  uint64_t file_size = 0;
};
SceneFileSummary peek_scene(const std::string& path);

}  // namespace kdray
