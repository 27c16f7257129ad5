// .kdscene reader: every input is read in full (header, sections, checksum, structured sections,
// consistency), for its geometry alone (everything but the arrays' elements) and by the
// header-only peek; each may only throw kdray::Error.
#include "fuzz_input.h"

#include <kdray/scene_file.h>

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  const std::string path = kdray::fuzz::input_file(data, size, ".kdscene");
  kdray::fuzz::expect_clean([&] { kdray::peek_scene(path); });
  kdray::fuzz::expect_clean([&] { kdray::read_scene(path); });
  kdray::fuzz::expect_clean([&] { kdray::read_scene_geometry(path); });
  return 0;
}
