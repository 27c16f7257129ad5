// The tree cache from the command line: kdbuild --cache (hits, misses, damaged entries, concurrent
// builders, eviction), kdinfo on a cache folder, and kdrender / kdtrace finding their tree there.
#include <subprocess.h>
#include <test_corpus.h>

#include <nlohmann/json.hpp>

#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <iterator>
#include <random>
#include <string>

#include <sys/stat.h>

namespace kdray {
namespace {

namespace fs = std::filesystem;

class TreeCacheCli : public test::TempDirTest<> {
 protected:
  void SetUp() override {
    for (const char* file : {"cornell-box.obj", "cornell-box.mtl"})
      fs::copy_file(fs::path(KDRAY_SOURCE_DIR) / "samples" / file, dir_ / file);
    convert("cornell-box.obj", "box.kdscene");
  }
  std::string cache() const { return path("cache"); }

  // The tool's exit code and stdout; stderr goes to err.txt.
  test::ToolRun tool(const std::string& name, const std::string& arguments) const {
    return test::run_command(test::tool_path(name) + " " + arguments + " 2>" + test::shell_quoted(path("err.txt")));
  }
  std::string stderr_text() const { return slurp(path("err.txt")); }
  void convert(const std::string& asset, const std::string& scene) const {
    const test::ToolRun run = tool("kdconvert", test::shell_quoted(path(asset)) + " " + test::shell_quoted(path(scene)) + " --quiet");
    ASSERT_EQ(run.exit_code, 0) << stderr_text();
  }
  // kdbuild --cache ... --json; the parsed report (exit code checked).
  nlohmann::json build(const std::string& scene, const std::string& more = "") const {
    const test::ToolRun run = tool("kdbuild", "--cache " + test::shell_quoted(cache()) + " " +
                                                  test::shell_quoted(path(scene)) + " " + more + " --json --quiet");
    EXPECT_EQ(run.exit_code, 0) << stderr_text();
    return run.exit_code == 0 ? nlohmann::json::parse(run.out) : nlohmann::json::object();
  }
  static std::string slurp(const std::string& file) {
    std::ifstream in(file, std::ios::binary);
    return std::string(std::istreambuf_iterator<char>(in), {});
  }
  static void replace_in_file(const std::string& file, const std::string& from, const std::string& to) {
    std::string text = slurp(file);
    const size_t at = text.find(from);
    ASSERT_NE(at, std::string::npos) << from;
    text.replace(at, from.size(), to);
    std::ofstream(file, std::ios::binary | std::ios::trunc) << text;
  }
  size_t cache_entries() const {
    size_t count = 0;
    for (const fs::directory_entry& entry : fs::directory_iterator(cache())) count += entry.path().extension() == ".kdtree";
    return count;
  }
};

TEST_F(TreeCacheCli, AMissBuildsAndAHitCopiesTheSameBytes) {
  const nlohmann::json first = build("box.kdscene", test::shell_quoted(path("a.kdtree")));
  EXPECT_EQ(first.at("cache"), "miss");
  const nlohmann::json second = build("box.kdscene", test::shell_quoted(path("b.kdtree")));
  EXPECT_EQ(second.at("cache"), "hit");
  EXPECT_EQ(second.at("key"), first.at("key"));
  EXPECT_EQ(second.at("sah_cost"), first.at("sah_cost"));
  EXPECT_FALSE(second.contains("build_seconds"));
  EXPECT_TRUE(slurp(path("a.kdtree")) == slurp(path("b.kdtree")));
  EXPECT_TRUE(slurp(path("b.kdtree")) == slurp(second.at("cache_entry").get<std::string>()));
  struct stat output {};
  ASSERT_EQ(::stat(path("b.kdtree").c_str(), &output), 0);
  EXPECT_EQ(output.st_nlink, 1u) << "a hit must not be a hard link to the entry";
  // A tree from the cache serves the scene like any other.
  EXPECT_EQ(tool("kdinfo", test::shell_quoted(path("box.kdscene")) + " " + test::shell_quoted(path("b.kdtree"))).exit_code, 0);
  // Without OUTPUT, kdbuild only makes sure the cache holds the tree.
  EXPECT_EQ(build("box.kdscene").at("cache"), "hit");
  EXPECT_EQ(cache_entries(), 1u);
}

TEST_F(TreeCacheCli, AMaterialChangeKeepsTheKeyAndAGeometryChangeDoesNot) {
  const nlohmann::json original = build("box.kdscene");
  replace_in_file(path("cornell-box.mtl"), "Kd 0.725 0.71 0.68", "Kd 0.1 0.9 0.1");
  convert("cornell-box.obj", "recoloured.kdscene");
  const nlohmann::json recoloured = build("recoloured.kdscene", test::shell_quoted(path("recoloured.kdtree")));
  EXPECT_NE(recoloured.at("scene_hash"), original.at("scene_hash"));
  EXPECT_EQ(recoloured.at("geometry_hash"), original.at("geometry_hash"));
  EXPECT_EQ(recoloured.at("key"), original.at("key"));
  EXPECT_EQ(recoloured.at("cache"), "hit");
  EXPECT_EQ(tool("kdinfo", test::shell_quoted(path("recoloured.kdscene")) + " " + test::shell_quoted(path("recoloured.kdtree"))).exit_code, 0);

  replace_in_file(path("cornell-box.obj"), "\nv ", "\nv 1 2 3\nv ");
  replace_in_file(path("cornell-box.obj"), "\nf ", "\nf -1 1 2\nf ");
  convert("cornell-box.obj", "reshaped.kdscene");
  const nlohmann::json reshaped = build("reshaped.kdscene");
  EXPECT_NE(reshaped.at("geometry_hash"), original.at("geometry_hash"));
  EXPECT_NE(reshaped.at("key"), original.at("key"));
  EXPECT_EQ(reshaped.at("cache"), "miss");
  // Other build settings are another key too.
  const nlohmann::json costly = build("box.kdscene", "--kt 30");
  EXPECT_NE(costly.at("key"), original.at("key"));
  EXPECT_EQ(costly.at("cache"), "miss");
  EXPECT_EQ(cache_entries(), 3u);
}

TEST_F(TreeCacheCli, ADamagedEntryIsRemovedRebuiltAndWarnedAbout) {
  const std::string entry = build("box.kdscene").at("cache_entry");
  std::string bytes = slurp(entry);
  bytes[bytes.size() / 2] ^= 0x10;
  std::ofstream(entry, std::ios::binary | std::ios::trunc) << bytes;
  const nlohmann::json again = build("box.kdscene", test::shell_quoted(path("out.kdtree")));
  EXPECT_EQ(again.at("cache"), "miss");
  EXPECT_NE(stderr_text().find("kdbuild: warning: " + entry + ": damaged cache entry removed"), std::string::npos)
      << stderr_text();
  EXPECT_TRUE(slurp(path("out.kdtree")) == slurp(entry));
  EXPECT_EQ(build("box.kdscene").at("cache"), "hit");
}

TEST_F(TreeCacheCli, ConcurrentBuildersOfOneKeyAllSucceedWithOneEntry) {
  // A mesh big enough that the builds overlap: a jittered 150 x 150 grid.
  {
    std::ofstream obj(path("grid.obj"));
    std::mt19937 random(3);
    std::uniform_real_distribution<float> jitter(0.0f, 0.3f);
    const int n = 150;
    for (int y = 0; y <= n; ++y)
      for (int x = 0; x <= n; ++x) obj << "v " << x << " " << y << " " << jitter(random) << "\n";
    for (int y = 0; y < n; ++y)
      for (int x = 0; x < n; ++x) {
        const int a = y * (n + 1) + x + 1, b = a + 1, c = a + n + 1, d = c + 1;
        obj << "f " << a << " " << b << " " << d << "\nf " << a << " " << d << " " << c << "\n";
      }
  }
  convert("grid.obj", "grid.kdscene");
  std::string command = "cd " + test::shell_quoted(dir_.string()) + " && for i in 0 1 2 3; do " +
                        test::tool_path("kdbuild") + " --cache cache grid.kdscene out$i.kdtree --threads 1 --json " +
                        "> report$i.json 2>> err.txt & done; wait; for i in 0 1 2 3; do grep -q '\"cache\"' report$i.json || exit 1; done";
  ASSERT_EQ(test::run_command(command).exit_code, 0) << stderr_text();
  EXPECT_EQ(stderr_text(), "");
  EXPECT_EQ(cache_entries(), 1u);
  std::string entry;
  for (int i = 0; i < 4; ++i) {
    const nlohmann::json report = nlohmann::json::parse(slurp(path("report" + std::to_string(i) + ".json")));
    entry = path(report.at("cache_entry"));
    EXPECT_TRUE(slurp(path("out" + std::to_string(i) + ".kdtree")) == slurp(entry)) << i;
  }
  EXPECT_EQ(tool("kdinfo", test::shell_quoted(entry)).exit_code, 0);
  for (const fs::directory_entry& file : fs::directory_iterator(cache()))
    EXPECT_EQ(file.path().filename().string().find(".tmp-"), std::string::npos) << file.path();
}

TEST_F(TreeCacheCli, MaxBytesEvictsTheLeastRecentlyUsedEntries) {
  std::vector<nlohmann::json> built;
  for (const char* kt : {"10", "20", "30", "40"}) built.push_back(build("box.kdscene", std::string("--kt ") + kt));
  // Last use, oldest first: kt 20, kt 10, kt 30, kt 40.
  const auto now = fs::file_time_type::clock::now();
  const int hours_ago[] = {3, 4, 2, 1};
  for (size_t i = 0; i < built.size(); ++i)
    fs::last_write_time(built[i].at("cache_entry").get<std::string>(), now - std::chrono::hours(hours_ago[i]));
  const nlohmann::json listing = nlohmann::json::parse(tool("kdinfo", test::shell_quoted(cache()) + " --json").out);
  ASSERT_EQ(listing.at("entries").size(), 4u);
  const nlohmann::json& entries = listing.at("entries");  // most recently used first
  const uint64_t oldest_two = entries[3].at("bytes").get<uint64_t>() + entries[2].at("bytes").get<uint64_t>();

  // Room for all but the two least recently used: they go, oldest first.
  const nlohmann::json hit = build("box.kdscene", "--kt 40 --cache-max-bytes " +
                                                      std::to_string(listing.at("total_bytes").get<uint64_t>() - oldest_two));
  EXPECT_EQ(hit.at("cache"), "hit");
  ASSERT_EQ(hit.at("evicted").size(), 2u);
  EXPECT_EQ(hit.at("evicted")[0], built[1].at("key"));
  EXPECT_EQ(hit.at("evicted")[1], built[0].at("key"));
  EXPECT_FALSE(fs::exists(built[1].at("cache_entry").get<std::string>()));
  EXPECT_TRUE(fs::exists(built[2].at("cache_entry").get<std::string>()));
  EXPECT_EQ(cache_entries(), 2u);
  // The entry just used is kept even when it alone is over the limit.
  const nlohmann::json tight = build("box.kdscene", "--kt 40 --cache-max-bytes 1");
  EXPECT_EQ(tight.at("cache"), "hit");
  EXPECT_EQ(tight.at("evicted"), nlohmann::json({built[2].at("key")}));
  EXPECT_EQ(cache_entries(), 1u);
  EXPECT_EQ(build("box.kdscene", "--kt 40").at("cache"), "hit");
}

TEST_F(TreeCacheCli, KdinfoListsACache) {
  const nlohmann::json a = build("box.kdscene");
  fs::copy_file(path("box.kdscene"), path("same-geometry.kdscene"));
  build("same-geometry.kdscene");
  const nlohmann::json b = build("box.kdscene", "--kt 30");
  fs::last_write_time(a.at("cache_entry").get<std::string>(), fs::file_time_type::clock::now() - std::chrono::hours(1));

  const test::ToolRun listing = tool("kdinfo", test::shell_quoted(cache()) + " --json");
  ASSERT_EQ(listing.exit_code, 0) << stderr_text();
  const nlohmann::json cache_json = nlohmann::json::parse(listing.out);
  EXPECT_EQ(cache_json.at("kind"), "tree cache");
  const nlohmann::json& entries = cache_json.at("entries");
  ASSERT_EQ(entries.size(), 2u);
  EXPECT_EQ(entries[0].at("key"), b.at("key"));  // most recently used first
  EXPECT_EQ(entries[1].at("key"), a.at("key"));
  EXPECT_EQ(entries[1].at("scenes"), nlohmann::json({path("box.kdscene"), path("same-geometry.kdscene")}));
  EXPECT_GT(entries[1].at("bytes").get<uint64_t>(), fs::file_size(a.at("cache_entry").get<std::string>()));
  EXPECT_EQ(entries[1].at("last_use").get<std::string>().size(), 20u);  // 2026-01-02T03:04:05Z

  const test::ToolRun text = tool("kdinfo", test::shell_quoted(cache()));
  ASSERT_EQ(text.exit_code, 0);
  EXPECT_NE(text.out.find("2 entries"), std::string::npos) << text.out;
  EXPECT_NE(text.out.find(a.at("key").get<std::string>()), std::string::npos) << text.out;
  EXPECT_NE(text.out.find(path("same-geometry.kdscene")), std::string::npos) << text.out;
}

TEST_F(TreeCacheCli, KdbuildNeedsAnOutputOrACache) {
  EXPECT_EQ(tool("kdbuild", test::shell_quoted(path("box.kdscene"))).exit_code, 2);
  EXPECT_NE(stderr_text().find("--cache"), std::string::npos) << stderr_text();
  EXPECT_EQ(tool("kdbuild", test::shell_quoted(path("box.kdscene")) + " out.kdtree --cache-max-bytes 10").exit_code, 2);
}

TEST_F(TreeCacheCli, KdtraceAndKdrenderFindOrBuildTheirTreeInACache) {
  const std::string scene = test::shell_quoted(path("box.kdscene"));
  const test::ToolRun traced =
      tool("kdtrace", scene + " --cache " + test::shell_quoted(cache()) + " --generate random --count 1000 --json");
  ASSERT_EQ(traced.exit_code, 0) << stderr_text();
  EXPECT_EQ(cache_entries(), 1u);
  ASSERT_EQ(tool("kdbuild", scene + " " + test::shell_quoted(path("box.kdtree")) + " --quiet").exit_code, 0);
  const test::ToolRun direct =
      tool("kdtrace", scene + " " + test::shell_quoted(path("box.kdtree")) + " --generate random --count 1000 --json");
  ASSERT_EQ(direct.exit_code, 0) << stderr_text();
  EXPECT_EQ(nlohmann::json::parse(traced.out).at("hits"), nlohmann::json::parse(direct.out).at("hits"));

  const std::string small = " --width 8 --height 8 --spp 1 --quiet";
  ASSERT_EQ(tool("kdrender", scene + " --cache " + test::shell_quoted(cache()) + " -o " +
                                 test::shell_quoted(path("cached.exr")) + small).exit_code, 0) << stderr_text();
  ASSERT_EQ(tool("kdrender", scene + " " + test::shell_quoted(path("box.kdtree")) + " -o " +
                                 test::shell_quoted(path("direct.exr")) + small).exit_code, 0) << stderr_text();
  EXPECT_EQ(tool("kdcompare", test::shell_quoted(path("cached.exr")) + " " + test::shell_quoted(path("direct.exr")) +
                                  " --threshold rmse=0").exit_code, 0);
  EXPECT_EQ(cache_entries(), 1u);
  // A tree path and a cache at once, or neither, is a usage error.
  EXPECT_EQ(tool("kdrender", scene + " " + test::shell_quoted(path("box.kdtree")) + " --cache " +
                                 test::shell_quoted(cache()) + " -o x.png").exit_code, 2);
  EXPECT_EQ(tool("kdtrace", scene + " --generate random").exit_code, 2);
}

}  // namespace
}  // namespace kdray
