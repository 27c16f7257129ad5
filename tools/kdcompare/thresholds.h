// kdcompare's --threshold METRIC=VALUE: parsed before any image is read, then judged against the
// overall metrics of a comparison.
#pragma once

#include <kdray/image_compare.h>

#include <string>

namespace kdcompare {

struct Threshold {
  std::string metric;
  double limit = 0;
  double actual = 0;
  bool met = true;
};

// Throws CLI::ValidationError for text that is not METRIC=VALUE with a known metric and a number.
Threshold parse_threshold(const std::string& text);

// Sets threshold.actual and threshold.met from the comparison's overall metrics.
void check_threshold(Threshold& threshold, const kdray::CompareResult& result);

}  // namespace kdcompare
