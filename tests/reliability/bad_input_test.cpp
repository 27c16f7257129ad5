// One table of cases, run through every tool: --help, --version, then bad inputs (a missing
// file, a file of the wrong kind, a damaged or truncated file, an out-of-range option).
// README's contract: exit 0 with the answer on stdout and nothing on stderr for --help and
// --version; exit 1 for a failure (a missing, unreadable or damaged input included), 2 for a
// malformed command line, and one line on stderr, "tool: error: <file>: <what>", naming the file
// (or the option) at fault, whether or not --quiet or --json is given.
#include <subprocess.h>
#include "test_corpus.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <sstream>

namespace kdray {
namespace {

namespace fs = std::filesystem;
using test::run_process;
using test::tool_path;

struct BadInput {
  std::string name;               // "tool/case"
  std::vector<std::string> args;  // after the tool; {DIR} is the fixture's folder
  int exit_code;                  // what README's contract asks for
  std::string must_mention;       // what stdout (exit 0) or the error line (otherwise) must contain
};

const char* const kTools[] = {"kdconvert", "kdbuild", "kdrender", "kdtrace", "kdinfo", "kdcompare"};

std::string slurp(const fs::path& path) {
  std::ifstream file(path, std::ios::binary);
  std::ostringstream bytes;
  bytes << file.rdbuf();
  return bytes.str();
}

void spit(const fs::path& path, const std::string& bytes) { std::ofstream(path, std::ios::binary) << bytes; }

class BadInputTable : public test::SuiteDirTest<BadInputTable> {
 protected:
  static void SetUpTestSuite() {
    SuiteDirTest::SetUpTestSuite();
    const fs::path& d = dir_;
    ::setenv("KDRAY_CACHE_DIR", (d / "cache").c_str(), 1);
    spit(d / "quad.obj", "v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\nf 1 2 3 4\n");
    spit(d / "text.txt", "this is not a scene, a tree, a ray file or an image\n");
    auto run = [](std::vector<std::string> argv) {
      const auto result = run_process(argv, 300);
      if (!result.exited || result.exit_code != 0) throw std::runtime_error(argv[0] + " failed: " + result.err);
    };
    run({tool_path("kdconvert"), "--quiet", (d / "quad.obj").string(), (d / "good.kdscene").string()});
    run({tool_path("kdbuild"), "--quiet", (d / "good.kdscene").string(), (d / "good.kdtree").string()});
    run({tool_path("kdrender"), (d / "good.kdscene").string(), (d / "good.kdtree").string(), "--quiet", "--width", "4",
         "--height", "4", "--spp", "1", "-o", (d / "good.exr").string()});
    run({tool_path("kdtrace"), (d / "good.kdscene").string(), (d / "good.kdtree").string(), "--generate", "random",
         "--count", "4", "--write-rays", (d / "good.rays").string()});
    for (const char* name : {"good.kdscene", "good.kdtree", "good.exr"}) {
      const std::string bytes = slurp(d / name);
      spit(d / ("truncated-" + std::string(name).substr(5)), bytes.substr(0, bytes.size() * 2 / 3));
      std::string damaged = bytes;
      damaged[damaged.size() - 5] ^= 0x5a;
      spit(d / ("damaged-" + std::string(name).substr(5)), damaged);
    }
    // The same damage under names OpenEXR reads (.exr); the names above go to OpenImageIO.
    fs::copy_file(d / "truncated-exr", d / "truncated.exr");
    fs::copy_file(d / "damaged-exr", d / "damaged.exr");
    spit(d / "text.exr", slurp(d / "text.txt"));
    spit(d / "truncated.rays", slurp(d / "good.rays").substr(0, 45));
    spit(d / "truncated.ply", "ply\nformat ascii 1.0\nelement vertex 4\nproperty float x\nproperty float y\n"
                              "property float z\nelement face 1\nproperty list uchar int vertex_indices\nend_header\n0 0 0\n");
  }
  static void TearDownTestSuite() {
    ::unsetenv("KDRAY_CACHE_DIR");
    SuiteDirTest::TearDownTestSuite();
  }
};

std::vector<BadInput> table() {
  const std::string scene = "{DIR}/good.kdscene", tree = "{DIR}/good.kdtree", out = "{DIR}/out";
  std::vector<BadInput> cases;
  for (const std::string tool : kTools) {
    cases.push_back({tool + "/help", {"--help"}, 0, "--json"});
    cases.push_back({tool + "/version", {"--version"}, 0, tool + " " + KDRAY_VERSION});
  }
  const std::vector<BadInput> bad = {
      {"kdconvert/missing input", {"{DIR}/missing.obj", out + ".kdscene"}, 1, "missing.obj"},
      {"kdconvert/wrong kind", {"{DIR}/good.kdtree", out + ".kdscene"}, 1, "good.kdtree"},
      {"kdconvert/truncated ply", {"{DIR}/truncated.ply", out + ".kdscene"}, 1, "truncated.ply"},
      {"kdconvert/output folder missing", {"{DIR}/quad.obj", "{DIR}/no/such/folder/x.kdscene"}, 1, "x.kdscene"},
      {"kdconvert/negative scale", {"{DIR}/quad.obj", out + ".kdscene", "--scale", "-1"}, 2, "scale"},
      {"kdconvert/memory budget not a size", {"{DIR}/quad.obj", out + ".kdscene", "--max-memory", "lots"}, 2, "max-memory"},
      {"kdconvert/unknown up axis", {"{DIR}/quad.obj", out + ".kdscene", "--up-axis", "w"}, 2, "up-axis"},

      {"kdbuild/missing scene", {"{DIR}/missing.kdscene", out + ".kdtree"}, 1, "missing.kdscene"},
      {"kdbuild/wrong kind", {tree, out + ".kdtree"}, 1, "good.kdtree"},
      {"kdbuild/text file", {"{DIR}/text.txt", out + ".kdtree"}, 1, "text.txt"},
      {"kdbuild/truncated scene", {"{DIR}/truncated-kdscene", out + ".kdtree"}, 1, "truncated-kdscene"},
      {"kdbuild/damaged scene", {"{DIR}/damaged-kdscene", out + ".kdtree"}, 1, "damaged-kdscene"},
      {"kdbuild/empty bonus out of range", {scene, out + ".kdtree", "--empty-bonus", "5"}, 2, "empty-bonus"},

      {"kdrender/missing scene", {"{DIR}/missing.kdscene", tree, "-o", out + ".png"}, 1, "missing.kdscene"},
      {"kdrender/wrong kind", {tree, tree, "-o", out + ".png"}, 1, "good.kdtree"},
      {"kdrender/truncated tree", {scene, "{DIR}/truncated-kdtree", "-o", out + ".png"}, 1, "truncated-kdtree"},
      {"kdrender/damaged tree", {scene, "{DIR}/damaged-kdtree", "-o", out + ".png"}, 1, "damaged-kdtree"},
      {"kdrender/damaged merge input", {"--merge", "{DIR}/good.exr", "{DIR}/damaged-exr", "-o", out + ".exr"}, 1, "damaged-exr"},
      {"kdrender/text merge input", {"--merge", "{DIR}/good.exr", "{DIR}/text.txt", "-o", out + ".exr"}, 1, "text.txt"},
      {"kdrender/damaged .exr merge input", {"--merge", "{DIR}/good.exr", "{DIR}/damaged.exr", "-o", out + ".exr"}, 1,
       "damaged.exr"},
      {"kdrender/truncated .exr merge input", {"--merge", "{DIR}/truncated.exr", "{DIR}/good.exr", "-o", out + ".exr"},
       1, "truncated.exr"},
      {"kdrender/zero spp", {scene, tree, "-o", out + ".png", "--spp", "0"}, 2, "spp"},
      {"kdrender/unknown device", {scene, tree, "-o", out + ".png", "--device", "tpu"}, 2, "'tpu' is not host"},
      {"kdrender/threads with OpenCL", {scene, tree, "-o", out + ".png", "--device", "cpu", "--threads", "2"}, 2,
       "--threads 2 is for --device host"},
      {"kdrender/local size on host", {scene, tree, "-o", out + ".png", "--device", "host", "--local-size", "8"}, 2,
       "not --device host"},

      {"kdtrace/missing scene", {"{DIR}/missing.kdscene", tree, "--generate", "random"}, 1, "missing.kdscene"},
      {"kdtrace/missing rays", {scene, tree, "--rays", "{DIR}/missing.rays"}, 1, "missing.rays"},
      {"kdtrace/wrong kind", {tree, tree, "--generate", "random"}, 1, "good.kdtree"},
      {"kdtrace/truncated rays", {scene, tree, "--rays", "{DIR}/truncated.rays"}, 1, "truncated.rays"},
      {"kdtrace/damaged scene", {"{DIR}/damaged-kdscene", tree, "--generate", "random"}, 1, "damaged-kdscene"},
      {"kdtrace/negative count", {scene, tree, "--generate", "random", "--count", "-5"}, 2, "count"},
      {"kdtrace/threads with OpenCL", {scene, tree, "--generate", "random", "--device", "cpu", "--threads", "2"}, 2,
       "--threads 2 is for --device host"},

      {"kdinfo/missing file", {"{DIR}/missing.kdtree"}, 1, "missing.kdtree"},
      {"kdinfo/wrong kind", {"{DIR}/text.txt"}, 1, "text.txt"},
      {"kdinfo/truncated tree", {"{DIR}/truncated-kdtree"}, 1, "truncated-kdtree"},
      {"kdinfo/damaged scene", {"{DIR}/damaged-kdscene"}, 1, "damaged-kdscene"},
      {"kdinfo/unknown option", {"{DIR}/good.kdtree", "--no-such-option"}, 2, "no-such-option"},

      {"kdcompare/missing test image", {"{DIR}/missing.exr", "{DIR}/good.exr"}, 1, "missing.exr"},
      {"kdcompare/wrong kind", {"{DIR}/text.txt", "{DIR}/good.exr"}, 1, "text.txt"},
      {"kdcompare/truncated reference", {"{DIR}/good.exr", "{DIR}/truncated-exr"}, 1, "truncated-exr"},
      {"kdcompare/truncated .exr reference", {"{DIR}/good.exr", "{DIR}/truncated.exr"}, 1, "truncated.exr"},
      {"kdcompare/damaged .exr test image", {"{DIR}/damaged.exr", "{DIR}/good.exr"}, 1, "damaged.exr"},
      {"kdcompare/text named .exr", {"{DIR}/text.exr", "{DIR}/good.exr"}, 1, "text.exr"},
      {"kdcompare/bad threshold", {"{DIR}/good.exr", "{DIR}/good.exr", "--threshold", "relmse=abc"}, 2, "threshold"},
  };
  for (const BadInput& c : bad) {
    cases.push_back(c);
    // --quiet and --json change what a tool prints on success, never how it reports a failure.
    for (const char* flag : {"--quiet", "--json"}) {
      BadInput with_flag = c;
      with_flag.name += std::string(" ") + flag;
      with_flag.args.push_back(flag);
      cases.push_back(with_flag);
    }
  }
  return cases;
}

TEST_F(BadInputTable, EveryToolAnswersWithOneLineAndTheDocumentedExitCode) {
  for (const BadInput& bad : table()) {
    const std::string tool = bad.name.substr(0, bad.name.find('/'));
    std::vector<std::string> argv{tool_path(tool)};
    for (std::string arg : bad.args) {
      if (arg.rfind("{DIR}", 0) == 0) arg = dir_.string() + arg.substr(5);
      argv.push_back(arg);
    }
    SCOPED_TRACE(bad.name);
    const auto result = run_process(argv, 120);
    // Never a crash or a hang, whatever the case.
    ASSERT_TRUE(result.exited) << "signal " << result.signal << (result.timed_out ? " (timed out)" : "") << "\n"
                               << result.err;
    EXPECT_EQ(result.exit_code, bad.exit_code) << result.err;
    if (bad.exit_code == 0) {
      EXPECT_NE(result.out.find(bad.must_mention), std::string::npos) << result.out;
      EXPECT_EQ(result.err, "");
      continue;
    }
    std::vector<std::string> lines;
    std::istringstream err(result.err);
    for (std::string line; std::getline(err, line);)
      if (!line.empty()) lines.push_back(line);
    ASSERT_EQ(lines.size(), 1u) << result.err;
    EXPECT_EQ(lines[0].rfind(tool + ": error: ", 0), 0u) << lines[0];
    EXPECT_NE(lines[0].find(bad.must_mention), std::string::npos) << lines[0];
  }
}

// A stage whose memory estimate exceeds --max-memory is refused before it starts, with one line
// naming the file, the stage and both figures, and nothing is written.
TEST_F(BadInputTable, EveryStageOverItsMemoryBudgetIsRefusedNamingTheStage) {
  const fs::path& d = dir_;
  const std::string scene = (d / "good.kdscene").string(), tree = (d / "good.kdtree").string();
  struct Case {
    std::vector<std::string> argv;
    std::string file, stage, output;
  };
  const std::vector<Case> cases = {
      {{tool_path("kdconvert"), (d / "quad.obj").string(), (d / "budget.kdscene").string()}, "quad.obj",
       "importing it", "budget.kdscene"},
      {{tool_path("kdbuild"), scene, (d / "budget.kdtree").string()}, "good.kdscene", "building its tree",
       "budget.kdtree"},
      {{tool_path("kdrender"), scene, tree, "--width", "4", "--height", "4", "--spp", "1", "-o",
        (d / "budget.exr").string()},
       "good.kdscene", "rendering it", "budget.exr"},
  };
  for (const Case& c : cases) {
    SCOPED_TRACE(c.argv[0]);
    std::vector<std::string> argv = c.argv;
    argv.insert(argv.end(), {"--max-memory", "100"});  // bytes: less than any stage needs
    const auto refused = run_process(argv, 120);
    ASSERT_TRUE(refused.exited) << refused.err;
    EXPECT_EQ(refused.exit_code, 1);
    EXPECT_EQ(std::count(refused.err.begin(), refused.err.end(), '\n'), 1) << refused.err;
    for (const std::string& part :
         std::vector<std::string>{c.file, c.stage + " needs about ", "memory budget of 100 bytes (--max-memory)"})
      EXPECT_NE(refused.err.find(part), std::string::npos) << part << " in: " << refused.err;
    EXPECT_FALSE(fs::exists(d / c.output));
    argv.back() = "0";  // no limit
    const auto unlimited = run_process(argv, 300);
    EXPECT_TRUE(unlimited.exited && unlimited.exit_code == 0) << unlimited.err;
    EXPECT_TRUE(fs::exists(d / c.output));
  }
}

}  // namespace
}  // namespace kdray
