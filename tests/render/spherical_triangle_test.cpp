// Solid-angle sampling of triangle lights (kernels/pt_spherical_triangle.h, compiled here as
// C++): the solid angle is right on known cases, sampled directions fall inside the triangle,
// and their density, measured as the Jacobian of the map from [0,1)^2, equals the 1 / solid
// angle that MIS evaluates for the same direction.
#include <kernels/pt_spherical_triangle.h>

#include <gtest/gtest.h>

#include <array>
#include <cmath>
#include <random>
#include <vector>

namespace {

constexpr double kPi = 3.14159265358979323846;

struct Triangle {
  float3 q0, q1, q2;
};

// The solid angle whatever the technique; 0 when p lies on a corner.
float solid_angle(float3 p, const Triangle& t) {
  float3 d0 = t.q0 - p, d1 = t.q1 - p, d2 = t.q2 - p;
  float l0 = kd_length(d0), l1 = kd_length(d1), l2 = kd_length(d2);
  if (!(l0 > 0 && l1 > 0 && l2 > 0)) return 0;
  return pt_solid_angle_of(d0 / l0, d1 / l1, d2 / l2);
}

float3 sample(float3 p, const Triangle& t, float u0, float u1) {
  float3 a{}, b{}, c{};
  float omega = pt_spherical_solid_angle(p, t.q0, t.q1, t.q2, &a, &b, &c);
  return pt_sample_spherical_triangle(a, b, c, omega, u0, u1);
}

// Distance along unit d from p to the triangle, or -1 when the ray misses it (double precision,
// with a relative tolerance on the barycentrics for directions on the edges).
double hit_distance(float3 p, float3 d, const Triangle& t, double tolerance) {
  auto sub = [](float3 a, float3 b) { return std::array<double, 3>{double(a.x) - b.x, double(a.y) - b.y, double(a.z) - b.z}; };
  auto crs = [](std::array<double, 3> a, std::array<double, 3> b) {
    return std::array<double, 3>{a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0]};
  };
  auto dt = [](std::array<double, 3> a, std::array<double, 3> b) { return a[0] * b[0] + a[1] * b[1] + a[2] * b[2]; };
  std::array<double, 3> e1 = sub(t.q1, t.q0), e2 = sub(t.q2, t.q0), dir{d.x, d.y, d.z}, s = sub(p, t.q0);
  std::array<double, 3> h = crs(dir, e2);
  double det = dt(e1, h);
  if (det == 0) return -1;
  double u = dt(s, h) / det;
  std::array<double, 3> q = crs(s, e1);
  double v = dt(dir, q) / det, dist = dt(e2, q) / det;
  if (u < -tolerance || v < -tolerance || u + v > 1 + tolerance || dist <= 0) return -1;
  return dist;
}

TEST(SphericalTriangle, SolidAngleOfKnownTriangles) {
  // An octant seen from its corner: 4 pi / 8.
  EXPECT_NEAR(solid_angle({0, 0, 0}, {{1, 0, 0}, {0, 1, 0}, {0, 0, 1}}), kPi / 2, 1e-6);
  // Distance and winding do not matter; a small far triangle tends to area * cos / d^2.
  EXPECT_NEAR(solid_angle({0, 0, 0}, {{5, 0, 0}, {0, 0, 5}, {0, 5, 0}}), kPi / 2, 1e-6);
  const float d = 100;
  EXPECT_NEAR(solid_angle({0, 0, 0}, {{-0.5f, -0.5f, d}, {0.5f, -0.5f, d}, {0, 0.5f, d}}), 0.5 / (d * d), 1e-4 * 0.5 / (d * d));
  // A corner at the point: nothing to sample.
  EXPECT_EQ(solid_angle({1, 0, 0}, {{1, 0, 0}, {0, 1, 0}, {0, 0, 1}}), 0.0f);
}

TEST(SphericalTriangle, UsesSolidAngleSamplingOnlyBetweenTheThresholds) {
  EXPECT_FALSE(pt_use_spherical_sampling(0.0f));
  EXPECT_FALSE(pt_use_spherical_sampling(0.04f));
  EXPECT_TRUE(pt_use_spherical_sampling(0.06f));
  EXPECT_TRUE(pt_use_spherical_sampling(2.0f));
  EXPECT_FALSE(pt_use_spherical_sampling(6.25f));
  // The density follows the decision (0: by area): by area it is dist^2 / cos, by solid angle
  // 1 / omega.
  EXPECT_FLOAT_EQ(pt_triangle_light_pdf(0.5f, 2.0f, 0.0f, 9.0f, 0.5f), 0.5f * 9.0f / 0.5f);
  EXPECT_FLOAT_EQ(pt_triangle_light_pdf(0.5f, 2.0f, 0.1f, 9.0f, 0.5f), 0.5f * 2.0f / 0.1f);
}

