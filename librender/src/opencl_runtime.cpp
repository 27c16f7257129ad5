// OpenCL devices, contexts and launches (see opencl_runtime.h).
#include "opencl_runtime.h"

#include <kdray/device_build_options.h>
#include <kdray/error.h>
#include <kdray/huge_pages.h>

#include <algorithm>
#include <cstdlib>
#include <cstring>
#include <stdexcept>
#include <vector>

namespace kdray {
namespace {

const char* const kNoPlatformHelp =
    "no OpenCL platform found: install an OpenCL driver, e.g. PoCL for the CPU "
    "(apt-get install pocl-opencl-icd), and check with `clinfo -l`";

// A string property from clGetDeviceInfo or clGetPlatformInfo (`get`, named `call` in errors).
template <typename Handle, typename Info>
std::string info_string(cl_int(CL_API_CALL* get)(Handle, Info, size_t, void*, size_t*), const char* call,
                        Handle handle, Info what) {
  size_t size = 0;
  cl::check(get(handle, what, 0, nullptr, &size), call);
  std::string text(size, '\0');
  cl::check(get(handle, what, size, text.data(), nullptr), call);
  while (!text.empty() && text.back() == '\0') text.pop_back();
  return text;
}

std::string device_string(cl_device_id device, cl_device_info what) {
  return info_string(clGetDeviceInfo, "clGetDeviceInfo", device, what);
}

std::string platform_string(cl_platform_id platform, cl_platform_info what) {
  return info_string(clGetPlatformInfo, "clGetPlatformInfo", platform, what);
}

// All devices in list order, with their ids (kept internal: DeviceInfo is host-only data).
std::vector<std::pair<DeviceInfo, cl_device_id>> enumerate_devices() {
  cl_uint platform_count = 0;
  cl_int status = clGetPlatformIDs(0, nullptr, &platform_count);
  if (status == CL_PLATFORM_NOT_FOUND_KHR || platform_count == 0) throw Error("", kNoPlatformHelp);
  cl::check(status, "clGetPlatformIDs");
  std::vector<cl_platform_id> platforms(platform_count);
  cl::check(clGetPlatformIDs(platform_count, platforms.data(), nullptr), "clGetPlatformIDs");
  std::vector<std::pair<DeviceInfo, cl_device_id>> devices;
  for (cl_platform_id platform : platforms) {
    cl_uint count = 0;
    if (clGetDeviceIDs(platform, CL_DEVICE_TYPE_ALL, 0, nullptr, &count) != CL_SUCCESS || count == 0) continue;
    std::vector<cl_device_id> ids(count);
    cl::check(clGetDeviceIDs(platform, CL_DEVICE_TYPE_ALL, count, ids.data(), nullptr), "clGetDeviceIDs");
    for (cl_device_id id : ids) {
      DeviceInfo info;
      info.index = static_cast<int>(devices.size());
      info.platform = platform_string(platform, CL_PLATFORM_NAME);
      info.name = device_string(id, CL_DEVICE_NAME);
      info.driver_version = device_string(id, CL_DRIVER_VERSION);
      cl_device_type type = 0;
      cl::check(clGetDeviceInfo(id, CL_DEVICE_TYPE, sizeof type, &type, nullptr), "clGetDeviceInfo");
      info.is_gpu = (type & CL_DEVICE_TYPE_GPU) != 0;
      cl_uint units = 0;
      cl::check(clGetDeviceInfo(id, CL_DEVICE_MAX_COMPUTE_UNITS, sizeof units, &units, nullptr), "clGetDeviceInfo");
      info.compute_units = units;
      cl::check(clGetDeviceInfo(id, CL_DEVICE_MAX_WORK_GROUP_SIZE, sizeof info.max_work_group_size,
                                &info.max_work_group_size, nullptr),
                "clGetDeviceInfo");
      devices.emplace_back(info, id);
    }
  }
  if (devices.empty()) throw Error("", kNoPlatformHelp);
  return devices;
}

std::pair<DeviceInfo, cl_device_id> resolve(const DeviceSelection& selection) {
  auto devices = enumerate_devices();
  const std::string& choice = selection.device;
  auto first_of = [&](bool gpu) {
    return std::find_if(devices.begin(), devices.end(), [&](const auto& d) { return d.first.is_gpu == gpu; });
  };
  if (choice == "auto") {
    auto gpu = first_of(true);
    return gpu != devices.end() ? *gpu : devices.front();
  }
  if (choice == "gpu" || choice == "cpu") {
    auto found = first_of(choice == "gpu");
    if (found == devices.end()) throw Error("", "OpenCL device \"" + choice + "\": there is none of that type");
    return *found;
  }
  char* end = nullptr;
  long index = std::strtol(choice.c_str(), &end, 10);
  if (choice.empty() || *end != '\0' || index < 0 || index >= static_cast<long>(devices.size())) {
    throw Error("", "OpenCL device \"" + choice + "\": expected auto, cpu, gpu or an index below " +
                        std::to_string(devices.size()));
  }
  return devices[static_cast<size_t>(index)];
}

}  // namespace

std::vector<DeviceInfo> list_devices() {
  std::vector<DeviceInfo> infos;
  for (auto& device : enumerate_devices()) infos.push_back(device.first);
  return infos;
}

DeviceInfo select_device(const DeviceSelection& selection) { return resolve(selection).first; }

std::vector<DeviceSelection> split_device_selection(const DeviceSelection& selection) {
  std::vector<std::string> names;
  if (selection.device == "all") {
    for (const DeviceInfo& info : list_devices()) names.push_back(std::to_string(info.index));
  } else if (selection.device.find(',') == std::string::npos) {
    return {selection};
  } else {
    size_t start = 0;
    for (size_t comma; (comma = selection.device.find(',', start)) != std::string::npos; start = comma + 1) {
      names.push_back(selection.device.substr(start, comma - start));
    }
    names.push_back(selection.device.substr(start));
  }
  std::vector<DeviceSelection> selections;
  std::vector<int> indices;
  for (const std::string& name : names) {
    DeviceSelection one = selection;
    one.device = name;
    const int index = select_device(one).index;
    if (std::find(indices.begin(), indices.end(), index) != indices.end()) {
      throw Error("", "OpenCL devices \"" + selection.device + "\": device " + std::to_string(index) + " is named twice");
    }
    indices.push_back(index);
    selections.push_back(one);
  }
  return selections;
}

namespace cl {

void check(cl_int status, const char* what) {
  if (status != CL_SUCCESS) {
    throw std::runtime_error(std::string("OpenCL: ") + what + " failed (error " + std::to_string(status) + ")");
  }
}

Runtime::Runtime(const DeviceInfo& info) : info_(info) {
  for (auto& device : enumerate_devices()) {
    if (device.first.index == info.index) device_ = device.second;
  }
  cl_int status = CL_SUCCESS;
  context_ = clCreateContext(nullptr, 1, &device_, nullptr, nullptr, &status);
  check(status, "clCreateContext");
  queue_ = clCreateCommandQueue(context_, device_, 0, &status);
  check(status, "clCreateCommandQueue");
  cl_device_fp_config fp_config = 0;
  check(clGetDeviceInfo(device_, CL_DEVICE_SINGLE_FP_CONFIG, sizeof fp_config, &fp_config, nullptr), "clGetDeviceInfo");
  common_options_ = device_build_options(fp_config);
}

Runtime::~Runtime() {
  programs_.clear();
  if (queue_) clReleaseCommandQueue(queue_);
  if (context_) clReleaseContext(context_);
}

Buffer Runtime::buffer(size_t bytes, const void* data, cl_mem_flags flags) {
  constexpr size_t kMinimumBytes = 16;
  cl_int status = CL_SUCCESS;
  cl_mem mem = clCreateBuffer(context_, flags, std::max(bytes, kMinimumBytes), nullptr, &status);
  check(status, "clCreateBuffer");
  Buffer buffer(mem);
  if (data && bytes > 0) {
    // Filled through a mapping: on a CPU device that is the buffer's own memory, advised huge
    // pages before its first write (the kernels read the tree's arrays at random, and with 4
    // KiB pages nearly every such read of a large array also misses the TLB).
    void* mapped = clEnqueueMapBuffer(queue_, mem, CL_TRUE, CL_MAP_WRITE_INVALIDATE_REGION, 0, bytes, 0, nullptr,
                                      nullptr, &status);
    check(status, "clEnqueueMapBuffer");
    advise_huge_pages(mapped, bytes);
    std::memcpy(mapped, data, bytes);
    check(clEnqueueUnmapMemObject(queue_, mem, mapped, 0, nullptr, nullptr), "clEnqueueUnmapMemObject");
    check(clFinish(queue_), "clFinish");
  }
  return buffer;
}

size_t Runtime::local_size(const DeviceSelection& selection) const {
  size_t wanted = selection.local_size ? selection.local_size : 64;
  if (wanted > info_.max_work_group_size) {
    throw Error("", "work-group size " + std::to_string(wanted) + " exceeds the device's limit of " +
                        std::to_string(info_.max_work_group_size));
  }
  return wanted;
}

size_t Runtime::persistent_global_size(size_t local_size) const {
  size_t groups_per_unit = info_.is_gpu ? 16 : 1;
  return local_size * groups_per_unit * std::max(1u, info_.compute_units);
}

Runtime& runtime_for(const DeviceSelection& selection) {
  static std::mutex mutex;
  static std::map<int, std::unique_ptr<Runtime>> runtimes;
  DeviceInfo info = select_device(selection);
  std::lock_guard<std::mutex> lock(mutex);
  auto& slot = runtimes[info.index];
  if (!slot) slot = std::make_unique<Runtime>(info);
  return *slot;
}

Kernel create_kernel(cl_program program, const char* name) {
  cl_int status = CL_SUCCESS;
  cl_kernel kernel = clCreateKernel(program, name, &status);
  check(status, "clCreateKernel");
  return Kernel(kernel);
}

void run_kernel(cl_command_queue queue, cl_kernel kernel, size_t global_size, size_t local_size) {
  size_t global = (global_size + local_size - 1) / local_size * local_size;
  check(clEnqueueNDRangeKernel(queue, kernel, 1, nullptr, &global, &local_size, 0, nullptr, nullptr),
        "clEnqueueNDRangeKernel");
}

void zero_buffer(cl_command_queue queue, const Buffer& buffer, size_t bytes) {
  const cl_uint zero = 0;
  check(clEnqueueFillBuffer(queue, buffer.get(), &zero, sizeof zero, 0, bytes, 0, nullptr, nullptr),
        "clEnqueueFillBuffer");
}

void read_buffer(cl_command_queue queue, const Buffer& buffer, size_t bytes, void* out) {
  check(clEnqueueReadBuffer(queue, buffer.get(), CL_TRUE, 0, bytes, out, 0, nullptr, nullptr), "clEnqueueReadBuffer");
}

}  // namespace cl
}  // namespace kdray
