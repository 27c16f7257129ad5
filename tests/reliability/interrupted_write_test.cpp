// Interrupted writes: kdconvert, kdbuild and kdrender are killed with SIGKILL at random moments,
// many times, while they replace an existing output. After every kill the output must be the
// previous complete file or the new complete one (never torn, never missing), and a later run
// that completes must leave no temporary file behind, whatever the killed runs left.
#include <kdray/atomic_file.h>
#include <kdray/image_io.h>

#include <subprocess.h>
#include "test_corpus.h"

#include <gtest/gtest.h>

#include <chrono>
#include <filesystem>
#include <fstream>
#include <functional>
#include <random>
#include <sstream>

#include <sys/wait.h>
#include <unistd.h>

namespace kdray {
namespace {

namespace fs = std::filesystem;
using test::run_process;
using test::tool_path;

std::string bytes_of(const fs::path& path) {
  std::ifstream file(path, std::ios::binary);
  std::ostringstream bytes;
  bytes << file.rdbuf();
  return bytes.str();
}

std::vector<std::string> temporaries_in(const fs::path& folder) {
  std::vector<std::string> found;
  for (const auto& entry : fs::directory_iterator(folder))
    if (entry.path().filename().string().find(".tmp-") != std::string::npos) found.push_back(entry.path().string());
  return found;
}

// A flat grid of 2*n*n triangles: big enough that writing its scene and tree takes a while.
void write_grid_obj(const fs::path& path, int n) {
  std::ofstream obj(path);
  for (int y = 0; y <= n; ++y)
    for (int x = 0; x <= n; ++x) obj << "v " << x << ' ' << y << ' ' << ((x * 7 + y * 3) % 5) * 0.1 << '\n';
  for (int y = 0; y < n; ++y)
    for (int x = 0; x < n; ++x) {
      const int a = y * (n + 1) + x + 1, b = a + 1, c = a + n + 1, d = c + 1;
      obj << "f " << a << ' ' << b << ' ' << d << "\nf " << a << ' ' << d << ' ' << c << '\n';
    }
}

class InterruptedWrite : public ::testing::Test {
 protected:
  void SetUp() override {
    dir_ = test::make_temp_dir("interrupted");
    // The renderer's program cache lives here too, so killed cache writes are checked as well.
    ::setenv("KDRAY_CACHE_DIR", (dir_ / "cache").c_str(), 1);
    write_grid_obj(dir_ / "grid.obj", 220);
    write_grid_obj(dir_ / "small.obj", 2);
  }
  void TearDown() override {
    ::unsetenv("KDRAY_CACHE_DIR");
    fs::remove_all(dir_);
  }

  void run_ok(const std::vector<std::string>& argv) {
    const auto result = run_process(argv, 300);
    ASSERT_TRUE(result.exited && result.exit_code == 0) << argv[0] << ": " << result.err;
  }

  // `previous` has already written `target`; `command` replaces it. `is_new` says whether a file
  // is the complete new output.
  void kill_repeatedly(const std::vector<std::string>& command, const fs::path& target,
                       const std::function<bool(const fs::path&)>& is_new) {
    const std::string previous = bytes_of(target);
    ASSERT_FALSE(previous.empty());
    ASSERT_FALSE(is_new(target)) << "the previous output must differ from the new one";
    // One complete run elsewhere gives the duration to draw kill moments from.
    std::vector<std::string> timing_run = command;
    const fs::path timing_target = dir_ / ("timing-" + target.filename().string());
    std::replace(timing_run.begin(), timing_run.end(), target.string(), timing_target.string());
    const auto start = std::chrono::steady_clock::now();
    run_ok(timing_run);
    const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    ASSERT_TRUE(is_new(timing_target));
    fs::remove(timing_target);

    std::mt19937 random(12345);
    std::uniform_real_distribution<double> moment(0.0, 1.2 * seconds);
    int interrupted = 0, torn_or_missing = 0;
    for (int attempt = 0; attempt < kAttempts; ++attempt) {
      const auto result = run_process(command, moment(random));
      interrupted += result.timed_out;
      if (!result.timed_out) {
        EXPECT_EQ(result.exit_code, 0) << result.err;
      }
      const bool intact = fs::exists(target) && (bytes_of(target) == previous || is_new(target));
      torn_or_missing += !intact;
      EXPECT_TRUE(intact) << target << " after a kill at attempt " << attempt;
    }
    RecordProperty("interrupted_runs", interrupted);
    EXPECT_EQ(torn_or_missing, 0);
    // Whatever the killed writers left is cleared by the next writer of the same target.
    run_ok(command);
    EXPECT_TRUE(is_new(target));
    EXPECT_EQ(temporaries_in(target.parent_path()), std::vector<std::string>{});
    if (fs::exists(dir_ / "cache")) {
      for (const auto& entry : fs::recursive_directory_iterator(dir_ / "cache"))
        EXPECT_EQ(entry.path().filename().string().find(".tmp-"), std::string::npos)
            << "cache temporary of a dead writer left: " << entry.path();
    }
  }

