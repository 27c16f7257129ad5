// Monte Carlo convergence on the sample Cornell box: relative MSE against a high-sample
// reference falls as 1/spp. The series is built the way the speed-vs-error report builds it
// (scripts/speed_vs_error.py): each step renders only the new samples [n, 2n) and merges them.
#include <kdray/film.h>
#include <kdray/image_compare.h>
#include <kdray/import.h>
#include <kdray/kdtree.h>
#include <kdray/render.h>

#include "test_corpus.h"

#include <gtest/gtest.h>

#include <cmath>
#include <vector>

namespace {

kdray::FloatImage radiance_image(const kdray::Film& film) {
  kdray::FloatImage image;
  image.width = int(film.width);
  image.height = int(film.height);
  image.channel_names = film.channels;
  image.pixels = film.means();
  return image;
}

// Least-squares slope of log(y) against log(x).
double log_log_slope(const std::vector<double>& x, const std::vector<double>& y) {
  double mean_x = 0, mean_y = 0;
  for (size_t i = 0; i < x.size(); ++i) {
    mean_x += std::log(x[i]) / double(x.size());
    mean_y += std::log(y[i]) / double(y.size());
  }
  double covariance = 0, variance = 0;
  for (size_t i = 0; i < x.size(); ++i) {
    covariance += (std::log(x[i]) - mean_x) * (std::log(y[i]) - mean_y);
    variance += (std::log(x[i]) - mean_x) * (std::log(x[i]) - mean_x);
  }
  return covariance / variance;
}

}  // namespace

TEST(Convergence, CornellBoxRelativeMseFallsAsOneOverSpp) {
  kdray::Scene scene = kdray::import_scene(kdray::test::cornell_obj(), {});
  scene.content_hash = kdray::compute_content_hash(scene);
  scene.geometry_hash = kdray::compute_geometry_hash(scene);
  const kdray::KdTree tree = kdray::build_kdtree(scene, kdray::BuildSettings{});

  kdray::RenderSettings settings;
  settings.width = settings.height = 32;  // small: a CI test, rendered twice (once under ASan)
  settings.max_bounces = 8;
  settings.camera = kdray::Camera{"cornell", {278, 273, -800}, {278, 273, 0}, {0, 1, 0}, 39.3077f};

  // The reference uses another seed, so its noise is independent of the series'. Its own
  // error (1/2048 of one sample's) biases relMSE at 256 spp up by 1/8: the slope stays near -1.
  kdray::RenderSettings reference_settings = settings;
  reference_settings.spp = 2048;
  reference_settings.seed = 1;
  const kdray::FloatImage reference =
      radiance_image(kdray::render(scene, tree, reference_settings, kdray::DeviceSelection{}));

  std::vector<double> spp_series, relmse_series;
  settings.seed = 0;
  settings.spp = 4;
  kdray::Film film = kdray::render(scene, tree, settings, kdray::DeviceSelection{});
  for (;;) {
    const kdray::CompareResult result = kdray::compare_images(radiance_image(film), reference);
    EXPECT_EQ(result.nonfinite_test, 0u);
    spp_series.push_back(film.sample_count);
    relmse_series.push_back(result.overall.relmse);
    if (film.sample_count >= 256) break;
    settings.sample_offset = film.sample_count;
    settings.spp = film.sample_count;
    film = kdray::merge_films(film, kdray::render(scene, tree, settings, kdray::DeviceSelection{}));
  }
  ASSERT_EQ(spp_series.size(), 7u);  // 4, 8, ..., 256

  const double slope = log_log_slope(spp_series, relmse_series);
  std::string series;
  for (size_t i = 0; i < spp_series.size(); ++i) {
    series += std::to_string(int(spp_series[i])) + " spp: " + std::to_string(relmse_series[i]) + "\n";
  }
  EXPECT_GE(slope, -1.2) << series;
  EXPECT_LE(slope, -0.8) << series;
}
