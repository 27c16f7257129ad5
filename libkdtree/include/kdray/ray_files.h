// Ray and hit files (formats/rays.md): headerless arrays of little-endian RayRecord (32 bytes)
// and HitRecord (16 bytes), so any language can write and read them.
#pragma once

#include <kernels/kd_types.h>

#include <string>
#include <vector>

namespace kdray {

// Throws kdray::Error naming the file when it cannot be read or its size is not a multiple of
// the record size.
std::vector<RayRecord> read_rays(const std::string& path);
std::vector<HitRecord> read_hits(const std::string& path);

// Atomic (temporary file in the same directory, flushed, renamed). Throws kdray::Error.
void write_rays(const std::string& path, const std::vector<RayRecord>& rays);
void write_hits(const std::string& path, const std::vector<HitRecord>& hits);

}  // namespace kdray
