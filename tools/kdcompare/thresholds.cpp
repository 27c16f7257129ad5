#include "thresholds.h"

#include <CLI/CLI.hpp>

#include <stdexcept>

namespace kdcompare {
namespace {

double metric_value(const kdray::CompareResult& result, const std::string& metric) {
  const kdray::ErrorMetrics& m = result.overall;
  if (metric == "rmse") return m.rmse;
  if (metric == "relmse") return m.relmse;
  if (metric == "mae") return m.mae;
  if (metric == "psnr") return m.psnr;
  if (metric == "max_abs") return m.max_abs;
  if (metric == "nonfinite") return double(result.nonfinite_test);
  throw CLI::ValidationError("--threshold", "unknown metric \"" + metric + "\" (rmse, relmse, mae, psnr, max_abs, nonfinite)");
}

}  // namespace

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
  metric_value(kdray::CompareResult{}, threshold.metric);  // rejects an unknown name before any image is read
  return threshold;
}

void check_threshold(Threshold& threshold, const kdray::CompareResult& result) {
  threshold.actual = metric_value(result, threshold.metric);
  // Higher PSNR is better; for every other metric lower is better. NaN never meets a threshold.
  threshold.met = threshold.metric == "psnr" ? threshold.actual >= threshold.limit : threshold.actual <= threshold.limit;
}

}  // namespace kdcompare
