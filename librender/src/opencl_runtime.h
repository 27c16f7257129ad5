// Internal to librender: an OpenCL context and queue per device (kept for the process lifetime,
// so tests and tools reuse built programs), RAII handles, and the program build with its caches.
#pragma once

#include <kdray/opencl_device.h>

#include <CL/cl.h>
#include <CL/cl_ext.h>

#include <map>
#include <memory>
#include <mutex>
#include <string>
#include <utility>

namespace kdray::cl {

// Throws std::runtime_error("OpenCL: <what> failed (<code name>)") when status is not CL_SUCCESS.
void check(cl_int status, const char* what);

template <typename Handle, cl_int (*Release)(Handle)>
class Ref {
 public:
  Ref() = default;
  explicit Ref(Handle handle) : handle_(handle) {}
  Ref(Ref&& other) noexcept : handle_(std::exchange(other.handle_, nullptr)) {}
  Ref& operator=(Ref&& other) noexcept {
    std::swap(handle_, other.handle_);
    return *this;
  }
  Ref(const Ref&) = delete;
  Ref& operator=(const Ref&) = delete;
  ~Ref() {
    if (handle_) Release(handle_);
  }
  Handle get() const { return handle_; }

 private:
  Handle handle_ = nullptr;
};
using Buffer = Ref<cl_mem, clReleaseMemObject>;
using Kernel = Ref<cl_kernel, clReleaseKernel>;
using Program = Ref<cl_program, clReleaseProgram>;

struct ProgramBuild {
  cl_program program = nullptr;  // owned by the Runtime
  double seconds = 0;            // time to obtain it now
  std::string source;            // "memory", "disk cache" or "compiled"
};

class Runtime {
 public:
  explicit Runtime(const DeviceInfo& info);
  ~Runtime();
  Runtime(const Runtime&) = delete;
  Runtime& operator=(const Runtime&) = delete;

  const DeviceInfo& info() const { return info_; }
  // Options every program gets: device_build_options of its CL_DEVICE_SINGLE_FP_CONFIG.
  const std::string& common_options() const { return common_options_; }
  cl_context context() const { return context_; }
  cl_command_queue queue() const { return queue_; }
  cl_device_id device() const { return device_; }

  // kernels/<entry_file> with its includes expanded, built with `options` and the device's
  // common_options(): from this process's programs, else the disk cache, else compiled (and
  // stored). A failed build throws with the log.
  ProgramBuild program(const std::string& entry_file, const std::string& options);

  // A device buffer; copies `bytes` from `data` when it is non-null. Zero sizes get 16 bytes so
  // an absent optional array still binds.
  Buffer buffer(size_t bytes, const void* data, cl_mem_flags flags = CL_MEM_READ_ONLY);

  // Work-group size to launch with, and the persistent-thread global size: enough groups to
  // fill every compute unit (more on GPUs, to hide latency).
  size_t local_size(const DeviceSelection& selection) const;
  size_t persistent_global_size(size_t local_size) const;

 private:
  DeviceInfo info_;
  cl_device_id device_ = nullptr;
  cl_context context_ = nullptr;
  cl_command_queue queue_ = nullptr;
  std::string common_options_;
  std::mutex mutex_;
  std::map<std::string, Program> programs_;  // by cache key
};

// The process-wide runtime of the selected device (created on first use).
Runtime& runtime_for(const DeviceSelection& selection);

Kernel create_kernel(cl_program program, const char* name);

// Sets kernel arguments in order: cl_mem handles, or any trivially copyable value.
template <typename T>
void set_arg(cl_kernel kernel, cl_uint index, const T& value) {
  check(clSetKernelArg(kernel, index, sizeof(T), &value), "clSetKernelArg");
}
inline void set_arg(cl_kernel kernel, cl_uint index, const Buffer& buffer) {
  cl_mem mem = buffer.get();
  check(clSetKernelArg(kernel, index, sizeof(cl_mem), &mem), "clSetKernelArg");
}

void run_kernel(cl_command_queue queue, cl_kernel kernel, size_t global_size, size_t local_size);
void zero_buffer(cl_command_queue queue, const Buffer& buffer, size_t bytes);
void read_buffer(cl_command_queue queue, const Buffer& buffer, size_t bytes, void* out);

// The text of kernels/<entry_file> with every #include "..." of another embedded file inlined
// once (the headers carry include guards), with #line markers so compiler logs name real files.
std::string expand_kernel_source(const std::string& entry_file);

}  // namespace kdray::cl
