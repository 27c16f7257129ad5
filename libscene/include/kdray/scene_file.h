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

// The geometry of a .kdscene for a tool that traces a tree built for it, which holds its
// triangles' corners and so never reads the scene's arrays: the file is checked as read_scene
// checks it (checksum, header, sections, scene info) but its arrays are neither copied nor
// checked element by element. A file older than version 4, whose info has no geometry hash, is
// read whole to compute it. Throws kdray::Error naming the file and the problem.
SceneGeometry read_scene_geometry(const std::string& path);

// Header-level facts without loading the payload (no checksum verification).
struct SceneFileSummary {
  uint32_t version = 0;
  uint64_t flags = 0;
  uint64_t content_hash = 0;
  uint64_t file_size = 0;
};
SceneFileSummary peek_scene(const std::string& path);

}  // namespace kdray
