// The options that describe one rendered frame: defined once, used by the command line and by
// every line of a --jobs file, so a single command turns into a jobs line by dropping the tool
// and file names.
#pragma once

#include <kdray/environment.h>
#include <kdray/opencl_device.h>
#include <kdray/render.h>

#include <CLI/CLI.hpp>
#include <tool_main.h>

#include <map>
#include <memory>
#include <string>

namespace kdrender {

// A command line (or jobs line) that parses but asks for something inconsistent: exit 2.
using kdray::tool::UsageError;

// The options as written; resolve_frame() turns them into render settings.
struct FrameOptions {
  std::string output;
  std::string aovs;
  std::string sampler = kdray::sampler_name(kdray::Sampler::Sobol);
  std::string cam_pos, cam_target, cam_up;
  float fov = 0;
  std::string env_image, env_color;
  float env_strength = 1, env_rotate = 0;
  bool no_default_light = false, no_mis = false, wavefront = false;
  std::string traversal = "auto";
  kdray::RenderSettings settings;  // the plain numbers (size, spp, seed, ...) are written here directly
  kdray::DeviceSelection device;
};

// Adds every per-frame option to `app`, bound to `o`; options absent from a parse keep o's values.
void add_frame_options(CLI::App& app, FrameOptions& o);

struct Frame {
  std::string output;
  kdray::RenderSettings settings;
  kdray::DeviceSelection device;
  double environment_seconds = 0;  // loading the environment map (0 when it came from the cache)
};

// Environments by their options, so a batch loads each map once.
class EnvironmentCache {
 public:
  // The environment the options ask for (null for none); loading errors throw kdray::Error.
  std::shared_ptr<const kdray::Environment> get(const FrameOptions& o, double* load_seconds);

 private:
  std::map<std::string, std::shared_ptr<const kdray::Environment>> loaded_;
};

// Checks the options and builds the frame's settings; throws UsageError for inconsistent ones.
Frame resolve_frame(const FrameOptions& o, EnvironmentCache& environments);

}  // namespace kdrender
