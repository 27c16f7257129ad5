// The rough coat's tables (kdray/coat_tables.h; layout and lookups of kernels/pt_coat.h, compiled
// here as C++): its transmittance and reflectance agree with brute-force integrals of the GGX
// BTDF and BRDF, tend to the smooth interface's Fresnel values as alpha goes to 0, and the
// kernel's bilinear lookups read the values the host computed.
#include "coat_reference.h"

#include <kdray/coat_tables.h>

#include <kernels/pt_coat.h>

#include <gtest/gtest.h>

#include <cmath>

namespace kdray {
namespace {

TEST(CoatTables, LobeEnergiesMatchBruteForceIntegrals) {
  // Outside (eta 1.5) and inside (1 / 1.5, total internal reflection) of a coat.
  for (double eta : {1.5, 1 / 1.5})
    for (double alpha : {0.27, 0.65})
      for (double mu : {0.3, 0.7, 0.95}) {
        const test::RoughInterface brute{alpha, eta};
        EXPECT_NEAR(rough_dielectric_transmittance(mu, alpha, eta), brute.energy(mu, true), 1e-3)
            << eta << " " << alpha << " " << mu;
        EXPECT_NEAR(rough_dielectric_reflectance(mu, alpha, eta), brute.energy(mu, false), 1e-3)
            << eta << " " << alpha << " " << mu;
      }
}

TEST(CoatTables, InternalReflectanceMatchesBruteForceIntegral) {
  for (double alpha : {0.27, 0.65}) {
    const double brute = test::RoughInterface{alpha, 1 / 1.5, 200}.hemispherical_mean(false);
    EXPECT_NEAR(rough_dielectric_internal_reflectance(alpha, 1.5), brute, 2e-3) << alpha;
  }
}

TEST(CoatTables, SmoothLimitIsFresnel) {
  const double eta = 1.5;
  const test::RoughInterface smooth{0, eta};  // only its Fresnel functions are used
  const test::RoughInterface inside{0, 1 / eta};
  for (double mu : {0.2, 0.5, 0.9, 1.0})
    EXPECT_NEAR(rough_dielectric_transmittance(mu, 0, eta), 1 - smooth.fresnel(mu), 2e-3) << mu;
  // The smooth interface's internal diffuse reflectance, 2 * integral of F(mu) mu dmu, and the
  // reciprocity that lets a white base under a smooth coat reflect everything:
  // eta^2 (1 - F_int) = 1 - F_ext.
  double f_int = 0, f_ext = 0;
  const int n = 200000;
  for (int i = 0; i < n; ++i) {
    const double mu = (i + 0.5) / n;
    f_int += 2 * inside.fresnel(mu) * mu / n;
    f_ext += 2 * smooth.fresnel(mu) * mu / n;
  }
  EXPECT_NEAR(eta * eta * (1 - f_int), 1 - f_ext, 1e-4);
  EXPECT_NEAR(rough_dielectric_internal_reflectance(0, eta), f_int, 2e-3);
}

TEST(CoatTables, LookupsReadTheHostValues) {
  const std::vector<float> table = build_coat_tables({1.5f, 1.33f, 1.5f});
  ASSERT_EQ(table[0], 2.0f);  // the repeated eta is kept once
  ASSERT_EQ(table.size(), size_t(3 + 2 * PT_COAT_BLOCK));
  for (float eta : {1.5f, 1.33f}) {
    // At a row (perceptual roughness 16/31) and a cosine (40/63) of the grid: the values themselves.
    const float alpha = (16.0f / 31) * (16.0f / 31), mu = 40.0f / 63;
    const PtCoatRow row = pt_coat_row(table.data(), eta, alpha);
    EXPECT_NEAR(pt_coat_transmittance(table.data(), row, mu), rough_dielectric_transmittance(mu, alpha, eta), 1e-5);
    EXPECT_NEAR(pt_coat_internal_reflectance(table.data(), row), rough_dielectric_internal_reflectance(alpha, eta), 1e-5);
    // Between rows and cosines: within the interpolation error.
    for (double a : {0.05, 0.3, 0.8})
      for (double c : {0.25, 0.55, 0.9}) {
        const PtCoatRow between = pt_coat_row(table.data(), eta, float(a));
        EXPECT_NEAR(pt_coat_transmittance(table.data(), between, float(c)), rough_dielectric_transmittance(c, a, eta),
                    3e-3)
            << eta << " " << a << " " << c;
        EXPECT_NEAR(pt_coat_internal_reflectance(table.data(), between), rough_dielectric_internal_reflectance(a, eta),
                    3e-3)
            << eta << " " << a;
      }
  }
}

}  // namespace
}  // namespace kdray