  static constexpr int kAttempts = 24;
  fs::path dir_;
};

TEST_F(InterruptedWrite, KdconvertLeavesOldOrNewScene) {
  const fs::path target = dir_ / "out.kdscene";
  run_ok({tool_path("kdconvert"), "--quiet", (dir_ / "grid.obj").string(), (dir_ / "reference.kdscene").string()});
  const std::string reference = bytes_of(dir_ / "reference.kdscene");
  run_ok({tool_path("kdconvert"), "--quiet", (dir_ / "small.obj").string(), target.string()});
  kill_repeatedly({tool_path("kdconvert"), "--quiet", (dir_ / "grid.obj").string(), target.string()}, target,
                  [&](const fs::path& file) { return bytes_of(file) == reference; });
}

TEST_F(InterruptedWrite, KdbuildLeavesOldOrNewTree) {
  const fs::path scene = dir_ / "grid.kdscene", small = dir_ / "small.kdscene", target = dir_ / "out.kdtree";
  run_ok({tool_path("kdconvert"), "--quiet", (dir_ / "grid.obj").string(), scene.string()});
  run_ok({tool_path("kdconvert"), "--quiet", (dir_ / "small.obj").string(), small.string()});
  run_ok({tool_path("kdbuild"), "--quiet", scene.string(), (dir_ / "reference.kdtree").string()});
  const std::string reference = bytes_of(dir_ / "reference.kdtree");
  run_ok({tool_path("kdbuild"), "--quiet", small.string(), target.string()});
  kill_repeatedly({tool_path("kdbuild"), "--quiet", scene.string(), target.string()}, target,
                  [&](const fs::path& file) { return bytes_of(file) == reference; });
}

TEST_F(InterruptedWrite, KdrenderLeavesOldOrNewImage) {
  const fs::path scene = dir_ / "cornell.kdscene", tree = dir_ / "cornell.kdtree", target = dir_ / "out.exr";
  run_ok({tool_path("kdconvert"), "--quiet", test::cornell_obj(), scene.string()});
  run_ok({tool_path("kdbuild"), "--quiet", scene.string(), tree.string()});
  const std::vector<std::string> render = {tool_path("kdrender"), scene.string(), tree.string(), "--quiet",
                                           "--width", "64", "--height", "64", "--spp", "4", "--seed", "3"};
  auto with_output = [&](std::vector<std::string> argv, const fs::path& output, const char* spp) {
    argv[9] = spp;
    argv.insert(argv.end(), {"-o", output.string()});
    return argv;
  };
  run_ok(with_output(render, dir_ / "reference.exr", "4"));
  const Film reference = read_film_exr((dir_ / "reference.exr").string());
  run_ok(with_output(render, target, "1"));
  // The image carries its render time, so "new" means the same samples, not the same bytes.
  kill_repeatedly(with_output(render, target, "4"), target, [&](const fs::path& file) {
    const Film film = read_film_exr(file.string());
    return film.sample_count == reference.sample_count && film.sums == reference.sums;
  });
}

TEST(AtomicFile, RemovesOnlyDeadWritersTemporariesOfItsTarget) {
  const fs::path dir = test::make_temp_dir("atomic");
  const pid_t dead = ::fork();
  if (dead == 0) ::_exit(0);
  ::waitpid(dead, nullptr, 0);
  const std::string live = std::to_string(::getpid());
  const std::vector<std::string> names = {
      "out.tmp-" + std::to_string(dead) + "-0123abcd.exr",  // dead writer of out.exr: removed
      "out.tmp-" + live + "-0123abcd.exr",                  // a live writer: kept
      "out.tmp-" + std::to_string(dead) + "-0123abcd.png",  // another target: kept
      "other.tmp-" + std::to_string(dead) + "-0123abcd.exr",
      "out.tmp-" + std::to_string(dead) + "-xyz.exr",  // not a temporary name
  };
  for (const std::string& name : names) std::ofstream(dir / name) << "partial";
  EXPECT_EQ(remove_dead_writers_temporaries((dir / "out.exr").string()), 1u);
  EXPECT_FALSE(fs::exists(dir / names[0]));
  for (size_t i = 1; i < names.size(); ++i) EXPECT_TRUE(fs::exists(dir / names[i])) << names[i];

  write_file_atomically((dir / "out.exr").string(), "abc", 3);
  EXPECT_EQ(bytes_of(dir / "out.exr"), "abc");
  EXPECT_TRUE(fs::exists(dir / names[1])) << "a live writer's temporary was removed";
  fs::remove_all(dir);
}

TEST(AtomicFile, FailedWriteLeavesTargetAndNoTemporary) {
  const fs::path dir = test::make_temp_dir("atomic");
  write_file_atomically((dir / "out.bin").string(), "old", 3);
  {
    AtomicFile file((dir / "out.bin").string());
    std::ofstream(file.temporary_path()) << "half";
    // Destroyed without commit(), as when the writer throws.
  }
  EXPECT_EQ(bytes_of(dir / "out.bin"), "old");
  EXPECT_EQ(temporaries_in(dir), std::vector<std::string>{});
  fs::remove_all(dir);
}

}  // namespace
}  // namespace kdray
