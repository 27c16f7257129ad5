// OpenCL devices through the ICD loader, and how a tool picks one (--device).
#pragma once

#include <kdray/traverse.h>

#include <cstddef>
#include <cstdint>
#include <optional>
#include <string>
#include <vector>

namespace kdray {

struct DeviceInfo {
  int index = 0;  // position in list_devices(), over all platforms
  std::string platform;
  std::string name;
  std::string driver_version;
  bool is_gpu = false;
  unsigned compute_units = 0;
  size_t max_work_group_size = 0;
};

// Every device of every platform. Throws kdray::Error when no OpenCL platform exists, saying how
// to install PoCL.
std::vector<DeviceInfo> list_devices();

// How to choose and drive a device; one struct so every tool and test passes the same thing.
struct DeviceSelection {
  // auto (a GPU if present, else the CPU) | cpu | gpu | INDEX; for a render also all | INDEX,INDEX,...
  // or host (the C++ build on the CPU, render.h)
  std::string device = "auto";
  unsigned threads = 0;         // host: worker threads; 0: all cores
  size_t local_size = 0;        // work-group size; 0: the device's default (64 on CPUs)
  unsigned short_stack_size = 0;  // KD_SHORT_STACK_SIZE for the traversal; 0: the kernel default
  // The traversal the programs compile; unset: the device's own (traversal_path_for, trace_opencl.h).
  std::optional<TraversalPath> traversal{};
  // kd_trace.cl on a CPU device: 24 rays per work-item in lanes where opencl_traces_in_lanes says
  // so (the same hits); false: one ray per work-item.
  bool lanes = true;
};

// The device `selection` names; throws kdray::Error if there is none.
DeviceInfo select_device(const DeviceSelection& selection);

// The devices a selection names, each as a one-device selection: every device for "all", each
// entry of a comma-separated list, else just `selection`. Throws kdray::Error for an unknown or
// repeated device.
std::vector<DeviceSelection> split_device_selection(const DeviceSelection& selection);

// Where compiled programs are cached: $KDRAY_CACHE_DIR, else $XDG_CACHE_HOME/kdray, else
// ~/.cache/kdray. KDRAY_CACHE_DIR=off disables the disk cache (an empty string is returned).
std::string program_cache_dir();

}  // namespace kdray
