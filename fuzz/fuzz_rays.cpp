// Ray and hit files: headerless record arrays; any size that is not a whole number of records
// must be rejected, and every record that is read must be usable by the tracer's checks.
#include "fuzz_input.h"

#include <kdray/ray_files.h>

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  const std::string path = kdray::fuzz::input_file(data, size, ".bin");
  kdray::fuzz::expect_clean([&] { kdray::read_rays(path); });
  kdray::fuzz::expect_clean([&] { kdray::read_hits(path); });
  return 0;
}
