// --device: one vocabulary in every tool that runs on a device.
//   host       kdray's own C++ code on the CPU, threads from --threads (kdtrace: libkdtree's
//              traversal; kdrender: the C++ build of the path tracer, the OpenCL kernel's bits)
//   auto       an OpenCL GPU if there is one, else the CPU: for kdrender its faster path
//              (kdray::device_for_render: host on an x86-64-v3 CPU), for kdtrace the OpenCL CPU
//              device
//   cpu, gpu   the first OpenCL device of that type (cpu is PoCL)
//   INDEX      an OpenCL device by its number in `--device list`
//   all        every OpenCL device at once
//   I,J,...    those OpenCL devices at once (kdrender)
//   list       print the OpenCL devices and exit
// Tools that link librender include this header (list_opencl_devices needs it).
#pragma once

#include <kdray/opencl_device.h>
#include <kdray/render.h>

#include "tool_main.h"

#include <CLI/CLI.hpp>

#include <cstdio>
#include <string>

namespace kdray::tool {

enum class DeviceKind { Host, OpenCl, All, List };

inline DeviceKind device_kind(const std::string& choice) {
  if (choice == "host") return DeviceKind::Host;
  if (choice == "all" || choice.find(',') != std::string::npos) return DeviceKind::All;
  if (choice == "list") return DeviceKind::List;
  return DeviceKind::OpenCl;
}

// Adds --device to `app`.
inline CLI::Option* add_device_option(CLI::App& app, std::string& choice) {
  const std::string help =
      "host (kdray's C++ code on the CPU, with --threads), or an OpenCL device: auto (a GPU if present, else the "
      "CPU), cpu (PoCL), gpu, an index of --device list, or all (or I,J,...: several at once); list prints the "
      "OpenCL devices";
  CLI::Validator names(
      [](std::string& text) -> std::string {
        if (text == "host" || text == "auto" || text == "cpu" || text == "gpu" || text == "all" || text == "list") return {};
        if (!text.empty() && text.size() < 64 && text.find_first_not_of("0123456789,") == std::string::npos) return {};
        return "'" + text + "' is not host, auto, cpu, gpu, all, list, a device index or a comma-separated list of them";
      },
      "DEVICE");
  return app.add_option("--device", choice, help)->check(names)->capture_default_str()->group("Device");
}

// Adds --threads, the worker threads of --device host.
inline CLI::Option* add_threads_option(CLI::App& app, unsigned& threads) {
  return app.add_option("--threads", threads, "Threads of --device host; 0: all cores")
      ->capture_default_str()
      ->group("Device");
}

// --threads counts the host's threads: with an OpenCL device it would be ignored, so it is refused.
inline void check_threads_option(const std::string& device, unsigned threads) {
  if (threads != 0 && device_kind(device) != DeviceKind::Host) {
    throw UsageError("--threads " + std::to_string(threads) + " is for --device host; OpenCL devices run their own");
  }
}

// `--device list`: every OpenCL device, the one `auto` picks marked; `auto_device` is what auto
// names in the tool (kdrender: kdray::device_for_render, the host where it is the faster CPU path,
// then listed after the OpenCL devices and marked instead).
inline int list_opencl_devices(bool json, const std::string& auto_device = "auto") {
  const std::vector<DeviceInfo> devices = list_devices();
  const bool host = auto_device == kHostDevice;
  const int chosen = host ? -1 : select_device({}).index;
  nlohmann::json list = nlohmann::json::array();
  for (const DeviceInfo& d : devices) {
    list.push_back({{"index", d.index}, {"platform", d.platform}, {"name", d.name}, {"driver", d.driver_version},
                    {"gpu", d.is_gpu}, {"compute_units", d.compute_units}, {"default", d.index == chosen}});
    if (!json) {
      std::printf("%d: %s / %s (%s, %u compute units, driver %s)%s\n", d.index, d.platform.c_str(), d.name.c_str(),
                  d.is_gpu ? "GPU" : "CPU", d.compute_units, d.driver_version.c_str(),
                  d.index == chosen ? "  [default]" : "");
    }
  }
  if (!json && host) std::printf("host: kdray's C++ build on this CPU  [default]\n");
  if (json) print_json({{"devices", list}, {"default", host ? nlohmann::json(kHostDevice) : nlohmann::json(chosen)}});
  return kExitOk;
}

}  // namespace kdray::tool
