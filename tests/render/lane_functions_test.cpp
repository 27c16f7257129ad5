// The device code's lane functions (kernels/kd_lane.h) with 8-float lanes (librender/src/lane8.h)
// against the same functions with float: every lane must give the float instantiation's bits, on
// random arguments and on the hard ones (NaN, infinities, signed zeros, denormals, values at the
// branch points), with the lanes of a group taking different sides of each select. The host's
// paths in lanes rely on it for a film equal to the kernel's. Compiled for x86-64-v3 without
// contraction into FMA, as the host's lanes are.
// the rough conductor's, glass's and the glTF material's functions (kernels/pt_bsdf.h)
#define KD_FEATURE_GLOSSY
#define KD_FEATURE_GLASS
#define KD_FEATURE_METALLIC_ROUGHNESS
#include <kernels/pt_bsdf.h>
#include <kernels/pt_sampling.h>
#include <kernels/pt_spherical_triangle.h>

#include <librender/src/lane8.h>

#include <gtest/gtest.h>

#include <cmath>
#include <cstdint>
#include <cstring>
#include <limits>
#include <random>
#include <vector>

namespace {

using lane8::Float8;
using lane8::Float8x3;
using lane8::kLanes;

constexpr float kInf = std::numeric_limits<float>::infinity();
constexpr float kNaN = std::numeric_limits<float>::quiet_NaN();

uint32_t bits_of(float x) {
  uint32_t b;
  std::memcpy(&b, &x, sizeof b);
  return b;
}

// Arguments: mostly ordinary values of a few magnitudes, a share of hard ones.
class Arguments {
 public:
  explicit Arguments(uint32_t seed) : random_(seed) {}
  float next(float scale) {
    static const float hard[] = {0.0f,     -0.0f,     kInf,    -kInf,   kNaN,     1e-40f,   -1e-40f, 1.0f,
                                 -1.0f,    0.5f,      2.0f,    1e30f,   -1e30f,   0.414213562f, 1.0f / 32.0f,
                                 -1.0f / 32.0f, 0.05f, 6.22f};
    const uint32_t pick = random_() % 16;
    if (pick == 0) return hard[random_() % (sizeof hard / sizeof hard[0])];
    std::uniform_real_distribution<float> uniform(-scale, scale);
    const float x = uniform(random_);
    return pick == 1 ? x * 1e-6f : pick == 2 ? x * 1e4f : x;
  }
  float3 next3(float scale) { return KD_FLOAT3(next(scale), next(scale), next(scale)); }
  float3 unit3() {
    std::normal_distribution<float> normal;
    return kd_normalize(KD_FLOAT3(normal(random_), normal(random_), normal(random_)));
  }
  float unit() { return std::uniform_real_distribution<float>(0.0f, 1.0f)(random_); }

