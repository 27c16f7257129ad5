// The environment sampling table (librender builds it, kernels/pt_environment.h draws from it;
// the drawing code is compiled here as C++): its density integrates to one, follows
// luminance x sin(theta), and matches the histogram of its samples (chi-square).
#include "light_scenes.h"

#include <test_corpus.h>

#include <kdray/environment.h>
#include <kdray/error.h>

#include <kernels/pt_environment.h>

#include <gtest/gtest.h>

#include <cmath>
#include <random>

namespace kdray {
namespace {

constexpr double kPi = 3.14159265358979323846;

double weight(const Environment& env, uint32_t i, uint32_t j) {
  const float* c = &env.rgb[(size_t(j) * env.width + i) * 3];
  return (double(c[0]) + c[1] + c[2]) / 3 * std::sin(kPi * (j + 0.5) / env.height);
}

TEST(EnvironmentTable, DensityIntegratesToOneAndFollowsLuminanceTimesSinTheta) {
  for (const Environment& env : {test::sun_environment(), test::coordinate_environment(7, 5),
                                 uniform_environment({1, 1, 1})}) {
    std::vector<float> table = environment_sampling_table(env);
    ASSERT_EQ(table.size(), size_t(env.width) * env.height + env.height +
                                size_t(env.height) * (pt_cdf_guide_size(env.width) + 1) +
                                pt_cdf_guide_size(env.height) + 1);
    double integral = 0, total_weight = 0;
    for (uint32_t j = 0; j < env.height; ++j)
      for (uint32_t i = 0; i < env.width; ++i) total_weight += weight(env, i, j);
    const double cell = 1.0 / (double(env.width) * env.height);
    for (uint32_t j = 0; j < env.height; ++j) {
      for (uint32_t i = 0; i < env.width; ++i) {
        const float pdf = pt_env_pdf_uv(table.data(), env.width, env.height, (i + 0.5f) / env.width,
                                        (j + 0.5f) / env.height);
        integral += pdf * cell;
        EXPECT_NEAR(pdf * cell, weight(env, i, j) / total_weight, 1e-6) << env.source << " " << i << "," << j;
      }
    }
    EXPECT_NEAR(integral, 1.0, 1e-5) << env.source;
  }
}

TEST(EnvironmentTable, SamplesMatchTheDensityChiSquare) {
  const Environment env = test::sun_environment(16, 8);
  std::vector<float> table = environment_sampling_table(env);
  const uint32_t w = env.width, h = env.height;
  const int n = 200000;
  std::vector<double> counts(size_t(w) * h, 0);
  std::mt19937 random(7);
  std::uniform_real_distribution<float> uniform(0.0f, 1.0f);
  for (int s = 0; s < n; ++s) {
    float u = 0, v = 0;
    const float pdf = pt_env_sample_uv(table.data(), w, h, uniform(random), uniform(random), &u, &v);
    ASSERT_TRUE(u >= 0 && u < 1 && v >= 0 && v < 1);
    ASSERT_GT(pdf, 0.0f);
    ASSERT_FLOAT_EQ(pdf, pt_env_pdf_uv(table.data(), w, h, u, v));  // the density it reports is the one it has
    counts[size_t(v * h) * w + size_t(u * w)] += 1;
  }
  // Pearson's statistic over cells with an expected count of at least 5 (the rest pooled; cells
  // of zero density must stay empty).
  double chi2 = 0, pooled_expected = 0, pooled_observed = 0;
  int dof = -1;
  for (uint32_t j = 0; j < h; ++j) {
    for (uint32_t i = 0; i < w; ++i) {
      const double expected = n * pt_env_pdf_uv(table.data(), w, h, (i + 0.5f) / w, (j + 0.5f) / h) / (w * h);
      const double observed = counts[size_t(j) * w + i];
      if (expected == 0) {
        EXPECT_EQ(observed, 0) << i << "," << j;
      } else if (expected < 5) {
        pooled_expected += expected;
        pooled_observed += observed;
      } else {
        chi2 += (observed - expected) * (observed - expected) / expected;
        ++dof;
      }
    }
  }
  if (pooled_expected > 0) {
    chi2 += (pooled_observed - pooled_expected) * (pooled_observed - pooled_expected) / pooled_expected;
    ++dof;
  }
  ASSERT_GT(dof, 20);
  // Wilson-Hilferty: the chi-square quantile at 1 - 1e-6 (z = 4.75) for dof degrees of freedom.
  const double z = 4.75, k = dof;
  const double limit = k * std::pow(1 - 2 / (9 * k) + z * std::sqrt(2 / (9 * k)), 3);
  EXPECT_LT(chi2, limit) << "dof " << dof;
}

// The first index whose value exceeds u, by bisecting the whole cdf.
uint32_t bisect(const float* cdf, uint32_t n, float u) {
  uint32_t lo = 0, hi = n - 1;
  while (lo < hi) {
    const uint32_t mid = (lo + hi) / 2;
    if (u < cdf[mid]) hi = mid; else lo = mid + 1;
  }
  return lo;
}

TEST(EnvironmentTable, TheGuidedSearchFindsWhatBisectingTheWholeCdfFinds) {
  // A sun (most of a row's mass in a few cells, and empty cells), a map of distinct cells, a
  // uniform one, a row width that is no power of two and one below 16; u at random, at the
  // guides' own bounds k / G and next to them, and at each cdf value and next to it.
  for (const Environment& env : {test::sun_environment(), test::sun_environment(1000, 300),
                                 test::coordinate_environment(7, 5), uniform_environment({1, 1, 1})}) {
    const std::vector<float> table = environment_sampling_table(env);
    const uint32_t w = env.width, h = env.height;
    std::mt19937 random(11);
    std::uniform_real_distribution<float> uniform(0.0f, 1.0f);
    for (uint32_t j = 0; j <= h; ++j) {
      const float* cdf = j < h ? table.data() + size_t(j) * w : table.data() + size_t(w) * h;
      const uint32_t n = j < h ? w : h;
      const float* guide = pt_env_guide(table.data(), w, h, j);
      std::vector<float> us;
      for (int s = 0; s < 200; ++s) us.push_back(uniform(random));
      const uint32_t cells = pt_cdf_guide_size(n);
      for (uint32_t k = 0; k < cells; ++k) {
        const float bound = float(k) / float(cells);
        us.push_back(bound);
        if (k > 0) us.push_back(std::nextafter(bound, 0.0f));
      }
      for (uint32_t i = 0; i < n; ++i) {
        if (cdf[i] < 1.0f) us.push_back(cdf[i]);
        us.push_back(std::nextafter(cdf[i], 0.0f));
      }
      for (const float u : us) {
        ASSERT_TRUE(u >= 0.0f && u < 1.0f);
        ASSERT_EQ(pt_cdf_find(cdf, n, guide, u), bisect(cdf, n, u)) << env.source << " row " << j << " u " << u;
      }
    }
  }
}

TEST(EnvironmentTable, ABlackMapGetsAUniformTableInsteadOfNaN) {
  Environment env = uniform_environment({0, 0, 0});
  std::vector<float> table = environment_sampling_table(env);
  for (float value : table) ASSERT_TRUE(std::isfinite(value));
  EXPECT_EQ(environment_mean_luminance(env), 0.0);
}

TEST(EnvironmentLoad, ACorpusMapLoadsAsLinearRgb) {
  std::string path;
  KDRAY_CORPUS_FILE(path, "hdri/studio.exr");
  Environment env = load_environment(path);
  EXPECT_EQ(env.width, 2 * env.height);
  EXPECT_EQ(env.rgb.size(), size_t(env.width) * env.height * 3);
  EXPECT_GT(environment_mean_luminance(env), 0.0);
}

TEST(EnvironmentLoad, AMissingOrBadFileIsOneErrorNamingIt) {
  EXPECT_THROW(load_environment("/nonexistent/map.exr"), Error);
  const std::string path = test::cornell_obj();
  try {
    load_environment(path);
    FAIL() << "no error";
  } catch (const Error& error) {
    EXPECT_NE(std::string(error.what()).find(path), std::string::npos);
  }
}

}  // namespace
}  // namespace kdray
