// scripts/speed_vs_error.py end to end on a tiny Cornell box: the CSV's rows and header, the
// exactness of reusing samples, and the plot.
#include <subprocess.h>
#include "test_corpus.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <sstream>

namespace fs = std::filesystem;
using kdray::test::shell_quoted;
using kdray::test::run_command;
using kdray::test::ToolRun;

namespace {

const std::string kCornellView = " --cam-pos 278,273,-800 --cam-target 278,273,0 --cam-up 0,1,0 --fov 39.3077";
const std::string kScript = std::string("/usr/bin/python3 ") + KDRAY_SOURCE_DIR + "/scripts/speed_vs_error.py";

std::string tool(const std::string& name) { return shell_quoted(kdray::test::tool_path(name)); }

struct Csv {
  std::vector<std::string> comments;
  std::vector<std::string> columns;
  std::vector<std::vector<std::string>> rows;

  double value(size_t row, const std::string& column) const {
    const auto found = std::find(columns.begin(), columns.end(), column);
    if (found == columns.end()) throw std::runtime_error("no column " + column);
    return std::stod(rows.at(row).at(size_t(found - columns.begin())));
  }
};

std::vector<std::string> split(const std::string& line) {
  std::vector<std::string> fields;
  std::stringstream stream(line);
  std::string field;
  while (std::getline(stream, field, ',')) fields.push_back(field);
  return fields;
}

Csv read_csv(const fs::path& path) {
  Csv csv;
  std::ifstream in(path);
  std::string line;
  while (std::getline(in, line)) {
    if (line.rfind("# ", 0) == 0) {
      csv.comments.push_back(line.substr(2));
    } else if (csv.columns.empty()) {
      csv.columns = split(line);
    } else {
      csv.rows.push_back(split(line));
    }
  }
  return csv;
}

class SpeedVsError : public kdray::test::TempDirTest<> {
 protected:
  void SetUp() override {
    scene_ = (dir_ / "cornell.kdscene").string();
    tree_ = (dir_ / "cornell.kdtree").string();
    const std::string obj = kdray::test::cornell_obj();
    ASSERT_EQ(run_command(tool("kdconvert") + " " + shell_quoted(obj) + " " + shell_quoted(scene_) + " --quiet").exit_code, 0);
    ASSERT_EQ(run_command(tool("kdbuild") + " " + shell_quoted(scene_) + " " + shell_quoted(tree_) + " --quiet").exit_code, 0);
  }

  // The report at 8x8 up to 4 spp, with `options` before the "--" that starts kdrender's.
  ToolRun report(const std::string& csv, const std::string& options) {
    return run_command(kScript + " run " + shell_quoted(scene_) + " " + shell_quoted(tree_) + " --csv " + shell_quoted(csv) +
                       " --width 8 --height 8 --max-spp 4 --kdrender " + tool("kdrender") + " --kdcompare " +
                       tool("kdcompare") + " " + options + " --" + kCornellView);
  }

  // Renders the Cornell box at 8x8 to `output` with `options`; kdrender's exit code.
  int render(const std::string& output, const std::string& options) {
    return run_command(tool("kdrender") + " " + shell_quoted(scene_) + " " + shell_quoted(tree_) + " -o " +
                       shell_quoted(output) + " --width 8 --height 8 --quiet " + options + kCornellView)
        .exit_code;
  }

  // kdcompare's exit code for two images that must be the same to the bit.
  static int compare_exactly(const std::string& a, const std::string& b) {
    return run_command(tool("kdcompare") + " " + shell_quoted(a) + " " + shell_quoted(b) + " --threshold max_abs=0")
        .exit_code;
  }

  std::string scene_, tree_;
};

}  // namespace

