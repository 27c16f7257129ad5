// kdbuild and kdtrace from the command line: exit codes, messages, JSON and files.
#include "test_scenes.h"

#include <kdray/container_file.h>
#include <kdray/kdtree.h>
#include <kdray/ray_files.h>
#include <kdray/ray_sets.h>
#include <kdray/scene_file.h>
#include <kdray/threads.h>
#include <kdray/traverse.h>

#include <nlohmann/json.hpp>
#include <subprocess.h>
#include <test_corpus.h>

#include <gtest/gtest.h>
#include <tbb/task_arena.h>

#include <cstring>
#include <filesystem>
#include <fstream>
#include <iterator>

namespace kdray {
namespace {

using test::ToolRun;

class KdCli : public test::TempDirTest<> {
 protected:
  void SetUp() override {
    scene_ = test::box_room();
    write_scene(path("room.kdscene"), scene_);
    scene_ = read_scene(path("room.kdscene"));
  }

  static std::string slurp(const std::string& file) {
    std::ifstream in(file);
    return std::string(std::istreambuf_iterator<char>(in), {});
  }
  static ToolRun run(const std::string& tool, const std::string& arguments) {
    return test::run_command(test::shell_quoted(test::tool_path(tool)) + " " + arguments);
  }

  Scene scene_;
};

TEST_F(KdCli, KdbuildHelpShowsDefaults) {
  const ToolRun help = run("kdbuild", "--help");
  EXPECT_EQ(help.exit_code, 0);
  EXPECT_NE(help.out.find("--kt"), std::string::npos);
  EXPECT_NE(help.out.find("15"), std::string::npos);
  EXPECT_NE(help.out.find("--empty-bonus"), std::string::npos);
  EXPECT_EQ(run("kdbuild", "--version").exit_code, 0);
}

TEST_F(KdCli, KdbuildWritesATreeAndReportsJson) {
  const ToolRun build = run("kdbuild", path("room.kdscene") + " " + path("room.kdtree") + " --json --threads 2");
  ASSERT_EQ(build.exit_code, 0) << build.err;
  const nlohmann::json report = nlohmann::json::parse(build.out);
  const KdTree tree = read_tree(path("room.kdtree"));
  EXPECT_DOUBLE_EQ(report.at("sah_cost").get<double>(), tree.stats.sah_cost);
  EXPECT_EQ(report.at("leaves").get<uint64_t>(), tree.stats.leaves);
  for (const char* key : {"inner_nodes", "empty_leaves", "max_leaf_depth", "mean_leaf_depth", "mean_triangles_per_leaf",
                          "references_per_triangle", "build_seconds", "peak_memory_mib", "nodes", "tree_bytes",
                          "phase_seconds"})
    EXPECT_TRUE(report.contains(key)) << key;
  EXPECT_NO_THROW(check_tree_matches_scene(tree, "room.kdtree", geometry_of(scene_), "room.kdscene"));

  const ToolRun human = run("kdbuild", path("room.kdscene") + " " + path("room2.kdtree") + " --kt 30");
  ASSERT_EQ(human.exit_code, 0) << human.err;
  EXPECT_NE(human.out.find("SAH cost"), std::string::npos);
  EXPECT_EQ(read_tree(path("room2.kdtree")).settings.traversal_cost, 30.0f);
}

TEST_F(KdCli, KdbuildExactBuildsWithTheExactSweepEverywhere) {
  EXPECT_NE(run("kdbuild", "--help").out.find("--exact"), std::string::npos);
  const ToolRun exact = run("kdbuild", path("room.kdscene") + " " + path("exact.kdtree") + " --exact --json");
  ASSERT_EQ(exact.exit_code, 0) << exact.err;
  EXPECT_EQ(nlohmann::json::parse(exact.out).at("build_settings").at("binned_above"), 0);
  EXPECT_EQ(read_tree(path("exact.kdtree")).settings.binned_above, 0u);
  const ToolRun binned = run("kdbuild", path("room.kdscene") + " " + path("binned.kdtree") + " --json --binned-above 8");
  ASSERT_EQ(binned.exit_code, 0) << binned.err;
  const nlohmann::json report = nlohmann::json::parse(binned.out);
  EXPECT_EQ(report.at("build_settings").at("binned_above"), 8);
  EXPECT_EQ(report.at("build_settings").at("bins"), BuildSettings::kDefaultBins);
  EXPECT_GT(report.at("peak_memory_mib").get<double>(), 0.0);
  for (const char* phase : {"load", "prepare", "events", "subdivide", "assemble", "statistics", "write"})
    EXPECT_GE(report.at("phase_seconds").at(phase).get<double>(), 0.0) << phase;
  EXPECT_EQ(run("kdbuild", path("room.kdscene") + " " + path("t.kdtree") + " --exact --binned-above 8").exit_code, 2);
  EXPECT_EQ(run("kdbuild", path("room.kdscene") + " " + path("t.kdtree") + " --bins 1").exit_code, 2);
}

// The leaf layout: a small scene's automatic one is grouped, either is taken by name and
// recorded, the same tree in both (the same hits: kdtrace's hit files byte for byte).
TEST_F(KdCli, KdbuildLeafLayoutIsChosenByNameOrBySize) {
  const ToolRun automatic = run("kdbuild", path("room.kdscene") + " " + path("auto.kdtree") + " --json");
  ASSERT_EQ(automatic.exit_code, 0) << automatic.err;
  EXPECT_EQ(nlohmann::json::parse(automatic.out).at("build_settings").at("leaf_layout"), "grouped");
  const ToolRun paged =
      run("kdbuild", path("room.kdscene") + " " + path("paged.kdtree") + " --leaf-layout paged --json");
  ASSERT_EQ(paged.exit_code, 0) << paged.err;
  EXPECT_EQ(nlohmann::json::parse(paged.out).at("build_settings").at("leaf_layout"), "paged");
  EXPECT_EQ(read_tree(path("paged.kdtree")).settings.leaf_layout, LeafLayout::paged);
  EXPECT_NE(run("kdinfo", path("paged.kdtree")).out.find("blocks     paged"), std::string::npos);
  for (const char* tree : {"auto.kdtree", "paged.kdtree"}) {
    const ToolRun trace = run("kdtrace", path("room.kdscene") + " " + path(tree) +
                                             " --generate hard --count 20000 --quiet --hits " + path(tree) + ".hits");
    ASSERT_EQ(trace.exit_code, 0) << trace.err;
  }
  EXPECT_EQ(slurp(path("auto.kdtree.hits")), slurp(path("paged.kdtree.hits")));
  EXPECT_EQ(run("kdbuild", path("room.kdscene") + " " + path("t.kdtree") + " --leaf-layout loose").exit_code, 2);
}

TEST_F(KdCli, KdbuildRejectsBadUsageAndBadInput) {
  EXPECT_EQ(run("kdbuild", "").exit_code, 2);
  EXPECT_EQ(run("kdbuild", path("room.kdscene") + " " + path("t.kdtree") + " --empty-bonus 1.5").exit_code, 2);
  EXPECT_EQ(run("kdbuild", path("room.kdscene") + " " + path("t.kdtree") + " --max-depth 65").exit_code, 2);
  std::ofstream(path("junk.kdscene")) << "not a scene";
  const ToolRun junk = run("kdbuild", path("junk.kdscene") + " " + path("t.kdtree"));
  EXPECT_EQ(junk.exit_code, 1);
  EXPECT_EQ(junk.err.rfind("kdbuild: error: ", 0), 0u) << junk.err;
  EXPECT_FALSE(std::filesystem::exists(path("t.kdtree"))) << "no output on failure";
}

TEST_F(KdCli, KdtraceWritesTheClosestHits) {
  ASSERT_EQ(run("kdbuild", path("room.kdscene") + " " + path("room.kdtree") + " --quiet").exit_code, 0);
  const KdTree tree = read_tree(path("room.kdtree"));
  const std::vector<RayRecord> rays = random_rays(tree.bounds, 5000, 3);
  write_rays(path("rays.bin"), rays);
  const ToolRun trace = run("kdtrace", path("room.kdscene") + " " + path("room.kdtree") + " --rays " +
                                           path("rays.bin") + " --hits " + path("hits.bin") + " --json");
  ASSERT_EQ(trace.exit_code, 0) << trace.err;
  const nlohmann::json report = nlohmann::json::parse(trace.out);
  EXPECT_EQ(report.at("rays").get<size_t>(), rays.size());
  EXPECT_GT(report.at("mrays_per_s").get<double>(), 0.0);
  std::vector<HitRecord> expected;
  trace_closest(tree, rays, expected);
  const std::vector<HitRecord> hits = read_hits(path("hits.bin"));
  ASSERT_EQ(hits.size(), rays.size());
  for (size_t i = 0; i < hits.size(); ++i) ASSERT_EQ(hits[i].triangle, expected[i].triangle) << i;

  const ToolRun generated = run("kdtrace", path("room.kdscene") + " " + path("room.kdtree") +
                                               " --generate camera --width 16 --height 8 --write-rays " + path("cam.bin"));
  ASSERT_EQ(generated.exit_code, 0) << generated.err;
  EXPECT_EQ(read_rays(path("cam.bin")).size(), 128u);
  EXPECT_NE(generated.out.find("Mrays/s"), std::string::npos);
}

TEST_F(KdCli, KdtraceOnOpenClWritesTheCpuHits) {
  ASSERT_EQ(run("kdbuild", path("room.kdscene") + " " + path("room.kdtree") + " --quiet").exit_code, 0);
  const std::string trace = path("room.kdscene") + " " + path("room.kdtree") + " --generate hard --count 4000 ";
  for (const std::string stack : {"short", "depth1"}) {
    const ToolRun cpu = run("kdtrace", trace + "--stack " + stack + " --hits " + path("cpu.bin"));
    ASSERT_EQ(cpu.exit_code, 0) << cpu.err;
    const ToolRun opencl =
        run("kdtrace", trace + "--stack " + stack + " --device cpu --json --hits " + path("opencl.bin"));
    ASSERT_EQ(opencl.exit_code, 0) << opencl.err;
    const nlohmann::json report = nlohmann::json::parse(opencl.out);
    EXPECT_NE(report.at("device"), "host");
    EXPECT_GT(report.at("mrays_per_s").get<double>(), 0.0);
    EXPECT_EQ(slurp(path("cpu.bin")), slurp(path("opencl.bin"))) << "stack " << stack;
  }
}

// More threads than the machine has are taken, as pbrt's and Cycles' options take them: oneTBB
// alone would cap them at the hardware's count and warn on stderr.
TEST_F(KdCli, ThreadCountsAboveTheHardwaresAreTakenWithoutAWarning) {
  const std::string threads = " --threads " + std::to_string(thread_count(0) + 3);
  const ToolRun build = run("kdbuild", path("room.kdscene") + " " + path("room.kdtree") + threads + " --quiet");
  ASSERT_EQ(build.exit_code, 0) << build.err;
  EXPECT_EQ(build.err, "");
  const ToolRun trace = run("kdtrace", path("room.kdscene") + " " + path("room.kdtree") +
                                           " --generate random --count 20000 --quiet" + threads);
  ASSERT_EQ(trace.exit_code, 0) << trace.err;
  EXPECT_EQ(trace.err, "");
  unsigned seen = 0;
  run_with_threads(thread_count(0) + 3, [&] { seen = static_cast<unsigned>(tbb::this_task_arena::max_concurrency()); });
  EXPECT_EQ(seen, thread_count(0) + 3);
}

TEST_F(KdCli, KdinfoDescribesTreesAndSaysWhetherTheyMatchAScene) {
  ASSERT_EQ(run("kdbuild", path("room.kdscene") + " " + path("room.kdtree") + " --quiet").exit_code, 0);
  const ToolRun info = run("kdinfo", path("room.kdtree") + " --json");
  ASSERT_EQ(info.exit_code, 0) << info.err;
  const nlohmann::json tree = nlohmann::json::parse(info.out);
  EXPECT_EQ(tree.at("kind"), "kdtree");
  EXPECT_EQ(tree.at("intact"), true);
  EXPECT_EQ(tree.at("geometry_hash"), hash_hex(scene_.geometry_hash));
  EXPECT_EQ(tree.at("key"), hash_hex(tree_key(scene_.geometry_hash, BuildSettings{}.resolved(scene_.triangle_count()))));
  EXPECT_EQ(tree.at("triangles").get<size_t>(), scene_.triangle_count());

  const ToolRun match = run("kdinfo", path("room.kdscene") + " " + path("room.kdtree"));
  EXPECT_EQ(match.exit_code, 0) << match.err;
  EXPECT_NE(match.out.find("match      yes"), std::string::npos) << match.out;

  write_scene(path("other.kdscene"), test::icosphere_scene(1, {0, 0, 0}, 1));
  const ToolRun stale = run("kdinfo", path("room.kdtree") + " " + path("other.kdscene") + " --json");
  EXPECT_EQ(stale.exit_code, 1);
  EXPECT_EQ(nlohmann::json::parse(stale.out).at("match"), false);
}

TEST_F(KdCli, KdtraceRejectsStaleTreesAndBadRayFiles) {
  write_tree(path("other.kdtree"), build_kdtree(test::icosphere_scene(1, {0, 0, 0}, 1), BuildSettings{}));
  const ToolRun stale = run("kdtrace", path("room.kdscene") + " " + path("other.kdtree") + " --generate random --count 10");
  EXPECT_EQ(stale.exit_code, 1);
  EXPECT_NE(stale.err.find("stale tree"), std::string::npos) << stale.err;
  EXPECT_NE(stale.err.find("rebuild with kdbuild"), std::string::npos) << stale.err;
  // Camera rays read the scene's arrays (random rays only its geometry's identity): refused the same way.
  const ToolRun stale_camera =
      run("kdtrace", path("room.kdscene") + " " + path("other.kdtree") + " --generate camera --width 4 --height 4");
  EXPECT_EQ(stale_camera.exit_code, 1);
  EXPECT_NE(stale_camera.err.find("stale tree"), std::string::npos) << stale_camera.err;

  ASSERT_EQ(run("kdbuild", path("room.kdscene") + " " + path("room.kdtree") + " --quiet").exit_code, 0);
  std::ofstream(path("odd.bin")) << "12345";
  const ToolRun odd = run("kdtrace", path("room.kdscene") + " " + path("room.kdtree") + " --rays " + path("odd.bin"));
  EXPECT_EQ(odd.exit_code, 1);
  EXPECT_NE(odd.err.find("multiple of 32"), std::string::npos) << odd.err;
  EXPECT_EQ(run("kdtrace", path("room.kdscene") + " " + path("room.kdtree")).exit_code, 2);
  EXPECT_EQ(run("kdtrace", path("room.kdscene") + " " + path("room.kdtree") + " --generate random --device quantum").exit_code, 2);
  EXPECT_EQ(run("kdtrace", path("room.kdscene") + " " + path("room.kdtree") + " --generate random --device all").exit_code, 2);
}

// Two kdtrace hit files of the same rays hold the same bytes.
void expect_same_hit_files(const std::string& first, const std::string& second) {
  const std::vector<HitRecord> a = read_hits(first), b = read_hits(second);
  ASSERT_EQ(a.size(), b.size());
  EXPECT_EQ(std::memcmp(a.data(), b.data(), a.size() * sizeof(HitRecord)), 0);
}

// --no-lanes traces one ray at a time on the host, says so in --json, and writes the same hits.
TEST_F(KdCli, KdtraceNoLanesWritesTheSameHits) {
  ASSERT_EQ(run("kdbuild", path("room.kdscene") + " " + path("room.kdtree") + " --quiet").exit_code, 0);
  const std::string trace =
      path("room.kdscene") + " " + path("room.kdtree") + " --generate random --count 5000 --json";
  const ToolRun chosen = run("kdtrace", trace + " --hits " + path("chosen.bin"));
  const ToolRun one_ray = run("kdtrace", trace + " --no-lanes --hits " + path("one.bin"));
  ASSERT_EQ(chosen.exit_code, 0) << chosen.err;
  ASSERT_EQ(one_ray.exit_code, 0) << one_ray.err;
  EXPECT_EQ(nlohmann::json::parse(one_ray.out).at("variant"), "cpu-one-ray-per-thread+prefetch");
  const std::string variant = nlohmann::json::parse(chosen.out).at("variant");
  EXPECT_TRUE(variant == "cpu-one-ray-per-thread+prefetch" ||
              variant == "cpu-16-rays-per-thread-in-avx2-lanes+prefetch")
      << variant;
  expect_same_hit_files(path("chosen.bin"), path("one.bin"));
}

// --packets traces camera rays 8 at a time as one packet on the host, says so in --json, and writes
// the same hits; an OpenCL device has no packets.
TEST_F(KdCli, KdtracePacketsWriteTheSameHits) {
  ASSERT_EQ(run("kdbuild", path("room.kdscene") + " " + path("room.kdtree") + " --quiet").exit_code, 0);
  const std::string trace =
      path("room.kdscene") + " " + path("room.kdtree") + " --generate camera --width 64 --height 48 --json";
  const ToolRun packets = run("kdtrace", trace + " --packets --hits " + path("packets.bin"));
  const ToolRun one_ray = run("kdtrace", trace + " --no-lanes --hits " + path("one.bin"));
  ASSERT_EQ(packets.exit_code, 0) << packets.err;
  ASSERT_EQ(one_ray.exit_code, 0) << one_ray.err;
  if (packets_supported()) {
    EXPECT_EQ(nlohmann::json::parse(packets.out).at("variant"), "cpu-8-ray-packets-in-avx2");
  }
  expect_same_hit_files(path("packets.bin"), path("one.bin"));
  const ToolRun opencl = run("kdtrace", trace + " --packets --device cpu");
  EXPECT_EQ(opencl.exit_code, 2);
  EXPECT_NE(opencl.err.find("--packets is for --device host"), std::string::npos) << opencl.err;
}

}  // namespace
}  // namespace kdray
