// kdrender --jobs: many frames of one scene in one process. The scene and tree are loaded once
// and each kernel is built once (the runtime keeps built programs, so only a line that changes
// the kernel's features or device builds another).
#pragma once

#include "frame_options.h"

#include <kdray/kdtree.h>
#include <kdray/scene.h>

#include <string>

namespace kdrender {

struct BatchOptions {
  std::string scene_path;  // for messages
  std::string jobs_path;
  bool resume = false;  // skip frames whose output is already present and complete
  bool json = false, quiet = false;
};

// Renders every frame of the jobs file with `defaults` as the options of every line. Lines are
// checked before anything renders (UsageError names FILE:LINE); a frame that fails is reported
// and the batch goes on. Returns the exit code: 0 when every frame was rendered or skipped, 1
// when any failed (they are listed). The host's frames trace the tree copied out of its file
// when the rays of the first that renders and of those after it repay the copy.
int run_batch(const kdray::Scene& scene, kdray::KdTree& tree, const FrameOptions& defaults,
              const BatchOptions& batch, double load_seconds);

}  // namespace kdrender
