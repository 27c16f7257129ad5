// The glTF metallic-roughness BRDF (kernels/pt_bsdf.h, compiled here as C++): what pt_bsdf_sample
// draws agrees with what pt_bsdf_eval says. The mean sample weight (f cos / pdf at the drawn
// direction) is the directional albedo that a quadrature of eval's f cos gives, and the share of
// draws that leave above the surface is the integral of eval's pdf there. A lobe choice whose
// probability eval's mixture pdf does not match, or a pdf of the wrong lobe, fails either.
#include <kernels/kd_types.h>
#include <kernels/kd_vector.h>
#include <kernels/pt_types.h>

#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <random>

namespace {
#define KD_FEATURE_METALLIC_ROUGHNESS
#include <kernels/pt_bsdf.h>
}  // namespace

namespace kdray {
namespace {

constexpr double kPi = 3.14159265358979323846;

struct Albedo {
  double rgb[3] = {0, 0, 0};
  double above = 0;  // quadrature: integral of the pdf; sampling: share of draws above
};

PtMaterial gltf_material(float alpha, float metallic) {
  PtMaterial m = {};
  m.type = PT_METALLIC_ROUGHNESS;
  m.roughness = alpha;
  m.metallic = metallic;
  m.ior = 1.5f;
  return m;
}

// Midpoint rule over the hemisphere in theta and phi.
Albedo albedo_by_quadrature(const PtMaterial& m, float3 color, float3 wo) {
  constexpr int kTheta = 1024, kPhi = 1024;
  const float3 n = KD_FLOAT3(0, 0, 1);
  Albedo a;
  for (int i = 0; i < kTheta; ++i) {
    const double theta = (i + 0.5) * (kPi / 2) / kTheta;
    const double d_omega = std::sin(theta) * (kPi / 2 / kTheta) * (2 * kPi / kPhi);
    for (int j = 0; j < kPhi; ++j) {
      const double phi = (j + 0.5) * 2 * kPi / kPhi;
      const float3 wi = KD_FLOAT3(float(std::sin(theta) * std::cos(phi)), float(std::sin(theta) * std::sin(phi)),
                                  float(std::cos(theta)));
      float pdf;
      const float3 f_cos = pt_bsdf_eval(&m, color, n, wo, wi, &pdf);
      a.rgb[0] += f_cos.x * d_omega;
      a.rgb[1] += f_cos.y * d_omega;
      a.rgb[2] += f_cos.z * d_omega;
      a.above += pdf * d_omega;
    }
  }
  return a;
}

Albedo albedo_by_sampling(const PtMaterial& m, float3 color, float3 wo, int samples) {
  const float3 n = KD_FLOAT3(0, 0, 1);
  std::mt19937 rng(7);
  std::uniform_real_distribution<float> u(0.0f, 1.0f);
  Albedo a;
  for (int k = 0; k < samples; ++k) {
    const float u1 = u(rng), u2 = u(rng), u_lobe = u(rng);
    const PtBsdfSample s = pt_bsdf_sample(&m, color, n, wo, 1, u1, u2, u_lobe);
    if (s.wi.z <= 0.0f) continue;
    a.rgb[0] += s.weight.x;
    a.rgb[1] += s.weight.y;
    a.rgb[2] += s.weight.z;
    a.above += 1;
  }
  for (double& c : a.rgb) c /= samples;
  a.above /= samples;
  return a;
}

TEST(GltfBrdf, SampledWeightsAverageToTheAlbedoOfItsEvaluation) {
  const float3 color = KD_FLOAT3(0.8f, 0.5f, 0.2f);
  constexpr int kSamples = 400000;
  for (float roughness : {0.25f, 0.5f, 1.0f})
    for (float metallic : {0.0f, 0.5f, 1.0f})
      for (float cos_o : {0.9f, 0.5f, 0.2f}) {
        const PtMaterial m = gltf_material(roughness * roughness, metallic);
        const float3 wo = KD_FLOAT3(std::sqrt(1 - cos_o * cos_o), 0, cos_o);
        const Albedo want = albedo_by_quadrature(m, color, wo);
        const Albedo got = albedo_by_sampling(m, color, wo, kSamples);
        std::printf("roughness %.2f metallic %.1f cos %.1f: albedo %.4f %.4f %.4f sampled %.4f %.4f %.4f, "
                    "pdf above %.4f drawn above %.4f\n",
                    roughness, metallic, cos_o, want.rgb[0], want.rgb[1], want.rgb[2], got.rgb[0], got.rgb[1],
                    got.rgb[2], want.above, got.above);
        for (int c = 0; c < 3; ++c)
          EXPECT_NEAR(got.rgb[c], want.rgb[c], 0.01 * want.rgb[c] + 1e-3)
              << "roughness " << roughness << " metallic " << metallic << " cos " << cos_o << " channel " << c;
        EXPECT_NEAR(got.above, want.above, 3e-3)
            << "roughness " << roughness << " metallic " << metallic << " cos " << cos_o;
      }
}

}  // namespace
}  // namespace kdray
