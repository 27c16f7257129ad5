// kdtrace's command line: the options as written, bound to CLI11 in one place, and the checks
// that turn them into where and how the rays are traced (inconsistent ones: exit 2).
#pragma once

#include <kdray/opencl_device.h>
#include <kdray/traverse.h>

#include "device_option.h"
#include "tool_main.h"

#include <CLI/CLI.hpp>

#include <cstddef>
#include <cstdint>
#include <string>

namespace kdtrace {

struct Options {
  std::string scene_path, tree_path, cache_folder;
  std::string rays_path, generate, write_rays_path, hits_path;
  size_t count = 1000000;
  uint32_t width = 1024, height = 768;
  uint64_t seed = 1;
  std::string stack_name = "short", path_name = "auto";
  bool no_lanes = false, packets = false;
  kdray::TraceOptions traversal;  // --threads is written here; stack and path come from their names
  kdray::DeviceSelection opencl_device;
  kdray::tool::OutputFlags flags;
};

// Adds every option but the shared contract (kdray::tool::add_contract) to `app`, bound to `o`.
void add_options(CLI::App& app, Options& o);

// The device the options name, after the checks that need no file: List is returned before
// any other check, since listing devices needs no scene; throws UsageError otherwise.
kdray::tool::DeviceKind checked_device(const Options& o);

// The traversal the names ask for; throws UsageError for a combination the host cannot run. The
// host's auto is the fast path, as on any CPU.
kdray::TraceOptions traversal_options(const Options& o, bool host);

// The OpenCL device with the traversal --traversal names (auto: left to the device).
kdray::DeviceSelection opencl_selection(const Options& o);

}  // namespace kdtrace
