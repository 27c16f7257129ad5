// kdcompare TEST REFERENCE: error metrics of one image against another, an optional
// false-colour error map, and thresholds for scripts and make rules.
#include <kdray/error.h>
#include <kdray/image_compare.h>

#include "tool_main.h"

#include <cmath>
#include <cstdio>
#include <string>
#include <vector>

namespace {

using kdray::CompareResult;
using kdray::ErrorMetrics;

constexpr const char* kExitCodeHelp =
    "Exit status:\n"
    "  0  compared; every --threshold met\n"
    "  1  failure: an image is missing or unreadable, the images differ in size or lack the compared\n"
    "     channels, or the heat map cannot be written\n"
    "  2  bad command line\n"
    "  3  compared, and a metric is worse than its --threshold (psnr: below it; the others: above it)\n"
    "Metrics (over pixels finite in both images; NaN/Inf pixels are counted, not compared):\n"
    "  rmse     sqrt(mean (t-r)^2)\n"
    "  relmse   mean (t-r)^2 / (r^2 + 0.01)\n"
    "  mae      mean |t-r|\n"
    "  psnr     10 log10(peak^2 / MSE) dB; peak = --peak, by default the largest reference value\n"
    "           over the compared channels but at least 1 (so 0..1 images use peak 1, HDR images\n"
    "           their brightest value); identical images give inf (null in --json)\n"
    "  max_abs  max |t-r|\n"
    "  nonfinite  (threshold only) pixels of TEST with a NaN or Inf\n";

struct Threshold {
  std::string metric;
  double limit = 0;
  double actual = 0;
  bool met = true;
};

double metric_value(const CompareResult& result, const std::string& metric) {
  const ErrorMetrics& m = result.overall;
  if (metric == "rmse") return m.rmse;
  if (metric == "relmse") return m.relmse;
  if (metric == "mae") return m.mae;
  if (metric == "psnr") return m.psnr;
  if (metric == "max_abs") return m.max_abs;
  if (metric == "nonfinite") return double(result.nonfinite_test);
  throw CLI::ValidationError("--threshold", "unknown metric \"" + metric + "\" (rmse, relmse, mae, psnr, max_abs, nonfinite)");
}

Threshold parse_threshold(const std::string& text) {
  const size_t equals = text.find('=');
  if (equals == std::string::npos) throw CLI::ValidationError("--threshold", "expected METRIC=VALUE, got \"" + text + "\"");
  Threshold threshold;
  threshold.metric = text.substr(0, equals);
  try {
    size_t used = 0;
    threshold.limit = std::stod(text.substr(equals + 1), &used);
    if (used != text.size() - equals - 1) throw std::invalid_argument("trailing characters");
  } catch (const std::exception&) {
    throw CLI::ValidationError("--threshold", "\"" + text.substr(equals + 1) + "\" is not a number");
  }
  metric_value(CompareResult{}, threshold.metric);  // rejects an unknown name before any image is read
  return threshold;
}

void check_threshold(Threshold& threshold, const CompareResult& result) {
  threshold.actual = metric_value(result, threshold.metric);
  // Higher PSNR is better; for every other metric lower is better. NaN never meets a threshold.
  threshold.met = threshold.metric == "psnr" ? threshold.actual >= threshold.limit : threshold.actual <= threshold.limit;
}

nlohmann::json finite_or_null(double value) { return std::isfinite(value) ? nlohmann::json(value) : nlohmann::json(); }

nlohmann::json metrics_json(const ErrorMetrics& m) {
  return {{"rmse", m.rmse},          {"relmse", m.relmse},       {"mae", m.mae},
          {"psnr", finite_or_null(m.psnr)}, {"max_abs", m.max_abs}, {"mean_test", m.mean_test},
          {"mean_reference", m.mean_reference}};
}

void print_metrics_row(const std::string& name, const ErrorMetrics& m) {
  std::printf("%-10s %12.6g %12.6g %12.6g %9.3f %12.6g %12.6g %12.6g\n", name.c_str(), m.rmse, m.relmse, m.mae, m.psnr,
              m.max_abs, m.mean_test, m.mean_reference);
}

void print_summary(const std::string& test_path, const std::string& reference_path, const kdray::FloatImage& test,
                   const CompareResult& result, const std::vector<Threshold>& thresholds) {
  std::printf("%s against %s: %dx%d, PSNR peak %g\n", test_path.c_str(), reference_path.c_str(), test.width,
              test.height, result.peak);
  std::printf("%-10s %12s %12s %12s %9s %12s %12s %12s\n", "channel", "rmse", "relmse", "mae", "psnr dB", "max_abs",
              "mean test", "mean ref");
  for (size_t c = 0; c < result.channel_names.size(); ++c) print_metrics_row(result.channel_names[c], result.per_channel[c]);
  print_metrics_row("overall", result.overall);
  std::printf("NaN/Inf pixels: test %llu, reference %llu\n", (unsigned long long)result.nonfinite_test,
              (unsigned long long)result.nonfinite_reference);
  for (const Threshold& t : thresholds) {
    std::printf("threshold %s %s %g: %g %s\n", t.metric.c_str(), t.metric == "psnr" ? ">=" : "<=", t.limit, t.actual,
                t.met ? "ok" : "FAILED");
  }
}

}  // namespace

