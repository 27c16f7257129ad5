// Rendering one frame and writing its image: the same call for a single command and for each
// frame of a batch, so a batch frame is the single command's image.
#pragma once

#include "frame_options.h"

#include <kdray/kdtree.h>
#include <kdray/render.h>
#include <kdray/scene.h>

#include <nlohmann/json.hpp>

namespace kdrender {

struct FrameResult {
  kdray::Film film;
  kdray::RenderStats stats;
  double write_seconds = 0;
};

FrameResult render_frame(const kdray::Scene& scene, const kdray::KdTree& tree, const Frame& frame,
                         const kdray::RenderProgress& progress = {});

// The rays a frame traces at most on the host (--device host: pixels x samples x (bounces + 1),
// a side left to the camera counted at the default size), 0 on an OpenCL device.
uint64_t host_rays_of(const Frame& frame);

// The frame's statistics (--json): output, device, sizes, samples, timings, rates.
nlohmann::json frame_json(const Frame& frame, const FrameResult& result);

// A human summary of the frame, three or four lines.
void print_frame_summary(const Frame& frame, const FrameResult& result);

// Warns on stderr (once per process) when the frame lights a scene that has no light with the default light.
void warn_if_default_light(const kdray::Scene& scene, const std::string& scene_path, const Frame& frame);

// True when frame.output exists and is this frame's complete image: an EXR with the frame's
// size, layers, sample range, seed, bounces, sampler, scene, tree and settings; a PNG/JPEG of its size
// (written atomically, so a present file is never a partial write).
bool frame_already_written(const Frame& frame, const kdray::Scene& scene, uint64_t tree_hash);

}  // namespace kdrender