TEST(SphericalTriangle, DecisionWithoutTheArctangentAgreesWithTheSolidAngle) {
  // pt_spherical_solid_angle tests the lower bound on tan(omega / 2) from unnormalised corner
  // vectors; away from the bounds (within 1e-4 relative) it must decide as the solid angle does,
  // and return that solid angle when it samples by solid angle. Triangles from 0.003 to 30 times
  // their distance, so solid angles from about 1e-5 sr to nearly 2 pi.
  std::mt19937 rng(11);
  std::uniform_real_distribution<float> coord(-1, 1);
  int spherical = 0, by_area = 0;
  for (int i = 0; i < 20000; ++i) {
    float scale = std::pow(10.0f, 2 * coord(rng) - 0.5f);
    float3 p{coord(rng), coord(rng), coord(rng)};
    Triangle t{{p.x + scale * coord(rng), p.y + scale * coord(rng), p.z + 1 + scale * coord(rng)},
               {p.x + scale * coord(rng), p.y + scale * coord(rng), p.z + 1 + scale * coord(rng)},
               {p.x + scale * coord(rng), p.y + scale * coord(rng), p.z + 1 + scale * coord(rng)}};
    float omega = solid_angle(p, t);
    if (std::abs(omega / PT_MIN_SPHERICAL_SOLID_ANGLE - 1) < 1e-4f || std::abs(omega / PT_MAX_SPHERICAL_SOLID_ANGLE - 1) < 1e-4f)
      continue;
    float3 a{}, b{}, c{};
    float decided = pt_spherical_solid_angle(p, t.q0, t.q1, t.q2, &a, &b, &c);
    if (pt_use_spherical_sampling(omega)) {
      ASSERT_EQ(decided, omega) << "case " << i;
      ++spherical;
    } else {
      ASSERT_EQ(decided, 0.0f) << "case " << i << ", solid angle " << omega;
      ++by_area;
    }
  }
  EXPECT_GT(spherical, 1000);
  EXPECT_GT(by_area, 1000);
}

// Random triangles seen from random points, from near (large solid angles) to far.
std::vector<std::pair<float3, Triangle>> cases() {
  std::mt19937 rng(7);
  std::uniform_real_distribution<float> coord(-1, 1);
  std::vector<std::pair<float3, Triangle>> out;
  while (out.size() < 200) {
    float scale = std::pow(10.0f, coord(rng) - 0.5f);  // triangles 0.03 to 3 times the distance
    float3 p{coord(rng), coord(rng), coord(rng)};
    Triangle t{{scale * coord(rng), scale * coord(rng), 1 + scale * coord(rng)},
               {scale * coord(rng), scale * coord(rng), 1 + scale * coord(rng)},
               {scale * coord(rng), scale * coord(rng), 1 + scale * coord(rng)}};
    t.q0 = t.q0 + p;
    t.q1 = t.q1 + p;
    t.q2 = t.q2 + p;
    float omega = solid_angle(p, t);
    if (pt_use_spherical_sampling(omega)) out.push_back({p, t});
  }
  return out;
}

TEST(SphericalTriangle, SampledDirectionsHitTheTriangle) {
  for (const auto& [p, t] : cases()) {
    for (int i = 0; i <= 16; ++i) {
      for (int j = 0; j <= 16; ++j) {
        float u0 = std::min(i / 16.0f, 0x1.fffffep-1f), u1 = std::min(j / 16.0f, 0x1.fffffep-1f);
        float3 d = sample(p, t, u0, u1);
        ASSERT_NEAR(kd_length(d), 1.0f, 1e-5f);
        ASSERT_GT(hit_distance(p, d, t, 1e-3), 0) << "u = " << u0 << ", " << u1 << ", solid angle " << solid_angle(p, t);
      }
    }
  }
}

// pt_solid_angle_of in double: the cells below are too small for float.
double solid_angle_double(float3 a, float3 b, float3 c) {
  double ax = a.x, ay = a.y, az = a.z, bx = b.x, by = b.y, bz = b.z, cx = c.x, cy = c.y, cz = c.z;
  double volume = std::abs(ax * (by * cz - bz * cy) + ay * (bz * cx - bx * cz) + az * (bx * cy - by * cx));
  return 2 * std::atan2(volume, 1 + ax * bx + ay * by + az * bz + bx * cx + by * cy + bz * cz + cx * ax + cy * ay + cz * az);
}

TEST(SphericalTriangle, SampledDensityEqualsOneOverTheSolidAngle) {
  // The solid angle of the image of a small square [u, u + h]^2 over h^2 is the inverse of the
  // sampling density there; it must equal the evaluated pdf 1 / omega everywhere in the square.
  const float h = 1.0f / 256;
  int checked = 0;
  for (const auto& [p, t] : cases()) {
    float omega = solid_angle(p, t);
    for (int i = 0; i < 8; ++i) {
      for (int j = 0; j < 8; ++j) {
        float u0 = (i + 0.5f) / 8, u1 = (j + 0.5f) / 8;
        float3 d00 = sample(p, t, u0, u1), d10 = sample(p, t, u0 + h, u1), d01 = sample(p, t, u0, u1 + h),
               d11 = sample(p, t, u0 + h, u1 + h);
        // the small quad's solid angle as two spherical triangles
        double cell = solid_angle_double(d00, d10, d11) + solid_angle_double(d00, d11, d01);
        ASSERT_NEAR(cell / (h * h) / omega, 1.0, 0.02) << "u = " << u0 << ", " << u1 << ", solid angle " << omega;
        ++checked;
      }
    }
  }
  EXPECT_EQ(checked, 200 * 64);
}

TEST(SphericalTriangle, HistogramOfSamplesMatchesTheDensity) {
  // Independent of the Jacobian above: the share of 2^14 stratified samples that fall in a
  // sub-triangle (corner, two edge midpoints) equals its share of the solid angle. (Arvo's
  // formulas taken literally in float miss by up to 0.008 on the small triangles here.)
  for (const auto& [p, t] : cases()) {
    Triangle corner{t.q0, 0.5f * (t.q0 + t.q1), 0.5f * (t.q0 + t.q2)};
    double expected = solid_angle(p, corner) / solid_angle(p, t);
    int inside = 0;
    const int n = 128;
    for (int i = 0; i < n; ++i) {
      for (int j = 0; j < n; ++j) inside += hit_distance(p, sample(p, t, (i + 0.5f) / n, (j + 0.5f) / n), corner, 0) > 0;
    }
    ASSERT_NEAR(double(inside) / (n * n), expected, 0.001);
  }
}

}  // namespace
