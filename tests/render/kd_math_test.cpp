// The float sin, cos, acos and atan2 of kernels/kd_math.h, which the path tracer uses on the device
// and in its C++ build, against double-precision libm over the ranges the path tracer passes
// (and a margin): their error stays within a few float ulps, so the renderer stays correct.
#include <kernels/kd_math.h>

#include <gtest/gtest.h>

#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstring>
#include <limits>

namespace {

constexpr double kPi = 3.14159265358979323846;

// Error of a float result against the exact value, in units of the float spacing at the exact
// value (so an error of 0.5 is correct rounding).
double ulps(float got, double exact) {
  const double spacing = std::ldexp(1.0, std::ilogb(std::fmax(std::fabs(exact), 1.1754943508222875e-38)) - 23);
  return std::fabs(double(got) - exact) / spacing;
}

struct Error {
  double max_abs = 0, max_ulps = 0;
  void add(float got, double exact, double ulp_floor) {
    max_abs = std::fmax(max_abs, std::fabs(double(got) - exact));
    // Near a zero of the function the relative error says little: count absolute error there.
    if (std::fabs(exact) >= ulp_floor) max_ulps = std::fmax(max_ulps, ulps(got, exact));
  }
};

TEST(KdMath, SinCosOverSeveralTurns) {
  Error sin_error, cos_error;
  const int steps = 1 << 21;
  for (int i = 0; i <= steps; ++i) {
    const float x = float(-4 * kPi + 8 * kPi * i / steps);
    float s, c;
    kd_sincos(x, &s, &c);
    EXPECT_EQ(s, kd_sin(x));
    EXPECT_EQ(c, kd_cos(x));
    sin_error.add(s, std::sin(double(x)), 1e-3);
    cos_error.add(c, std::cos(double(x)), 1e-3);
  }
  std::printf("sin: max abs %.3g, max ulps %.3g; cos: max abs %.3g, max ulps %.3g\n", sin_error.max_abs,
              sin_error.max_ulps, cos_error.max_abs, cos_error.max_ulps);
  EXPECT_LE(sin_error.max_abs, 1.2e-7);
  EXPECT_LE(cos_error.max_abs, 1.2e-7);
  EXPECT_LE(sin_error.max_ulps, 2.0);
  EXPECT_LE(cos_error.max_ulps, 2.0);
  // Exact at 0, and odd/even as the functions are.
  EXPECT_EQ(kd_sin(0.0f), 0.0f);
  EXPECT_EQ(kd_cos(0.0f), 1.0f);
  EXPECT_EQ(kd_sin(-1.25f), -kd_sin(1.25f));
  EXPECT_EQ(kd_cos(-1.25f), kd_cos(1.25f));
}

TEST(KdMath, SinCosReductionHoldsFarOut) {
  Error error;
  for (int i = 0; i <= 100000; ++i) {
    const float x = float(-1e4 + 2e4 * i / 100000.0);
    error.add(kd_sin(x), std::sin(double(x)), 1e-3);
  }
  std::printf("sin on [-1e4, 1e4]: max abs %.3g, max ulps %.3g\n", error.max_abs, error.max_ulps);
  EXPECT_LE(error.max_abs, 2e-7);
}

TEST(KdMath, AcosOverItsDomain) {
  Error error;
  const int steps = 1 << 21;
  for (int i = 0; i <= steps; ++i) {
    const float x = float(-1.0 + 2.0 * i / steps);
    error.add(kd_acos(x), std::acos(double(x)), 1e-3);
  }
  std::printf("acos: max abs %.3g, max ulps %.3g\n", error.max_abs, error.max_ulps);
  EXPECT_LE(error.max_abs, 4e-7);  // 1.3 ulps of pi, near x = -1
  EXPECT_LE(error.max_ulps, 2.0);
  EXPECT_EQ(kd_acos(1.0f), 0.0f);
  EXPECT_NEAR(kd_acos(-1.0f), kPi, 2.5e-7);
  EXPECT_TRUE(std::isnan(kd_acos(1.5f)));
}

TEST(KdMath, Atan2AllAround) {
  Error error;
  const int steps = 1 << 20;
  for (int i = 0; i < steps; ++i) {
    // Points on circles of several radii, so every octant and both argument orders occur.
    const double angle = -kPi + 2 * kPi * (i + 0.5) / steps;
    const double radius = std::ldexp(1.0, (i % 41) - 20);
    const float y = float(radius * std::sin(angle)), x = float(radius * std::cos(angle));
    error.add(kd_atan2(y, x), std::atan2(double(y), double(x)), 1e-3);
  }
  std::printf("atan2: max abs %.3g, max ulps %.3g\n", error.max_abs, error.max_ulps);
  EXPECT_LE(error.max_abs, 3e-7);
  EXPECT_LE(error.max_ulps, 3.5);  // the rounded quotient and pi/2 - r or pi - r add to the fit's error
  // The axes and the signs of zero.
  EXPECT_EQ(kd_atan2(0.0f, 1.0f), 0.0f);
  EXPECT_FLOAT_EQ(kd_atan2(1.0f, 0.0f), float(kPi / 2));
  EXPECT_FLOAT_EQ(kd_atan2(0.0f, -1.0f), float(kPi));
  EXPECT_FLOAT_EQ(kd_atan2(-0.0f, -1.0f), -float(kPi));
  EXPECT_EQ(kd_atan2(0.0f, 0.0f), 0.0f);
  EXPECT_TRUE(std::isnan(kd_atan2(std::numeric_limits<float>::quiet_NaN(), 1.0f)));
  EXPECT_TRUE(std::isnan(kd_atan2(1.0f, std::numeric_limits<float>::quiet_NaN())));
}

TEST(KdMath, VectorFunctions) {
  const float3 a = KD_FLOAT3(1.0f, 2.0f, 2.0f), b = KD_FLOAT3(0.0f, 1.0f, 0.0f);
  EXPECT_EQ(kd_dot(a, b), 2.0f);
  EXPECT_EQ(kd_length(a), 3.0f);
  const float3 n = kd_normalize(a);
  EXPECT_NEAR(kd_length(n), 1.0f, 1e-7f);
  const float3 c = kd_cross(b, a);
  EXPECT_EQ(c.x, 2.0f);
  EXPECT_EQ(c.y, 0.0f);
  EXPECT_EQ(c.z, -1.0f);
  const float3 m = kd_mix3(a, b, 0.5f);
  EXPECT_EQ(m.y, 1.5f);
  EXPECT_EQ(kd_rsqrt(4.0f), 0.5f);
}

// The C++ build's own fmax and fmin (kernels/kd_vector.h) give the C library's results: the
// non-NaN operand of a NaN and a number, the larger or smaller of two numbers. Of 0 and -0 C
// leaves the sign of the result open (glibc's x86-64 code returns the second operand, GCC's
// constant folding may return either), so there only a zero is asked for.
TEST(KdMath, FmaxAndFminAreTheCLibrarys) {
  const float nan = std::numeric_limits<float>::quiet_NaN(), inf = std::numeric_limits<float>::infinity();
  const float values[] = {0.0f, -0.0f, 1.0f, -1.0f, 1e-45f, -1e-45f, 3.4028235e38f, inf, -inf, nan, -nan, 0.5f};
  const auto bits = [](float x) {
    uint32_t b;
    std::memcpy(&b, &x, sizeof b);
    return b;
  };
  const auto expect_same = [&](float got, float c, float a, float b) {
    if (std::isnan(c)) EXPECT_TRUE(std::isnan(got)) << a << " " << b;
    else if (a == 0.0f && b == 0.0f) EXPECT_EQ(got, 0.0f) << a << " " << b;
    else EXPECT_EQ(bits(got), bits(c)) << a << " " << b;
  };
  for (float a : values) {
    for (float b : values) {
      expect_same(fmax(a, b), ::fmaxf(a, b), a, b);
      expect_same(fmin(a, b), ::fminf(a, b), a, b);
    }
  }
}

}  // namespace