 private:
  std::mt19937 random_;
};

Float8 lanes(const float* values) { return lane8::load(values); }
Float8x3 lanes3(const float3* values) {
  float x[kLanes], y[kLanes], z[kLanes];
  for (int l = 0; l < kLanes; ++l) x[l] = values[l].x, y[l] = values[l].y, z[l] = values[l].z;
  return {lane8::load(x), lane8::load(y), lane8::load(z)};
}

// Counts the lanes whose bits differ from the scalar answers.
struct Mismatches {
  int count = 0;
  void compare(Float8 got, const float* want) {
    for (int l = 0; l < kLanes; ++l) count += bits_of(got[l]) != bits_of(want[l]);
  }
  void compare(Float8x3 got, const float3* want) {
    for (int l = 0; l < kLanes; ++l) {
      count += bits_of(got.x[l]) != bits_of(want[l].x) || bits_of(got.y[l]) != bits_of(want[l].y) ||
               bits_of(got.z[l]) != bits_of(want[l].z);
    }
  }
};

constexpr int kGroups = 20000;

bool has_avx2() { return __builtin_cpu_supports("avx2") && __builtin_cpu_supports("fma"); }

TEST(LaneFunctions, SinCosAndAtan2) {
  if (!has_avx2()) GTEST_SKIP() << "the lanes need AVX2";
  Arguments arguments(1);
  Mismatches sin_cos, atan2;
  for (int g = 0; g < kGroups; ++g) {
    float x[kLanes], y[kLanes], s[kLanes], c[kLanes], a[kLanes];
    for (int l = 0; l < kLanes; ++l) {
      x[l] = arguments.next(13.0f);
      y[l] = arguments.next(13.0f);
      kd_sincos(x[l], &s[l], &c[l]);
      a[l] = kd_atan2(y[l], x[l]);
    }
    Float8 ls, lc;
    kd_sincos(lanes(x), &ls, &lc);
    sin_cos.compare(ls, s);
    sin_cos.compare(lc, c);
    atan2.compare(kd_atan2(lanes(y), lanes(x)), a);
  }
  EXPECT_EQ(sin_cos.count, 0);
  EXPECT_EQ(atan2.count, 0);
}

TEST(LaneFunctions, VectorsMaximaAndMisWeights) {
  if (!has_avx2()) GTEST_SKIP() << "the lanes need AVX2";
  Arguments arguments(2);
  Mismatches mismatches;
  for (int g = 0; g < kGroups; ++g) {
    float3 u[kLanes], v[kLanes], cross[kLanes], normalized[kLanes];
    float dot[kLanes], max[kLanes], luminance[kLanes], power[kLanes], pa[kLanes], pb[kLanes];
    for (int l = 0; l < kLanes; ++l) {
      u[l] = arguments.next3(4.0f);
      v[l] = arguments.next3(4.0f);
      pa[l] = arguments.next(2.0f);
      pb[l] = arguments.next(2.0f);
      cross[l] = kd_cross(u[l], v[l]);
      normalized[l] = kd_normalize(u[l]);
      dot[l] = kd_dot(u[l], v[l]);
      max[l] = pt_max3(u[l]);
      luminance[l] = pt_luminance(u[l]);
      power[l] = pt_power_heuristic(pa[l], pb[l]);
    }
    const Float8x3 lu = lanes3(u), lv = lanes3(v);
    mismatches.compare(kd_cross(lu, lv), cross);
    mismatches.compare(kd_normalize(lu), normalized);
    mismatches.compare(kd_dot(lu, lv), dot);
    mismatches.compare(pt_max3(lu), max);
    mismatches.compare(pt_luminance(lu), luminance);
    mismatches.compare(pt_power_heuristic(lanes(pa), lanes(pb)), power);
  }
  EXPECT_EQ(mismatches.count, 0);
}

TEST(LaneFunctions, CosineSamplesAndOffsetOrigins) {
  if (!has_avx2()) GTEST_SKIP() << "the lanes need AVX2";
  Arguments arguments(3);
  Mismatches mismatches;
  for (int g = 0; g < kGroups; ++g) {
    float3 n[kLanes], p[kLanes], direction[kLanes], offset[kLanes];
    float u1[kLanes], u2[kLanes];
    for (int l = 0; l < kLanes; ++l) {
      n[l] = arguments.unit3();
      if (l == 0) n[l] = KD_FLOAT3(0.0f, 0.0f, g % 2 ? -1.0f : 1.0f);  // the basis's sign at the poles
      if (l == 1) n[l].z = g % 2 ? -0.0f : 0.0f;
      p[l] = arguments.next3(g % 3 ? 0.1f : 300.0f);
      u1[l] = arguments.unit();
      u2[l] = arguments.unit();
      direction[l] = pt_sample_cosine(n[l], u1[l], u2[l]);
      offset[l] = pt_offset_origin(p[l], n[l]);
    }
    mismatches.compare(pt_sample_cosine(lanes3(n), lanes(u1), lanes(u2)), direction);
    mismatches.compare(pt_offset_origin(lanes3(p), lanes3(n)), offset);
  }
  EXPECT_EQ(mismatches.count, 0);
}

// Triangle lights seen from a point: far and small (sampled by area), near and large (by solid
// angle), degenerate and seen edge-on, mixed within each group of 8.
TEST(LaneFunctions, SphericalTrianglesAndTheirSamples) {
  if (!has_avx2()) GTEST_SKIP() << "the lanes need AVX2";
  Arguments arguments(4);
  Mismatches mismatches;
  int spherical_lanes = 0;
  for (int g = 0; g < kGroups; ++g) {
    float3 p[kLanes], q0[kLanes], q1[kLanes], q2[kLanes], a[kLanes], b[kLanes], c[kLanes], wi[kLanes];
    float solid_angle[kLanes], u0[kLanes], u1[kLanes], pdf[kLanes];
    for (int l = 0; l < kLanes; ++l) {
      const float distance = (l % 4 == 0) ? 50.0f : (l % 4 == 1) ? 0.3f : 2.0f;
      p[l] = arguments.next3(1.0f);
      q0[l] = p[l] + distance * arguments.unit3();
      q1[l] = q0[l] + arguments.unit3();
      q2[l] = l == 7 ? q1[l] : q0[l] + arguments.unit3();  // lane 7: a degenerate triangle
      u0[l] = arguments.unit();
      u1[l] = arguments.unit();
      a[l] = b[l] = c[l] = KD_FLOAT3(0.0f, 0.0f, 0.0f);
      solid_angle[l] = pt_spherical_solid_angle(p[l], q0[l], q1[l], q2[l], &a[l], &b[l], &c[l]);
      spherical_lanes += solid_angle[l] > 0.0f;
      wi[l] = solid_angle[l] > 0.0f ? pt_sample_spherical_triangle(a[l], b[l], c[l], solid_angle[l], u0[l], u1[l])
                                    : KD_FLOAT3(0.0f, 0.0f, 0.0f);
      pdf[l] = pt_triangle_light_pdf(0.7f, 0.5f, solid_angle[l], u0[l], u1[l]);
    }
    Float8x3 la = {}, lb = {}, lc = {};
    const Float8 lane_solid_angle =
        pt_spherical_solid_angle(lanes3(p), lanes3(q0), lanes3(q1), lanes3(q2), &la, &lb, &lc);
    mismatches.compare(lane_solid_angle, solid_angle);
    const Float8x3 lane_wi = pt_sample_spherical_triangle(la, lb, lc, lane_solid_angle, lanes(u0), lanes(u1));
    mismatches.compare(pt_triangle_light_pdf(Float8(0.7f), Float8(0.5f), lane_solid_angle, lanes(u0), lanes(u1)), pdf);
    for (int l = 0; l < kLanes; ++l) {
      if (!(solid_angle[l] > 0.0f)) continue;
      mismatches.count += bits_of(lane_wi.x[l]) != bits_of(wi[l].x) || bits_of(lane_wi.y[l]) != bits_of(wi[l].y) ||
                          bits_of(lane_wi.z[l]) != bits_of(wi[l].z);
    }
  }
  EXPECT_EQ(mismatches.count, 0);
  // both sampling techniques were exercised
  EXPECT_GT(spherical_lanes, kGroups);
  EXPECT_LT(spherical_lanes, kGroups * kLanes / 2);
}

// The glTF material: directions on both sides of the normal and grazing ones, roughness from a
// mirror's to 1 (and the hard values), indices from 1 up, metallic from 0 to 1.
TEST(LaneFunctions, GltfMaterialEvaluationAndSamples) {
  if (!has_avx2()) GTEST_SKIP() << "the lanes need AVX2";
  Arguments arguments(5);
  Mismatches mismatches;
  int evaluated_lanes = 0;
  for (int g = 0; g < kGroups; ++g) {
    float3 color[kLanes], n[kLanes], wo[kLanes], wi[kLanes], f_cos[kLanes], sampled[kLanes];
    float roughness[kLanes], ior[kLanes], metallic[kLanes], u1[kLanes], u2[kLanes], pdf[kLanes], p_ggx[kLanes];
    for (int l = 0; l < kLanes; ++l) {
      color[l] = KD_FLOAT3(arguments.unit(), arguments.unit(), arguments.unit());
      n[l] = arguments.unit3();
      wo[l] = arguments.unit3();
      wi[l] = l == 6 ? n[l] : arguments.unit3();
      if (l == 5) wo[l] = kd_normalize(wo[l] - kd_dot(wo[l], n[l]) * n[l]);  // grazing
      roughness[l] = l < 4 ? arguments.unit() : l == 4 ? 0.0f : arguments.next(1.0f);
      ior[l] = 1.0f + 1.5f * arguments.unit();
      metallic[l] = l % 3 == 0 ? 0.0f : arguments.unit();
      u1[l] = arguments.unit();
      u2[l] = arguments.unit();
      f_cos[l] = pt_metal_rough_eval(roughness[l], ior[l], metallic[l], color[l], n[l], wo[l], wi[l], &pdf[l]);
      evaluated_lanes += pdf[l] > 0.0f;
      p_ggx[l] = pt_gltf_ggx_probability(metallic[l], ior[l], color[l], kd_dot(n[l], wo[l]));
      sampled[l] = pt_ggx_sample_wi(roughness[l], n[l], wo[l], u1[l], u2[l]);
    }
    Float8 lane_pdf;
    const Float8x3 lane_f_cos = pt_metal_rough_eval(lanes(roughness), lanes(ior), lanes(metallic), lanes3(color),
                                                    lanes3(n), lanes3(wo), lanes3(wi), &lane_pdf);
    mismatches.compare(lane_f_cos, f_cos);
    mismatches.compare(lane_pdf, pdf);
    mismatches.compare(pt_gltf_ggx_probability(lanes(metallic), lanes(ior), lanes3(color), kd_dot(lanes3(n), lanes3(wo))),
                       p_ggx);
    mismatches.compare(pt_ggx_sample_wi(lanes(roughness), lanes3(n), lanes3(wo), lanes(u1), lanes(u2)), sampled);
  }
  EXPECT_EQ(mismatches.count, 0);
  // both sides of the evaluation's early exit were taken
  EXPECT_GT(evaluated_lanes, kGroups);
  EXPECT_LT(evaluated_lanes, kGroups * kLanes);
}

// The rough conductor and glass: directions on both sides of the normal, roughness from a mirror's
// to 1 (and the hard values), glass from either side at indices from 1 up (total internal
// reflection included).
TEST(LaneFunctions, ConductorAndGlass) {
  if (!has_avx2()) GTEST_SKIP() << "the lanes need AVX2";
  Arguments arguments(6);
  Mismatches mismatches;
  int total_reflection_lanes = 0;
  for (int g = 0; g < kGroups; ++g) {
    float3 color[kLanes], n[kLanes], wo[kLanes], wi[kLanes], f_cos[kLanes], refracted[kLanes];
    float roughness[kLanes], ior[kLanes], pdf[kLanes], reflectance[kLanes], eta[kLanes], cos_i[kLanes], cos_t[kLanes];
    bool entering[kLanes];
    for (int l = 0; l < kLanes; ++l) {
      color[l] = KD_FLOAT3(arguments.unit(), arguments.unit(), arguments.unit());
      n[l] = arguments.unit3();
      wo[l] = arguments.unit3();
      if (kd_dot(n[l], wo[l]) < 0.0f) n[l] = -n[l];  // n is on wo's side
      wi[l] = arguments.unit3();
      roughness[l] = l < 5 ? arguments.unit() : l == 5 ? 0.0f : arguments.next(1.0f);
      ior[l] = 1.0f + 1.5f * arguments.unit();
      entering[l] = l % 2 == 0;
      f_cos[l] = pt_ggx_eval(color[l], roughness[l], n[l], wo[l], wi[l], &pdf[l]);
      reflectance[l] = pt_glass_reflectance(ior[l], entering[l], n[l], wo[l], &eta[l], &cos_i[l], &cos_t[l]);
      total_reflection_lanes += reflectance[l] == 1.0f;
      refracted[l] = pt_glass_refraction(eta[l], cos_i[l], cos_t[l], n[l], wo[l]);
    }
    Float8 lane_pdf, lane_eta, lane_cos_i, lane_cos_t;
    mismatches.compare(pt_ggx_eval(lanes3(color), lanes(roughness), lanes3(n), lanes3(wo), lanes3(wi), &lane_pdf), f_cos);
    mismatches.compare(lane_pdf, pdf);
    const lane8::Mask8 lane_entering = lane8::lanes_of(0x55);  // the even lanes, as above
    mismatches.compare(pt_glass_reflectance(lanes(ior), lane_entering, lanes3(n), lanes3(wo), &lane_eta, &lane_cos_i,
                                            &lane_cos_t),
                       reflectance);
    mismatches.compare(lane_eta, eta);
    mismatches.compare(lane_cos_i, cos_i);
    mismatches.compare(lane_cos_t, cos_t);
    mismatches.compare(pt_glass_refraction(lane_eta, lane_cos_i, lane_cos_t, lanes3(n), lanes3(wo)), refracted);
  }
  EXPECT_EQ(mismatches.count, 0);
  EXPECT_GT(total_reflection_lanes, 0);  // past the critical angle, from inside
}

}  // namespace
