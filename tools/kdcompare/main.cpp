// kdcompare TEST REFERENCE: error metrics of one image against another, an optional
// false-colour error map, and thresholds for scripts and make rules.
//
//   kdcompare render.exr reference.exr --json
//   kdcompare render.exr reference.exr --threshold relmse=1e-3 --heatmap error.png
#include "compare_report.h"
#include "thresholds.h"

#include <kdray/error.h>
#include <kdray/image_compare.h>

#include "tool_main.h"

#include <string>
#include <vector>

namespace {

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

struct Options {
  std::string test_path, reference_path, heatmap_path;
  std::vector<std::string> threshold_texts;
  std::vector<kdcompare::Threshold> thresholds;  // parsed from threshold_texts before any image is read
  kdray::CompareOptions compare;
  kdray::HeatmapOptions heatmap;
  kdray::tool::OutputFlags flags;
};

void add_options(CLI::App& app, Options& o) {
  app.add_option("TEST", o.test_path, "The image to judge")->required();
  app.add_option("REFERENCE", o.reference_path, "The reference image, same size")->required();
  app.add_option("--channels", o.compare.channels,
                 "Channels to compare, by name (default: R,G,B when both have them, else all both have but alpha)")
      ->delimiter(',')
      ->group("Comparison");
  app.add_option("--peak", o.compare.peak, "PSNR peak (default 0: largest reference value, at least 1)")
      ->check(CLI::NonNegativeNumber)
      ->group("Comparison");
  app.add_option("--threshold", o.threshold_texts,
                 "METRIC=VALUE, repeatable: exit 3 when the overall metric is worse (rmse, relmse, mae, psnr, max_abs, "
                 "nonfinite)")
      ->type_name("METRIC=VALUE")
      ->expected(1)
      ->take_all()
      ->group("Comparison");
  app.add_option("--heatmap", o.heatmap_path, "Write a false-colour map of per-pixel error (mean |t-r| over channels)")
      ->type_name("OUT.png")
      ->group("Heat map");
  app.add_option("--heatmap-scale", o.heatmap.scale,
                 "Error shown at full colour (default 0: the 99th percentile of the pixel errors)")
      ->check(CLI::NonNegativeNumber)
      ->group("Heat map");
  app.callback([&o] {
    for (const std::string& text : o.threshold_texts) o.thresholds.push_back(kdcompare::parse_threshold(text));
  });
}

int compare(const Options& o) {
  const kdray::FloatImage test = kdray::read_float_image(o.test_path);
  const kdray::FloatImage reference = kdray::read_float_image(o.reference_path);
  if (!kdray::images_same_size(test, reference)) {
    throw kdray::Error(o.test_path, "size " + std::to_string(test.width) + "x" + std::to_string(test.height) +
                                        " differs from the reference's " + std::to_string(reference.width) + "x" +
                                        std::to_string(reference.height) + " (" + o.reference_path + ")");
  }
  kdcompare::Comparison comparison{o.test_path, o.reference_path, test.width, test.height, {}, o.thresholds,
                                   o.heatmap_path};
  try {
    comparison.result = kdray::compare_images(test, reference, o.compare);
  } catch (const kdray::Error& error) {
    throw kdray::Error(o.test_path, std::string(error.what()) + " (choose them with --channels)");
  }
  if (!o.heatmap_path.empty()) {
    const std::vector<float> error = kdray::per_pixel_abs_error(test, reference, comparison.result.channel_names);
    kdray::write_float_image_atomic(
        o.heatmap_path, kdray::error_heatmap(error, test.width, test.height, o.heatmap, &comparison.heatmap_scale));
  }
  for (kdcompare::Threshold& threshold : comparison.thresholds) {
    kdcompare::check_threshold(threshold, comparison.result);
    comparison.all_met = comparison.all_met && threshold.met;
  }
  if (o.flags.json) {
    kdray::tool::print_json(kdcompare::comparison_json(comparison));
  } else if (!o.flags.quiet) {
    kdcompare::print_comparison(comparison);
  }
  return comparison.all_met ? kdray::tool::kExitOk : kdray::tool::kExitAboveThreshold;
}

}  // namespace

int main(int argc, char** argv) {
  CLI::App app{"kdcompare: error of a rendered image against a reference"};
  Options o;
  kdray::tool::add_contract(app, "kdcompare", o.flags, "Print JSON on stdout instead of the table", kExitCodeHelp);
  add_options(app, o);
  return kdray::tool::run(app, argc, argv, [&]() -> int { return compare(o); });
}
