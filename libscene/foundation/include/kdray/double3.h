// Double-precision 3-vectors for host code that works from differences of nearby float
// positions and UVs (normals, tangents), where float would lose the digits that matter. The
// kernels and the scene keep float; this is for the few computations that derive data from them.
#pragma once

#include <array>

namespace kdray {

using Double3 = std::array<double, 3>;

// Any x, y, z vector (kdray::Vec3, the kernels' float3) in double precision.
template <typename Vector>
Double3 double3(const Vector& v) {
  return {v.x, v.y, v.z};
}

inline Double3 operator+(const Double3& a, const Double3& b) { return {a[0] + b[0], a[1] + b[1], a[2] + b[2]}; }
inline Double3 operator-(const Double3& a, const Double3& b) { return {a[0] - b[0], a[1] - b[1], a[2] - b[2]}; }
inline Double3 operator*(const Double3& a, double s) { return {a[0] * s, a[1] * s, a[2] * s}; }
inline double dot(const Double3& a, const Double3& b) { return a[0] * b[0] + a[1] * b[1] + a[2] * b[2]; }
inline Double3 cross(const Double3& a, const Double3& b) {
  return {a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0]};
}

}  // namespace kdray
