// .kdtree reader: container checks, parameter and statistics sections, structural validation.
#include "fuzz_input.h"

#include <kdray/kdtree.h>

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  const std::string path = kdray::fuzz::input_file(data, size, ".kdtree");
  kdray::fuzz::expect_clean([&] { kdray::read_tree(path); });
  return 0;
}
