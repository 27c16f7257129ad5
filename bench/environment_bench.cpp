// Environment map preparation times for bench/lights.sh: reading the image,
// building the sampling table, the mean luminance, each the median of several runs after one
// warm-up (which also pays OpenImageIO's one-off start-up). Wall and process CPU seconds (all
// threads): on a shared machine the CPU time is the steadier figure.
#include <kdray/environment.h>

#include <nlohmann/json.hpp>

#include <algorithm>
#include <chrono>
#include <cstdlib>
#include <ctime>
#include <cstdio>
#include <vector>

int main(int argc, char** argv) {
  if (argc < 2) {
    std::fprintf(stderr, "usage: environment_bench MAP [RUNS]\n");
    return 2;
  }
  const int runs = argc > 2 ? std::max(1, std::atoi(argv[2])) : 5;
  using Clock = std::chrono::steady_clock;
  auto seconds = [](Clock::time_point a) { return std::chrono::duration<double>(Clock::now() - a).count(); };
  std::vector<double> load, load_cpu, table, table_cpu, mean;
  auto cpu_seconds = [](std::clock_t a) { return double(std::clock() - a) / CLOCKS_PER_SEC; };
  kdray::Environment env = kdray::load_environment(argv[1]);
  for (int run = 0; run < runs; ++run) {
    auto start = Clock::now();
    std::clock_t cpu = std::clock();
    env = kdray::load_environment(argv[1]);
    load.push_back(seconds(start));
    load_cpu.push_back(cpu_seconds(cpu));
    start = Clock::now();
    cpu = std::clock();
    std::vector<float> cdf = kdray::environment_sampling_table(env);
    table.push_back(seconds(start));
    table_cpu.push_back(cpu_seconds(cpu));
    start = Clock::now();
    volatile double m = kdray::environment_mean_luminance(env);
    (void)m;
    mean.push_back(seconds(start));
  }
  auto median = [](std::vector<double> v) {
    std::sort(v.begin(), v.end());
    return v[v.size() / 2];
  };
  std::printf("%s\n", nlohmann::json({{"map", argv[1]}, {"width", env.width}, {"height", env.height}, {"runs", runs},
                                      {"load_seconds", median(load)}, {"load_cpu_seconds", median(load_cpu)},
                                      {"table_seconds", median(table)}, {"table_cpu_seconds", median(table_cpu)},
                                      {"mean_luminance_seconds", median(mean)}})
                          .dump()
                          .c_str());
  return 0;
}
