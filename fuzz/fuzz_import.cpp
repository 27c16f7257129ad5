// The importers, by file kind: KDRAY_FUZZ_EXTENSION (".obj" or ".ply") picks tinyobjloader or
// Assimp's PLY loader the way kdconvert does. The whole import runs: parsing, triangulation,
// material mapping, the emissive list and the default camera.
#include "fuzz_input.h"

#include <kdray/import.h>

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  const std::string path = kdray::fuzz::input_file(data, size, KDRAY_FUZZ_EXTENSION);
  kdray::fuzz::expect_clean([&] { kdray::import_scene(path, kdray::ImportOptions{}); });
  return 0;
}