int main(int argc, char** argv) {
  CLI::App app{"kdcompare: error of a rendered image against a reference"};
  kdray::tool::OutputFlags output;
  kdray::tool::add_contract(app, "kdcompare", output, "Print JSON on stdout instead of the table", kExitCodeHelp);

  std::string test_path, reference_path, heatmap_path;
  std::vector<std::string> threshold_texts;
  kdray::CompareOptions compare_options;
  kdray::HeatmapOptions heatmap_options;

  app.add_option("TEST", test_path, "The image to judge")->required();
  app.add_option("REFERENCE", reference_path, "The reference image, same size")->required();
  app.add_option("--channels", compare_options.channels,
                 "Channels to compare, by name (default: R,G,B when both have them, else all both have but alpha)")
      ->delimiter(',')
      ->group("Comparison");
  app.add_option("--peak", compare_options.peak, "PSNR peak (default 0: largest reference value, at least 1)")
      ->check(CLI::NonNegativeNumber)
      ->group("Comparison");
  app.add_option("--threshold", threshold_texts,
                 "METRIC=VALUE, repeatable: exit 3 when the overall metric is worse (rmse, relmse, mae, psnr, max_abs, "
                 "nonfinite)")
      ->type_name("METRIC=VALUE")
      ->expected(1)
      ->take_all()
      ->group("Comparison");
  app.add_option("--heatmap", heatmap_path, "Write a false-colour map of per-pixel error (mean |t-r| over channels)")
      ->type_name("OUT.png")
      ->group("Heat map");
  app.add_option("--heatmap-scale", heatmap_options.scale,
                 "Error shown at full colour (default 0: the 99th percentile of the pixel errors)")
      ->check(CLI::NonNegativeNumber)
      ->group("Heat map");

  std::vector<Threshold> thresholds;
  app.callback([&] {
    for (const std::string& text : threshold_texts) thresholds.push_back(parse_threshold(text));
  });

  return kdray::tool::run(app, argc, argv, [&]() -> int {
    const kdray::FloatImage test = kdray::read_float_image(test_path);
    const kdray::FloatImage reference = kdray::read_float_image(reference_path);
    if (!kdray::images_same_size(test, reference)) {
      throw kdray::Error(test_path, "size " + std::to_string(test.width) + "x" + std::to_string(test.height) +
                                        " differs from the reference's " + std::to_string(reference.width) + "x" +
                                        std::to_string(reference.height) + " (" + reference_path + ")");
    }
    CompareResult result;
    try {
      result = kdray::compare_images(test, reference, compare_options);
    } catch (const kdray::Error& error) {
      throw kdray::Error(test_path, std::string(error.what()) + " (choose them with --channels)");
    }

    double heatmap_scale = 0;
    if (!heatmap_path.empty()) {
      const std::vector<float> error = kdray::per_pixel_abs_error(test, reference, result.channel_names);
      kdray::write_float_image_atomic(heatmap_path,
                                      kdray::error_heatmap(error, test.width, test.height, heatmap_options, &heatmap_scale));
    }

    bool all_met = true;
    for (Threshold& threshold : thresholds) {
      check_threshold(threshold, result);
      all_met = all_met && threshold.met;
    }

    if (output.json) {
      nlohmann::json document = metrics_json(result.overall);
      document["test"] = test_path;
      document["reference"] = reference_path;
      document["width"] = test.width;
      document["height"] = test.height;
      document["channels"] = result.channel_names;
      document["psnr_peak"] = result.peak;
      document["nonfinite_test"] = result.nonfinite_test;
      document["nonfinite_reference"] = result.nonfinite_reference;
      document["compared_pixels"] = result.compared_pixels;
      nlohmann::json per_channel = nlohmann::json::object();
      for (size_t c = 0; c < result.channel_names.size(); ++c) {
        per_channel[result.channel_names[c]] = metrics_json(result.per_channel[c]);
      }
      document["per_channel"] = per_channel;
      if (!heatmap_path.empty()) document["heatmap"] = {{"path", heatmap_path}, {"scale", heatmap_scale}};
      nlohmann::json threshold_list = nlohmann::json::array();
      for (const Threshold& t : thresholds) {
        threshold_list.push_back({{"metric", t.metric}, {"limit", t.limit}, {"actual", finite_or_null(t.actual)}, {"met", t.met}});
      }
      document["thresholds"] = threshold_list;
      document["passed"] = all_met;
      kdray::tool::print_json(document);
    } else if (!output.quiet) {
      print_summary(test_path, reference_path, test, result, thresholds);
      if (!heatmap_path.empty()) std::printf("heat map: %s (full colour at error %g)\n", heatmap_path.c_str(), heatmap_scale);
    }
    return all_met ? kdray::tool::kExitOk : kdray::tool::kExitAboveThreshold;
  });
}
