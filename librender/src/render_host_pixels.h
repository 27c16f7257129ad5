// The host renderer's inner loop, the path tracer of kernels/pt_path.h compiled as C++ for a run
// of pixels, in two builds: for any CPU of the target (generic), and for x86-64-v3 (AVX2, BMI2,
// FMA), which the host renderer takes where the CPU has it. The second build has no contraction
// into FMA either, so both give the kernels' bits; they differ in instructions only (rint and
// selects in one instruction each, three-operand forms).
#pragma once

#include "scene_arrays.h"

#include <kernels/pt_types.h>

#include <cstddef>
#include <cstdint>

namespace kdray {

// Renders pixels [begin, end) of the pass `params` names into `film`; returns the rays traced
// and adds the non-finite values met to *nonfinite.
using RenderHostPixels = uint64_t (*)(const SceneArrays& arrays, const PtRenderParams& params, uint32_t begin,
                                      uint32_t end, int64_t* film, uint32_t* nonfinite);

struct HostPixelsBuild {
  RenderHostPixels render;
  const char* name;  // "generic", "x86-64-v3", or "x86-64-v3, paths in lanes"
  bool bounce_bits_in_lanes;  // PT_BOUNCE_BITS_IN_LANES (kernels/pt_rng.h): the AVX2 build's
};

// The build for this CPU and a scene whose longest gathered array has `gathered_floats` floats
// (paths_in_lanes_apply's): x86-64-v3 where the CPU has it, with 8 paths at a time in lanes where
// they apply (path_lanes.h), unless the environment asks for another to compare them:
// KDRAY_HOST_ISA=generic for the generic build, KDRAY_HOST_LANES=off for the x86-64-v3 build one
// path at a time. Throws kdray::Error for any other value of those variables.
HostPixelsBuild host_pixels_build(size_t gathered_floats);

namespace host_pixels_generic {
uint64_t render_pixels(const SceneArrays& arrays, const PtRenderParams& params, uint32_t begin, uint32_t end,
                       int64_t* film, uint32_t* nonfinite);
}
#ifdef KDRAY_HOST_PIXELS_HAVE_X86_64_V3
namespace host_pixels_x86_64_v3 {
uint64_t render_pixels(const SceneArrays& arrays, const PtRenderParams& params, uint32_t begin, uint32_t end,
                       int64_t* film, uint32_t* nonfinite);
// The same film, 8 paths at a time (path_lanes.h), for passes where paths_in_lanes_apply holds.
bool paths_in_lanes_apply(size_t gathered_floats);
uint64_t render_pixels_in_lanes(const SceneArrays& arrays, const PtRenderParams& params, uint32_t begin, uint32_t end,
                                int64_t* film, uint32_t* nonfinite);
}
#endif

}  // namespace kdray
