// A guard for loaders that trust the element counts in a file's header: Assimp's OFF loader
// allocates and clears whatever count the header states (invalid/OutOfMemory.off announces
// 353,535,235,358 vertices in 309 bytes and takes a minute and 16 GB before failing).
#pragma once

#include <string>

namespace kdray {

// Throws kdray::Error when an OFF or PLY header announces more elements than the file has
// bytes (every element takes at least one byte). Other files pass unchecked.
void check_declared_counts(const std::string& path);

}  // namespace kdray
