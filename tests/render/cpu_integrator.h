// The path tracer's C++ build against its OpenCL kernel: librender's host renderer (kernels/
// pt_path.h compiled with every feature in, librender/src/render_host_pixels.cpp) and the PoCL
// kernel built for the scene's own features render the same film, every pixel's fixed-point sums
// bit for bit. Each test names the features its scene's kernel is built with, so together they
// show that a feature compiled in but unused changes no bit. The host renderer and the kernels
// are compiled without contraction into FMA (kernels/kd_compat.h).
#pragma once

#include "render_fixture.h"

#include <kdray/render.h>

#include <gtest/gtest.h>

#include <algorithm>
#include <cstdint>
#include <cstdlib>
#include <set>
#include <sstream>
#include <string>
#include <vector>

namespace kdray::test {
namespace {

// The -D options of a kernel build's option string.
inline std::set<std::string> option_defines(const std::string& options) {
  std::set<std::string> defines;
  std::istringstream words(options);
  for (std::string word; words >> word;) {
    if (word.rfind("-D", 0) == 0) defines.insert(word);
  }
  return defines;
}

// Renders the scene on PoCL and on the host (with `threads`, 0: all cores), in each of the host's
// builds of the path tracer (the one for this CPU, which takes 8 paths at a time in lanes where
// the scene is of their kind; the same one path at a time, as KDRAY_HOST_LANES=off asks; the
// generic one that KDRAY_HOST_ISA names), and expects the same film sums, and the kernel built
// with exactly the -D options `kernel_defines`. Returns the number of pixels whose radiance is not
// zero (so a caller can check the scene is lit).
inline size_t expect_host_matches_kernel(Scene& scene, const RenderSettings& settings,
                                         const std::set<std::string>& kernel_defines, unsigned threads = 0) {
  const KdTree tree = tree_for(scene);
  // and, on a CPU, the bounce's sample values in lanes (kernels/pt_rng.h) and a leaf's triangles
  // tested four at a time (kernels/kd_scene_view.h)
  std::set<std::string> cpu_defines = kernel_defines;
  cpu_defines.insert("-DPT_BOUNCE_BITS_IN_LANES");
  cpu_defines.insert("-DKD_LEAF_TESTS_IN_LANES");
  EXPECT_EQ(option_defines(kernel_feature_options(scene, settings, DeviceSelection{"cpu"})), cpu_defines)
      << "the scene's kernel features";
  const Film film = render(scene, tree, settings, DeviceSelection{"cpu"});
  const size_t channels = film.channels.size();
  size_t lit = 0;
  for (size_t i = 0; i < film.sums.size(); i += channels) lit += film.sums[i] || film.sums[i + 1] || film.sums[i + 2];
  struct HostBuild {
    const char* variable;
    const char* value;
  };
  for (const HostBuild& build : {HostBuild{nullptr, nullptr}, HostBuild{"KDRAY_HOST_LANES", "off"},
                                 HostBuild{"KDRAY_HOST_ISA", "generic"}}) {
    if (build.variable) setenv(build.variable, build.value, 1);
    DeviceSelection host{kHostDevice};
    host.threads = threads;
    RenderStats stats;
    const Film cpu = render(scene, tree, settings, host, &stats);
    if (build.variable) unsetenv(build.variable);
    EXPECT_EQ(stats.device, kHostDevice);
    const bool x86_64_v3 = stats.build_source.rfind("built in, x86-64-v3", 0) == 0;
    if (build.variable == nullptr && x86_64_v3) {
      EXPECT_EQ(stats.build_source, "built in, x86-64-v3, paths in lanes");  // every scene of the tests
    } else if (build.variable != nullptr && std::string(build.variable) == "KDRAY_HOST_ISA") {
      EXPECT_EQ(stats.build_source, "built in, generic");
    } else if (x86_64_v3) {
      EXPECT_EQ(stats.build_source, "built in, x86-64-v3");
    }
    // The generic build computes each sample value alone, the x86-64-v3 one in lanes.
    EXPECT_EQ(option_defines(stats.kernel_options).count("-DPT_BOUNCE_BITS_IN_LANES"), x86_64_v3 ? 1u : 0u)
        << stats.kernel_options;
    EXPECT_EQ(cpu.sums.size(), film.sums.size());
    size_t mismatches = 0;
    for (size_t i = 0; i < std::min(cpu.sums.size(), film.sums.size()); ++i) {
      if (cpu.sums[i] == film.sums[i]) continue;
      if (++mismatches <= 5) {
        ADD_FAILURE() << stats.build_source << ": pixel " << i / channels << " channel " << film.channels[i % channels]
                      << ": C++ " << cpu.sums[i] << ", kernel " << film.sums[i];
      }
    }
    EXPECT_EQ(mismatches, 0u) << "of " << cpu.sums.size() << " film sums, " << stats.build_source;
  }
  return lit;
}

}  // namespace
}  // namespace kdray::test
