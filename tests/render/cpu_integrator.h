// The path tracer's C++ build (kernels/pt_path.h compiled as C++) against its OpenCL kernel on
// PoCL: every pixel's fixed-point film sums, bit for bit. A test file defines the KD_FEATURE_*
// macros its scene's kernel is built with, then includes this header, which compiles the device
// code in an anonymous namespace (each test file is its own feature set). The test target is
// compiled with -ffp-contract=off, as the kernels are (kernels/kd_compat.h).
#pragma once

#include "render_fixture.h"

#include <kdray/render.h>

#include <kernels/kd_types.h>
#include <kernels/kd_vector.h>
#include <kernels/pt_types.h>

#include <gtest/gtest.h>

#include <algorithm>
#include <cstdint>
#include <set>
#include <sstream>
#include <string>
#include <vector>

namespace {
#include <kernels/pt_path.h>
}  // namespace

namespace kdray::test {
namespace {

// The -D options this file's device code was compiled with, as the kernel build spells them.
std::set<std::string> compiled_defines() {
  std::set<std::string> defines;
#ifdef KD_FEATURE_EMISSION
  defines.insert("-DKD_FEATURE_EMISSION");
#endif
#ifdef KD_FEATURE_MIRROR
  defines.insert("-DKD_FEATURE_MIRROR");
#endif
#ifdef KD_FEATURE_GLOSSY
  defines.insert("-DKD_FEATURE_GLOSSY");
#endif
#ifdef KD_FEATURE_GLASS
  defines.insert("-DKD_FEATURE_GLASS");
#endif
#ifdef KD_FEATURE_METALLIC_ROUGHNESS
  defines.insert("-DKD_FEATURE_METALLIC_ROUGHNESS");
#endif
#ifdef KD_FEATURE_ALPHA
  defines.insert("-DKD_FEATURE_ALPHA");
#endif
#ifdef KD_FEATURE_TEXTURES
  defines.insert("-DKD_FEATURE_TEXTURES");
#endif
#ifdef KD_FEATURE_METAL_ROUGH_TEXTURE
  defines.insert("-DKD_FEATURE_METAL_ROUGH_TEXTURE");
#endif
#ifdef KD_FEATURE_NORMAL_MAP
  defines.insert("-DKD_FEATURE_NORMAL_MAP");
#endif
#ifdef KD_FEATURE_EMISSIVE_TEXTURE
  defines.insert("-DKD_FEATURE_EMISSIVE_TEXTURE");
#endif
#ifdef KD_FEATURE_NORMALS
  defines.insert("-DKD_FEATURE_NORMALS");
#endif
#ifdef KD_FEATURE_ENVIRONMENT
  defines.insert("-DKD_FEATURE_ENVIRONMENT");
#endif
#ifdef KD_FEATURE_PUNCTUAL
  defines.insert("-DKD_FEATURE_PUNCTUAL");
#endif
#ifdef KD_MIS_OFF
  defines.insert("-DKD_MIS_OFF");
#endif
  return defines;
}

// The -D options of a kernel build's option string.
std::set<std::string> option_defines(const std::string& options) {
  std::set<std::string> defines;
  std::istringstream words(options);
  for (std::string word; words >> word;) {
    if (word.rfind("-D", 0) == 0) defines.insert(word);
  }
  return defines;
}

// The film sums of every pixel for the inputs' sample range, computed by the C++ build from the
// kernel's own buffers.
std::vector<int64_t> cpu_film(const KernelInputs& inputs) {
  size_t next = 0;
#define KD_CPU_ARG(type, name) const type* name = reinterpret_cast<const type*>(inputs.buffers.at(next++).data());
  PT_SCENE_BUFFERS(KD_CPU_ARG, KD_CPU_ARG)
#undef KD_CPU_ARG
  const PtRenderParams* params = reinterpret_cast<const PtRenderParams*>(inputs.params.data());
  const PtSceneData scene = PT_MAKE_SCENE();
  const uint32_t channels = params->film_channels, pixels = params->width * params->height;
  std::vector<int64_t> film(size_t(pixels) * channels, 0);
  for (uint32_t pixel = 0; pixel < pixels; ++pixel) {
    long sums[PT_MAX_FILM_CHANNELS] = {0};
    uint nonfinite = 0;
    for (uint32_t i = 0; i < params->sample_count; ++i) {
      pt_render_sample(&scene, params, pixel, params->sample_offset + i, sums, &nonfinite);
    }
    for (uint32_t c = 0; c < channels; ++c) film[size_t(pixel) * channels + c] = sums[c];
  }
  return film;
}

// Renders the scene on PoCL and with the C++ build and expects the same film sums. Returns the
// number of pixels whose radiance is not zero (so a caller can check the scene is lit).
size_t expect_cpu_matches_kernel(Scene& scene, const RenderSettings& settings) {
  const KdTree tree = tree_for(scene);
  const KernelInputs inputs = read_kernel_inputs(scene, tree, settings, DeviceSelection{"cpu"});
  EXPECT_EQ(option_defines(inputs.options), compiled_defines())
      << "this test file's KD_FEATURE_* must be the kernel's: " << inputs.options;
  const Film film = render(scene, tree, settings, DeviceSelection{"cpu"});
  const std::vector<int64_t> cpu = cpu_film(inputs);
  EXPECT_EQ(cpu.size(), film.sums.size());
  const size_t channels = film.channels.size();
  size_t mismatches = 0, lit = 0;
  for (size_t i = 0; i < std::min(cpu.size(), film.sums.size()); ++i) {
    if (i % channels == 0 && (film.sums[i] || film.sums[i + 1] || film.sums[i + 2])) ++lit;
    if (cpu[i] == film.sums[i]) continue;
    if (++mismatches <= 5) {
      ADD_FAILURE() << "pixel " << i / channels << " channel " << film.channels[i % channels] << ": C++ " << cpu[i]
                    << ", kernel " << film.sums[i];
    }
  }
  EXPECT_EQ(mismatches, 0u) << "of " << cpu.size() << " film sums";
  return lit;
}

}  // namespace
}  // namespace kdray::test
