// Tables of the rough dielectric coat of glTF non-metals (layout and meaning in
// kernels/pt_coat.h): computed at render setup for the indices of refraction the scene uses.
#pragma once

#include <vector>

namespace kdray {

// Energy of the GGX refraction lobe of a rough dielectric interface (relative index eta, light
// arriving from the side of index 1 at cos theta = cos_theta): the expectation over GGX visible
// normals of (1 - Fresnel) times the Smith masking of the refracted direction.
double rough_dielectric_transmittance(double cos_theta, double alpha, double eta);

// Energy of its GGX reflection lobe: the expectation of Fresnel times the Smith masking of the
// reflected direction (total internal reflection included when eta < 1).
double rough_dielectric_reflectance(double cos_theta, double alpha, double eta);

// Cosine-weighted hemispherical mean of the reflectance seen from inside a coat of index eta:
// 2 * integral over mu in [0, 1] of rough_dielectric_reflectance(mu, alpha, 1 / eta) * mu.
double rough_dielectric_internal_reflectance(double alpha, double eta);

// The tables of kernels/pt_coat.h for these etas (duplicates kept once, in first-seen order).
std::vector<float> build_coat_tables(const std::vector<float>& etas);

}  // namespace kdray
