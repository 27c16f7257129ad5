// Triangulating one planar (or nearly planar) polygon by ear clipping in its own plane, so
// concave faces come out right where a fan would cover area outside the polygon.
#pragma once

#include <kdray/scene.h>

#include <array>
#include <cstdint>
#include <vector>

namespace kdray {

// Returns polygon.size() - 2 triangles as corner numbers into `polygon`, with the polygon's
// winding. Degenerate input (collinear, repeated or non-finite corners) still yields that many
// triangles; the mesh builder decides which of them to drop.
std::vector<std::array<uint32_t, 3>> triangulate_polygon(const std::vector<Vec3>& polygon);

}  // namespace kdray
