#include "tree_placement.h"

#include <kdray/clock.h>
#include <kdray/render.h>
#include <kdray/traverse.h>

namespace kdrender {

uint64_t host_rays_of(const Frame& frame) {
  if (frame.device.device != kdray::kHostDevice) return 0;
  const kdray::RenderSettings& s = frame.settings;
  const uint64_t width = s.width ? s.width : kdray::RenderSettings::kDefaultSize;
  const uint64_t height = s.height ? s.height : kdray::RenderSettings::kDefaultSize;
  return width * height * s.spp * (uint64_t{s.max_bounces} + 1);
}

double place_tree_for_host(kdray::KdTree& tree, uint64_t host_rays, unsigned threads) {
  if (host_rays == 0) return -1;
  const auto start = kdray::Clock::now();
  return kdray::copy_tree_for_rays(tree, host_rays, threads) ? kdray::seconds_since(start) : -1;
}

void add_tree_memory(nlohmann::json& report, double copy_seconds) {
  report["tree_memory"] = copy_seconds >= 0 ? "copied" : "file mapping";
  if (copy_seconds >= 0) report["tree_copy_seconds"] = copy_seconds;
}

}  // namespace kdrender
