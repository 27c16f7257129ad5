#include "compare_report.h"

#include <cmath>
#include <cstdio>

namespace kdcompare {
namespace {

nlohmann::json finite_or_null(double value) { return std::isfinite(value) ? nlohmann::json(value) : nlohmann::json(); }

nlohmann::json metrics_json(const kdray::ErrorMetrics& m) {
  return {{"rmse", m.rmse},          {"relmse", m.relmse},       {"mae", m.mae},
          {"psnr", finite_or_null(m.psnr)}, {"max_abs", m.max_abs}, {"mean_test", m.mean_test},
          {"mean_reference", m.mean_reference}};
}

void print_metrics_row(const std::string& name, const kdray::ErrorMetrics& m) {
  std::printf("%-10s %12.6g %12.6g %12.6g %9.3f %12.6g %12.6g %12.6g\n", name.c_str(), m.rmse, m.relmse, m.mae, m.psnr,
              m.max_abs, m.mean_test, m.mean_reference);
}

}  // namespace

nlohmann::json comparison_json(const Comparison& c) {
  const kdray::CompareResult& result = c.result;
  nlohmann::json document = metrics_json(result.overall);
  document["test"] = c.test_path;
  document["reference"] = c.reference_path;
  document["width"] = c.width;
  document["height"] = c.height;
  document["channels"] = result.channel_names;
  document["psnr_peak"] = result.peak;
  document["nonfinite_test"] = result.nonfinite_test;
  document["nonfinite_reference"] = result.nonfinite_reference;
  document["compared_pixels"] = result.compared_pixels;
  nlohmann::json per_channel = nlohmann::json::object();
  for (size_t i = 0; i < result.channel_names.size(); ++i) {
    per_channel[result.channel_names[i]] = metrics_json(result.per_channel[i]);
  }
  document["per_channel"] = per_channel;
  if (!c.heatmap_path.empty()) document["heatmap"] = {{"path", c.heatmap_path}, {"scale", c.heatmap_scale}};
  nlohmann::json threshold_list = nlohmann::json::array();
  for (const Threshold& t : c.thresholds) {
    threshold_list.push_back({{"metric", t.metric}, {"limit", t.limit}, {"actual", finite_or_null(t.actual)}, {"met", t.met}});
  }
  document["thresholds"] = threshold_list;
  document["passed"] = c.all_met;
  return document;
}

void print_comparison(const Comparison& c) {
  const kdray::CompareResult& result = c.result;
  std::printf("%s against %s: %dx%d, PSNR peak %g\n", c.test_path.c_str(), c.reference_path.c_str(), c.width, c.height,
              result.peak);
  std::printf("%-10s %12s %12s %12s %9s %12s %12s %12s\n", "channel", "rmse", "relmse", "mae", "psnr dB", "max_abs",
              "mean test", "mean ref");
  for (size_t i = 0; i < result.channel_names.size(); ++i) print_metrics_row(result.channel_names[i], result.per_channel[i]);
  print_metrics_row("overall", result.overall);
  std::printf("NaN/Inf pixels: test %llu, reference %llu\n", (unsigned long long)result.nonfinite_test,
              (unsigned long long)result.nonfinite_reference);
  for (const Threshold& t : c.thresholds) {
    std::printf("threshold %s %s %g: %g %s\n", t.metric.c_str(), t.metric == "psnr" ? ">=" : "<=", t.limit, t.actual,
                t.met ? "ok" : "FAILED");
  }
  if (!c.heatmap_path.empty()) std::printf("heat map: %s (full colour at error %g)\n", c.heatmap_path.c_str(), c.heatmap_scale);
}

}  // namespace kdcompare
