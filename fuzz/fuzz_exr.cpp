// The EXR inputs of `kdrender --merge`: OpenEXR parses the file (Debian's build, not
// instrumented), kdray checks channels, metadata and sizes before it reads the exact sums.
#include "fuzz_input.h"

#include <kdray/image_io.h>

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  const std::string path = kdray::fuzz::input_file(data, size, ".exr");
  kdray::fuzz::expect_clean([&] { kdray::read_film_exr(path); });
  return 0;
}
