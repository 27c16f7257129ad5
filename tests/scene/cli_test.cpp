// kdconvert and kdinfo as users run them: exit codes, messages, JSON, and no partial output.
#include <kdray/container_file.h>
#include <kdray/scene_file.h>

#include <subprocess.h>
#include "test_corpus.h"

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include <algorithm>
#include <filesystem>
#include <fstream>

namespace kdray {
namespace {

using test::run_process;
using test::tool_path;

class Cli : public test::TempDirTest<> {
 protected:
  std::string small_obj() const {
    const std::string obj = path("tri.obj");
    std::ofstream(obj) << "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n";
    return obj;
  }

  test::ToolRun convert(std::vector<std::string> arguments) const {
    arguments.insert(arguments.begin(), tool_path("kdconvert"));
    return run_process(arguments);
  }
  test::ToolRun info(std::vector<std::string> arguments) const {
    arguments.insert(arguments.begin(), tool_path("kdinfo"));
    return run_process(arguments);
  }
};

void expect_one_error_line(const test::ToolRun& result, const std::string& starts_with) {
  EXPECT_EQ(result.err.rfind(starts_with, 0), 0u) << result.err;
  EXPECT_EQ(std::count(result.err.begin(), result.err.end(), '\n'), 1) << result.err;
}

TEST_F(Cli, ConvertWritesASceneAndSummarises) {
  const auto result = convert({small_obj(), path("tri.kdscene")});
  ASSERT_EQ(result.exit_code, 0) << result.err;
  EXPECT_NE(result.out.find("1 kept of 1"), std::string::npos) << result.out;
  EXPECT_EQ(read_scene(path("tri.kdscene")).triangle_count(), 1u);
}

TEST_F(Cli, ConvertJsonSaysWhatWasDropped) {
  const std::string obj = path("drops.obj");
  std::ofstream(obj) << "v 0 0 0\nv 1 0 0\nv 0 1 0\nv 2 0 0\nf 1 2 3\nf 1 2 4\nf 1 1 2\nl 1 2\np 3\n";
  const auto result = convert({obj, path("drops.kdscene"), "--json"});
  ASSERT_EQ(result.exit_code, 0) << result.err;
  const nlohmann::json summary = nlohmann::json::parse(result.out);
  EXPECT_EQ(summary["triangles"], 1);
  EXPECT_EQ(summary["source_triangles"], 3);
  EXPECT_EQ(summary["dropped_degenerate"], 2);
  EXPECT_EQ(summary["ignored_lines"], 1);
  EXPECT_EQ(summary["ignored_points"], 1);
  EXPECT_EQ(summary["content_hash"].get<std::string>().size(), 16u);
}

TEST_F(Cli, QuietConvertPrintsNothing) {
  const auto result = convert({small_obj(), path("tri.kdscene"), "--quiet"});
  EXPECT_EQ(result.exit_code, 0);
  EXPECT_EQ(result.out, "");
  EXPECT_EQ(result.err, "");
}

TEST_F(Cli, MissingInputIsOneLineAndExitOne) {
  const auto result = convert({path("absent.obj"), path("out.kdscene")});
  EXPECT_EQ(result.exit_code, 1);
  expect_one_error_line(result, "kdconvert: error: " + path("absent.obj") + ": no such file");
  EXPECT_FALSE(std::filesystem::exists(path("out.kdscene")));
}

TEST_F(Cli, BadArgumentsExitTwo) {
  const std::string obj = small_obj();
  for (const std::vector<std::string>& arguments :
       {std::vector<std::string>{}, {obj}, {obj, path("o.kdscene"), "--importer", "blender"},
        {obj, path("o.kdscene"), "--scale", "-1"}, {obj, path("o.kdscene"), "--up-axis", "x"},
        {obj, path("o.kdscene"), "--no-such-option"}}) {
    const auto result = convert(arguments);
    EXPECT_EQ(result.exit_code, 2) << result.err;
    EXPECT_EQ(result.err.rfind("kdconvert: error: ", 0), 0u) << result.err;
  }
  EXPECT_EQ(info({}).exit_code, 2);
  EXPECT_EQ(info({"a", "b", "c"}).exit_code, 2);  // one file, or a scene and a tree
}

TEST_F(Cli, HelpShowsGroupsAndDefaults) {
  const auto result = convert({"--help"});
  EXPECT_EQ(result.exit_code, 0);
  EXPECT_NE(result.out.find("Import:"), std::string::npos);
  EXPECT_NE(result.out.find("--importer TEXT:{auto,assimp,tinyobj}=auto"), std::string::npos) << result.out;
  EXPECT_NE(result.out.find("--scale FLOAT:POSITIVE=1"), std::string::npos) << result.out;
  EXPECT_EQ(info({"--help"}).exit_code, 0);
  EXPECT_NE(convert({"--version"}).out.find("kdconvert "), std::string::npos);
  EXPECT_NE(info({"--version"}).out.find("kdinfo "), std::string::npos);
}

TEST_F(Cli, UnwritableOutputFailsCleanly) {
  const auto result = convert({small_obj(), path("no-such-dir/out.kdscene")});
  EXPECT_EQ(result.exit_code, 1);
  expect_one_error_line(result, "kdconvert: error: " + path("no-such-dir/out.kdscene") + ": cannot create");
}

TEST_F(Cli, FileWithoutTrianglesLeavesNoOutput) {
  const std::string obj = path("points.obj");
  std::ofstream(obj) << "v 0 0 0\nv 1 0 0\np 1 2\n";
  const auto result = convert({obj, path("points.kdscene")});
  EXPECT_EQ(result.exit_code, 1);
  expect_one_error_line(result, "kdconvert: error: " + obj + ": no triangles to keep");
  EXPECT_TRUE(std::filesystem::exists(obj));
  EXPECT_EQ(std::distance(std::filesystem::directory_iterator(dir_), {}), 1) << "only the input remains";
}

TEST_F(Cli, UnknownCameraIsAnError) {
  const auto result = convert({small_obj(), path("tri.kdscene"), "--camera", "top"});
  EXPECT_EQ(result.exit_code, 1);
  expect_one_error_line(result, "kdconvert: error: " + path("tri.obj") + ": no camera 'top' (the file has no cameras)");
}

TEST_F(Cli, InfoDescribesAnIntactScene) {
  ASSERT_EQ(convert({small_obj(), path("tri.kdscene"), "--quiet"}).exit_code, 0);
  const auto text = info({path("tri.kdscene")});
  EXPECT_EQ(text.exit_code, 0) << text.err;
  EXPECT_NE(text.out.find("intact     yes"), std::string::npos) << text.out;
  EXPECT_NE(text.out.find("triangles  1"), std::string::npos) << text.out;
  const auto json = info({path("tri.kdscene"), "--json"});
  const nlohmann::json description = nlohmann::json::parse(json.out);
  EXPECT_EQ(description["intact"], true);
  EXPECT_EQ(description["kind"], "kdscene");
  EXPECT_EQ(description["format_version"], format::kSceneVersion);
  EXPECT_EQ(description["triangles"], 1);
  EXPECT_EQ(description["cameras"].size(), 1u);
  EXPECT_EQ(description["materials"][0]["type"], "diffuse");
  EXPECT_EQ(description["content_hash"], hash_hex(read_scene(path("tri.kdscene")).content_hash));
}

TEST_F(Cli, InfoReportsADamagedSceneAndExitsOne) {
  ASSERT_EQ(convert({small_obj(), path("tri.kdscene"), "--quiet"}).exit_code, 0);
  {
    std::fstream file(path("tri.kdscene"), std::ios::in | std::ios::out | std::ios::binary);
    file.seekp(-1, std::ios::end);
    file.put('\x7f');
  }
  const auto text = info({path("tri.kdscene")});
  EXPECT_EQ(text.exit_code, 1);
  EXPECT_NE(text.out.find("intact     NO: " + path("tri.kdscene") + ": checksum mismatch"), std::string::npos) << text.out;
  const nlohmann::json description = nlohmann::json::parse(info({path("tri.kdscene"), "--json"}).out);
  EXPECT_EQ(description["intact"], false);
}

TEST_F(Cli, InfoRejectsFilesItDoesNotKnow) {
  const auto missing = info({path("absent.kdscene")});
  EXPECT_EQ(missing.exit_code, 1);
  expect_one_error_line(missing, "kdinfo: error: " + path("absent.kdscene") + ": no such file");
  const auto foreign = info({small_obj()});
  EXPECT_EQ(foreign.exit_code, 1);
  expect_one_error_line(foreign, "kdinfo: error: " + path("tri.obj") + ": not a kdray file");
}

}  // namespace
}  // namespace kdray
