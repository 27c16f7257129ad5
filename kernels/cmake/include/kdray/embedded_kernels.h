// The kernels/ sources embedded at build time (kernels/cmake/embed_kernels.cmake).
#pragma once

#include <cstddef>

namespace kdray::kernels {

struct EmbeddedFile {
  const char* name;  // file name inside kernels/, e.g. "kd_traverse.h"
  const char* text;
};

extern const EmbeddedFile kEmbeddedFiles[];
extern const size_t kEmbeddedFileCount;

}  // namespace kdray::kernels