TEST_F(SpeedVsError, WritesADoublingSeriesAgainstItsOwnReference) {
  const std::string csv_path = (dir_ / "report.csv").string();
  const std::string final_image = (dir_ / "final.exr").string();
  const ToolRun run = report(csv_path, "--reference-spp 16 --keep-image " + shell_quoted(final_image));
  ASSERT_EQ(run.exit_code, 0) << run.out;

  const Csv csv = read_csv(csv_path);
  bool reference_described = false;
  for (const std::string& comment : csv.comments) {
    reference_described |= comment.find("reference: rendered by this script, 16 spp with seed 1") != std::string::npos;
  }
  EXPECT_TRUE(reference_described);
  ASSERT_EQ(csv.rows.size(), 3u);
  for (size_t row = 0; row < 3; ++row) {
    EXPECT_EQ(csv.value(row, "spp"), double(1u << row));
    EXPECT_GT(csv.value(row, "relmse"), 0.0);
    EXPECT_EQ(csv.value(row, "nonfinite"), 0.0);
    if (row > 0) {
      EXPECT_GT(csv.value(row, "seconds"), csv.value(row - 1, "seconds"));
    }
  }

  // Reusing samples is exact: the merged 1 + 1 + 2 samples are the bytes of one 4-sample render.
  const std::string direct = (dir_ / "direct.exr").string();
  ASSERT_EQ(render(direct, "--spp 4 --seed 0"), 0);
  EXPECT_EQ(compare_exactly(final_image, direct), 0);
}

TEST_F(SpeedVsError, NamesAGivenReferenceAndPlots) {
  const std::string reference = (dir_ / "reference.exr").string();
  ASSERT_EQ(render(reference, "--spp 8 --seed 7"), 0);
  const std::string csv_path = (dir_ / "given.csv").string();
  const ToolRun run = report(csv_path, "--reference " + shell_quoted(reference));
  ASSERT_EQ(run.exit_code, 0) << run.out;
  const Csv csv = read_csv(csv_path);
  ASSERT_FALSE(csv.comments.empty());
  EXPECT_NE(csv.comments.back().find("reference: given"), std::string::npos) << csv.comments.back();

  const std::string plot = (dir_ / "plot.png").string();
  const ToolRun plotted = run_command(kScript + " plot " + shell_quoted(csv_path) + " -o " + shell_quoted(plot));
  ASSERT_EQ(plotted.exit_code, 0) << plotted.out;
  EXPECT_GT(fs::file_size(plot), 1000u);
}

TEST_F(SpeedVsError, SeriesOfBothSamplersShareOneOwnReference) {
  const std::string sobol_csv = (dir_ / "sobol.csv").string(), independent_csv = (dir_ / "independent.csv").string();
  const std::string final_image = (dir_ / "final.exr").string();
  ASSERT_EQ(report(sobol_csv, "--reference-spp 16 --sampler sobol").exit_code, 0);
  const ToolRun run = report(independent_csv, "--reference-spp 16 --sampler independent --keep-image " + shell_quoted(final_image));
  ASSERT_EQ(run.exit_code, 0) << run.out;
  const Csv csv = read_csv(independent_csv);
  bool sampler_described = false, reference_reused = false;
  for (const std::string& comment : csv.comments) {
    sampler_described |= comment.find("sampler independent") != std::string::npos;
    reference_reused |= comment.find("reused from an earlier run") != std::string::npos;
  }
  EXPECT_TRUE(sampler_described);
  EXPECT_TRUE(reference_reused) << "the second series renders no reference of its own";
  // The series renders with the sampler asked for: its 4-spp image is one independent render's bytes.
  const std::string direct = (dir_ / "direct.exr").string();
  ASSERT_EQ(render(direct, "--spp 4 --seed 0 --sampler independent"), 0);
  EXPECT_EQ(compare_exactly(final_image, direct), 0);
}

TEST_F(SpeedVsError, RefusesAMaxSppThatIsNotAPowerOfTwo) {
  const ToolRun run = run_command(kScript + " run " + shell_quoted(scene_) + " " + shell_quoted(tree_) + " --csv " +
                                  shell_quoted((dir_ / "x.csv").string()) + " --max-spp 3 2>&1");
  EXPECT_NE(run.exit_code, 0);
  EXPECT_NE(run.out.find("power of two"), std::string::npos) << run.out;
  EXPECT_FALSE(fs::exists(dir_ / "x.csv"));
}
