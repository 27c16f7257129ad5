// What kdcompare prints: the JSON document of --json, or the table.
#pragma once

#include "thresholds.h"

#include <kdray/image_compare.h>

#include <nlohmann/json.hpp>

#include <string>
#include <vector>

namespace kdcompare {

// What one comparison found, for either report.
struct Comparison {
  std::string test_path, reference_path;
  int width = 0, height = 0;
  kdray::CompareResult result;
  std::vector<Threshold> thresholds;
  std::string heatmap_path;  // empty: none written
  double heatmap_scale = 0;
  bool all_met = true;
};

nlohmann::json comparison_json(const Comparison& comparison);
void print_comparison(const Comparison& comparison);

}  // namespace kdcompare
